"""
``MassProperties``: the one value type for mass, centre of mass and inertia tensor.

Conventions (DESIGN.md): SI units; ``inertia`` is the 3×3 tensor about the centre of mass,
expressed in the axes of the frame the value lives in; products of inertia use the tensor
convention of URDF and SDFormat, ``ixy = -∫ x y dm``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.frames import as_transform, as_vector3, rpy_matrix, transform

# the default relative tolerance of the triangle inequality in ``MassProperties.validity``:
# loose enough for the rounding of a value written with 9 significant digits
TRIANGLE_RTOL = 1e-9


def shift_tensor(mass: float, offset: ArrayLike) -> NDArray[np.float64]:
    """
    Parallel-axis term: what a point mass adds to an inertia tensor about a point ``offset`` away.

    Parameters
    ----------
    mass : float
      kg
    offset : (3,) float
      Vector from the reference point to the centre of mass, m.

    Returns
    -------
    term : (3, 3) float
      ``mass * (|d|² E - d dᵀ)``, kg·m²
    """
    d = np.asarray(offset, dtype=np.float64)
    return mass * (np.dot(d, d) * np.eye(3) - np.outer(d, d))


def inertia_from_second_moment(second_moment: ArrayLike) -> NDArray[np.float64]:
    """
    Inertia tensor of a body from its central second moment ``C = ∫ r rᵀ dm`` (about the COM).

    ``I = tr(C) E - C``; the inverse is :func:`second_moment_from_inertia`.
    """
    c = np.asarray(second_moment, dtype=np.float64)
    return np.trace(c) * np.eye(3) - c


def second_moment_from_inertia(inertia: ArrayLike) -> NDArray[np.float64]:
    """Central second moment ``C = ∫ r rᵀ dm`` of an inertia tensor: ``C = tr(I)/2 E - I``."""
    i = np.asarray(inertia, dtype=np.float64)
    return 0.5 * np.trace(i) * np.eye(3) - i


@dataclass(frozen=True)
class Problem:
    """One reason a ``MassProperties`` value is not physically possible."""

    # non-finite | non-positive-mass | asymmetric | not-positive-definite | triangle-inequality
    kind: str
    message: str


@dataclass(frozen=True)
class Validity:
    """Whether mass properties are physically possible, and if not, every reason why."""

    problems: tuple[Problem, ...] = ()

    @property
    def ok(self) -> bool:
        return not self.problems

    def __bool__(self) -> bool:
        return self.ok

    def kinds(self) -> set[str]:
        return {p.kind for p in self.problems}

    def __str__(self) -> str:
        return "valid" if self.ok else "; ".join(p.message for p in self.problems)


def _readonly(array: NDArray) -> NDArray:
    array.flags.writeable = False
    return array


@dataclass(frozen=True, eq=False)
class MassProperties:
    """
    Mass, centre of mass and inertia tensor of a rigid body, in SI units.

    Attributes
    ----------
    mass : float
      kg
    com : (3,) float
      Centre of mass in the frame's coordinates, m.
    inertia : (3, 3) float
      Inertia tensor about the centre of mass, in the frame's axes, kg·m².

    Values are immutable; every operation returns a new value. Construction checks shapes,
    not physics: a declared tensor may be impossible, and :meth:`validity` says why.
    """

    mass: float
    com: NDArray[np.float64] = field(default_factory=lambda: np.zeros(3))
    inertia: NDArray[np.float64] = field(default_factory=lambda: np.zeros((3, 3)))

    def __post_init__(self) -> None:
        object.__setattr__(self, "mass", float(self.mass))
        object.__setattr__(self, "com", _readonly(as_vector3(self.com, "com").copy()))
        inertia = np.array(self.inertia, dtype=np.float64)
        if inertia.shape != (3, 3):
            raise ValueError(f"inertia must be (3, 3), got shape {inertia.shape}")
        object.__setattr__(self, "inertia", _readonly(inertia))

    # --- construction -------------------------------------------------------------------

    @classmethod
    def from_urdf(
        cls,
        mass: float,
        ixx: float,
        ixy: float,
        ixz: float,
        iyy: float,
        iyz: float,
        izz: float,
        xyz: ArrayLike = (0.0, 0.0, 0.0),
        rpy: ArrayLike = (0.0, 0.0, 0.0),
    ) -> MassProperties:
        """
        Mass properties of a URDF ``<inertial>`` block, in the link frame.

        ``xyz`` is the centre of mass; ``rpy`` rotates the axes the six values are written in,
        so the tensor in link axes is ``R I Rᵀ``.
        """
        tensor = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]], dtype=np.float64)
        rotation = rpy_matrix(rpy)
        return cls(mass, as_vector3(xyz, "xyz"), rotation @ tensor @ rotation.T)

    # --- combination --------------------------------------------------------------------

    def __add__(self, other: MassProperties) -> MassProperties:
        """The rigid union of two bodies (both in the same frame), by the parallel-axis theorem."""
        if not isinstance(other, MassProperties):
            return NotImplemented
        mass = self.mass + other.mass
        if not mass > 0:
            raise ValueError(f"combined mass must be positive, got {mass} kg")
        com = (self.mass * self.com + other.mass * other.com) / mass
        inertia = (
            self.inertia
            + shift_tensor(self.mass, self.com - com)
            + other.inertia
            + shift_tensor(other.mass, other.com - com)
        )
        return MassProperties(mass, com, inertia)

    def __radd__(self, other: object) -> MassProperties:
        # lets sum() start from its default 0
        if isinstance(other, int) and other == 0:
            return self
        return NotImplemented

    def __sub__(self, other: MassProperties) -> MassProperties:
        """Remove a part of this body (a hole, an overlap counted twice): the inverse of ``+``."""
        if not isinstance(other, MassProperties):
            return NotImplemented
        mass = self.mass - other.mass
        if not mass > 0:
            raise ValueError(
                f"cannot remove {fmt(other.mass)} kg from a body of {fmt(self.mass)} kg"
            )
        com = (self.mass * self.com - other.mass * other.com) / mass
        inertia = (
            self.inertia
            + shift_tensor(self.mass, self.com - com)
            - other.inertia
            - shift_tensor(other.mass, other.com - com)
        )
        return MassProperties(mass, com, inertia)

    # --- frames -------------------------------------------------------------------------

    def transformed(self, matrix: ArrayLike) -> MassProperties:
        """
        The same body expressed in a parent frame.

        Parameters
        ----------
        matrix : (4, 4) float
          Rigid transform mapping this value's frame to the parent frame (a URDF ``<origin>``).
        """
        m = as_transform(matrix)
        rotation = m[:3, :3]
        return MassProperties(
            self.mass, rotation @ self.com + m[:3, 3], rotation @ self.inertia @ rotation.T
        )

    def placed(
        self, xyz: ArrayLike = (0.0, 0.0, 0.0), rpy: ArrayLike = (0.0, 0.0, 0.0)
    ) -> MassProperties:
        """:meth:`transformed` by a URDF ``<origin xyz rpy>``."""
        return self.transformed(transform(xyz, rpy))

    def inertia_about(
        self, point: ArrayLike = (0.0, 0.0, 0.0), axes: ArrayLike | None = None
    ) -> NDArray[np.float64]:
        """
        Inertia tensor about any point, optionally in other axes: what CAD tools report
        "at the output coordinate system".

        Parameters
        ----------
        point : (3,) float
          The reference point in this frame's coordinates, m.
        axes : (3, 3) float, optional
          Rotation whose columns are the output axes expressed in this frame; default: this
          frame's own axes.

        Returns
        -------
        inertia : (3, 3) float
          kg·m²
        """
        about_point = self.inertia + shift_tensor(self.mass, self.com - as_vector3(point, "point"))
        if axes is None:
            return about_point
        rotation = as_transform(_rotation_as_transform(axes))[:3, :3]
        return rotation.T @ about_point @ rotation

    def inertia_at(self, frame: ArrayLike) -> NDArray[np.float64]:
        """
        Inertia tensor about the origin and in the axes of ``frame``.

        Parameters
        ----------
        frame : (4, 4) float
          Pose of the output coordinate system in this frame.
        """
        m = as_transform(frame)
        return self.inertia_about(m[:3, 3], m[:3, :3])

    # --- derived quantities -------------------------------------------------------------

    def cleaned(self, rtol: float = 1e-12) -> MassProperties:
        """
        The same value with rounding noise of a zero set to zero: tensor entries below ``rtol``
        of the largest moment, COM coordinates below ``rtol`` of the body's size (its largest
        radius of gyration) or of its distance from the origin. For display and writing.
        """
        tensor = self.inertia.copy()
        tensor[np.abs(tensor) <= rtol * np.abs(np.diag(tensor)).max()] = 0.0
        size = np.sqrt(np.abs(np.diag(self.inertia)).max() / self.mass) if self.mass > 0 else 0.0
        com = self.com.copy()
        com[np.abs(com) <= rtol * max(size, np.abs(com).max())] = 0.0
        return MassProperties(self.mass, com, tensor)

    def with_mass(self, mass: float) -> MassProperties:
        """The same shape of distribution rescaled to ``mass`` kg (a measured mass wins)."""
        if not self.mass > 0:
            raise ValueError(f"cannot rescale a body of mass {self.mass} kg")
        return MassProperties(mass, self.com, self.inertia * (mass / self.mass))

    @property
    def principal_moments(self) -> NDArray[np.float64]:
        """(3,) principal moments of inertia about the COM, ascending, kg·m²."""
        return np.linalg.eigvalsh(self._symmetric())

    @property
    def principal_axes(self) -> NDArray[np.float64]:
        """(3, 3) right-handed rotation whose columns are the principal axes, in moment order."""
        # eigh: symmetric input, best precision, ascending eigenvalues
        _, axes = np.linalg.eigh(self._symmetric())
        if np.linalg.det(axes) < 0:
            axes[:, 2] = -axes[:, 2]
        return axes

    @property
    def radii_of_gyration(self) -> NDArray[np.float64]:
        """(3,) ``sqrt(moment / mass)`` for the principal moments, m."""
        return np.sqrt(self.principal_moments / self.mass)

    @property
    def second_moment(self) -> NDArray[np.float64]:
        """(3, 3) central second moment ``∫ r rᵀ dm`` about the COM, kg·m²."""
        return second_moment_from_inertia(self.inertia)

    def _symmetric(self) -> NDArray[np.float64]:
        return 0.5 * (self.inertia + self.inertia.T)

    # --- validity -----------------------------------------------------------------------

    def validity(self, rtol: float = TRIANGLE_RTOL) -> Validity:
        """
        Whether these values describe a physically possible rigid body, and if not, why.

        Checks: every value finite; mass > 0; the tensor symmetric; positive definite; the
        principal moments satisfy the triangle inequality ``A + B ≥ C`` within ``rtol·C``.
        """
        problems: list[Problem] = []
        if not (
            np.isfinite(self.mass)
            and np.isfinite(self.com).all()
            and np.isfinite(self.inertia).all()
        ):
            bad = [
                name
                for name, value in (
                    ("mass", self.mass),
                    ("com", self.com),
                    ("inertia", self.inertia),
                )
                if not np.isfinite(value).all()
            ]
            problems.append(Problem("non-finite", f"{', '.join(bad)} not finite"))
            return Validity(tuple(problems))
        if not self.mass > 0:
            problems.append(
                Problem("non-positive-mass", f"mass {fmt(self.mass)} kg is not positive")
            )
        scale = max(np.abs(self.inertia).max(), np.finfo(float).tiny)
        asymmetry = np.abs(self.inertia - self.inertia.T).max()
        if asymmetry > 1e-9 * scale:
            problems.append(
                Problem(
                    "asymmetric",
                    f"inertia tensor is not symmetric (max |Iij - Iji| = {fmt(asymmetry)} kg·m²)",
                )
            )
        a, b, c = self.principal_moments
        if a <= 0:
            problems.append(
                Problem(
                    "not-positive-definite",
                    f"principal moments ({fmt(a)}, {fmt(b)}, {fmt(c)}) kg·m² are not all positive",
                )
            )
        elif a + b < c * (1.0 - rtol):
            problems.append(
                Problem(
                    "triangle-inequality",
                    f"principal moments ({fmt(a)}, {fmt(b)}, {fmt(c)}) kg·m² break A + B ≥ C: "
                    f"{fmt(a)} + {fmt(b)} = {fmt(a + b)} < {fmt(c)}",
                )
            )
        return Validity(tuple(problems))

    # --- comparison ---------------------------------------------------------------------

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, MassProperties):
            return NotImplemented
        return (
            self.mass == other.mass
            and np.array_equal(self.com, other.com)
            and np.array_equal(self.inertia, other.inertia)
        )

    __hash__ = None  # type: ignore[assignment]  # holds arrays; equal values must not collide

    def isclose(self, other: MassProperties, rtol: float = 1e-9, atol: float = 0.0) -> bool:
        """Equal within ``rtol`` of each quantity's scale (mass, body size, tensor norm)."""
        length = max(np.sqrt(np.abs(self.principal_moments).max() / abs(self.mass)), 1e-300)
        tensor = max(np.abs(self.inertia).max(), 1e-300)
        return bool(
            np.isclose(self.mass, other.mass, rtol=rtol, atol=atol)
            and np.allclose(self.com, other.com, rtol=0, atol=atol + rtol * length)
            and np.allclose(self.inertia, other.inertia, rtol=0, atol=atol + rtol * tensor)
        )

    def __repr__(self) -> str:
        com = ", ".join(fmt(x) for x in self.com)
        moments = ", ".join(fmt(x) for x in np.diag(self.inertia))
        return f"MassProperties(mass={fmt(self.mass)} kg, com=({com}) m, diag=({moments}) kg·m²)"


def _rotation_as_transform(axes: ArrayLike) -> NDArray[np.float64]:
    rotation = np.asarray(axes, dtype=np.float64)
    if rotation.shape != (3, 3):
        raise ValueError(f"axes must be (3, 3), got shape {rotation.shape}")
    matrix = np.eye(4)
    matrix[:3, :3] = rotation
    return matrix
