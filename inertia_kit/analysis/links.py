"""
Per-link analysis shared by report, lint and fill: the declared mass properties, as the
simulators will read them, and the ones the link's geometry implies.

Geometry-derived values (DESIGN.md): the link's ``<collision>`` shapes, else its ``<visual>``
ones, each placed by its origin, meshes scaled as URDF says, at uniform density, overlaps of
primitives counted once (solid union). Everything here is computed on first use and kept, so
rules that do not need meshes never read them.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from inertia_kit.description import model
from inertia_kit.physics.mass import MassProperties

if TYPE_CHECKING:
    from inertia_kit.physics.meshes import MeshSolid
    from inertia_kit.physics.unions import Part


def _finite(value: model.Number) -> float | None:
    return value if isinstance(value, float) else None


def declared_mass(link: model.Link) -> float | None:
    """The link's declared ``<mass value>`` when it is a finite positive number, else ``None``."""
    inertial = link.inertial
    mass = None if inertial is None else inertial.mass
    return mass if isinstance(mass, float) and math.isfinite(mass) and mass > 0 else None


def declared(link: model.Link) -> MassProperties | None:
    """
    The link's ``<inertial>`` as mass properties in the link frame, or ``None`` when it is
    absent or incomplete (a value missing or not a finite number).
    """
    inertial = link.inertial
    if inertial is None:
        return None
    mass = _finite(inertial.mass)
    tensor = [_finite(v) for v in inertial.tensor_values().values()]
    xyz, rpy = inertial.origin.xyz, inertial.origin.rpy
    if mass is None or None in tensor or not isinstance(xyz, tuple) or not isinstance(rpy, tuple):
        return None
    ixx, ixy, ixz, iyy, iyz, izz = tensor
    return MassProperties.from_urdf(mass, ixx, ixy, ixz, iyy, iyz, izz, xyz=xyz, rpy=rpy)  # type: ignore[arg-type]


def _number(value: model.Number) -> str:
    from inertia_kit.physics.formatting import fmt

    if value is None:
        return "?"
    return f"{value.text!r}" if isinstance(value, model.Invalid) else fmt(value, 4)


def _vector(value: model.Vector) -> str:
    if value is None:
        return "?"
    if isinstance(value, model.Invalid):
        return repr(value.text)
    return "×".join(_number(v) for v in value)


def describe_geometry(geometry: model.Geometry) -> str:
    """A short summary: ``box 0.4×0.4×0.1``, ``cylinder r0.35 l0.4``, ``mesh pan.stl ×0.001``."""
    if isinstance(geometry, model.Box):
        return f"box {_vector(geometry.size)}"
    if isinstance(geometry, model.Cylinder):
        return f"cylinder r{_number(geometry.radius)} l{_number(geometry.length)}"
    if isinstance(geometry, model.Sphere):
        return f"sphere r{_number(geometry.radius)}"
    if isinstance(geometry, model.Capsule):
        return f"capsule r{_number(geometry.radius)} l{_number(geometry.length)}"
    if isinstance(geometry, model.Mesh):
        name = geometry.filename.rsplit("/", 1)[-1]
        scale = geometry.scale
        scaled = (
            ""
            if scale == (1.0, 1.0, 1.0)
            else (
                f" ×{_number(scale[0])}"
                if isinstance(scale, tuple) and len(set(scale)) == 1
                else f" ×{_vector(scale)}"
            )
        )
        missing = "" if geometry.path else " (not found)"
        return f"mesh {name}{scaled}{missing}"
    return f"<{geometry.tag}>" if geometry.tag else "empty geometry"


def geometry_summary(link: model.Link) -> str:
    """What geometry the link has: collision shapes, else visual ones."""
    if link.collisions:
        return "collision: " + ", ".join(describe_geometry(s.geometry) for s in link.collisions)
    if link.visuals:
        return "visual only: " + ", ".join(describe_geometry(s.geometry) for s in link.visuals)
    return "no geometry"


# --- geometry ---------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Solid:
    """
    One ``<visual>``/``<collision>`` shape evaluated as a solid in the link frame.

    ``unit`` is its mass properties at 1 kg/m³ (so ``unit.mass`` is its volume); ``None``
    with ``problem`` set when the shape yields none: ``(kind, message)`` with kind one of
    ``invalid-number``, ``degenerate``, ``unknown-geometry``, ``mesh-not-found``,
    ``mesh-unreadable``, ``mesh-empty``.
    """

    shape: model.Shape
    unit: MassProperties | None
    corners: (
        NDArray[np.float64] | None
    )  # (8, 3) corners of the shape's own bounding box, link frame
    part: Part | None = None
    mesh: MeshSolid | None = None
    problem: tuple[str, str] | None = None

    @property
    def volume(self) -> float:
        return 0.0 if self.unit is None else self.unit.mass

    @functools.cached_property
    def hull(self) -> Hull | None:
        """A convex set containing the solid (see :class:`Hull`), or ``None`` without a solid."""
        if self.part is not None:
            return Hull.of_part(self.part)
        if self.corners is not None:
            return Hull(self.corners)
        return None

    def contains(self, point: ArrayLike, tol: float = 0.0) -> bool | None:
        """
        Whether ``point`` (3,) m in the link frame lies inside the solid (within ``tol`` m):
        exact for primitives; for a mesh ``None`` (unknown) inside its bounding box.
        """
        if self.part is None:
            if self.corners is None:
                return None
            hull = Hull(self.corners)
            return None if hull.distance_outside(point) <= tol else False
        return _part_contains(self.part, np.asarray(point, dtype=np.float64), tol)


@dataclass(frozen=True, eq=False)
class Geometry:
    """
    The solids of one kind (``collision`` or ``visual``) of a link, and their union.

    ``unit`` is the union's mass properties at 1 kg/m³ when every shape yielded a solid, else
    ``None`` (a partial geometry would give wrong expectations).
    """

    kind: str | None
    solids: tuple[Solid, ...]
    unit: MassProperties | None
    overlap_volume: float = 0.0

    @property
    def volume(self) -> float:
        return 0.0 if self.unit is None else self.unit.mass

    @property
    def problems(self) -> list[tuple[Solid, tuple[str, str]]]:
        return [(s, s.problem) for s in self.solids if s.problem is not None]

    @property
    def corners(self) -> NDArray[np.float64] | None:
        """(8k, 3) bounding-box corners of every solid, link frame: a hull of the geometry."""
        boxes = [s.corners for s in self.solids if s.corners is not None]
        return np.concatenate(boxes) if boxes else None

    @functools.cached_property
    def hull(self) -> Hull | None:
        """A convex set containing every solid, or ``None`` when a shape yielded no solid."""
        hulls = [s.hull for s in self.solids]
        if not hulls or any(h is None for h in hulls):
            return None
        return Hull.union(hulls)  # type: ignore[arg-type]

    def at_mass(self, mass: float) -> MassProperties | None:
        """The geometry's mass properties for a total mass, at uniform density."""
        if self.unit is None or not self.unit.mass > 0 or not mass > 0:
            return None
        return self.unit.with_mass(mass)

    def describe(self) -> str:
        """``collision cylinder (r = 0.05 m, l = 0.3 m)`` or ``2 collision shapes (...)``."""
        parts = [shape_text(s.shape.geometry) for s in self.solids]
        if len(parts) == 1:
            return f"{self.kind} {parts[0]}"
        return f"{len(parts)} {self.kind} shapes ({'; '.join(parts)})"


MeshLoader = Callable[[str, tuple[float, float, float]], "MeshSolid"]


def _default_mesh_loader(path: str, scale: tuple[float, float, float]) -> MeshSolid:
    # the on-disk cache: re-linting an unchanged mesh reads a 1 kB entry, not the mesh
    from inertia_kit.physics.mesh_cache import cached_mesh_solid

    return cached_mesh_solid(path, scale)


def shape_text(geometry: model.Geometry) -> str:
    """A geometry with its dimensions and units, for messages."""
    from inertia_kit.physics.formatting import fmt

    def n(value: model.Number) -> str:
        return fmt(value, 4) if isinstance(value, float) else "?"

    if isinstance(geometry, model.Box):
        size = geometry.size
        dims = " × ".join(n(v) for v in size) if isinstance(size, tuple) else "?"
        return f"box ({dims} m)"
    if isinstance(geometry, model.Cylinder):
        return f"cylinder (r = {n(geometry.radius)} m, l = {n(geometry.length)} m)"
    if isinstance(geometry, model.Sphere):
        return f"sphere (r = {n(geometry.radius)} m)"
    if isinstance(geometry, model.Capsule):
        return f"capsule (r = {n(geometry.radius)} m, l = {n(geometry.length)} m)"
    if isinstance(geometry, model.Mesh):
        return f"mesh `{geometry.filename}`"
    return "unknown geometry"


def _pose(origin: model.Origin) -> NDArray[np.float64] | None:
    from inertia_kit.physics.frames import transform

    if not isinstance(origin.xyz, tuple) or not isinstance(origin.rpy, tuple):
        return None
    return transform(origin.xyz, origin.rpy)


def _positive(values: tuple[model.Number, ...]) -> tuple[float, ...] | None:
    if not all(isinstance(v, float) for v in values):
        return None
    return tuple(values) if all(v > 0 for v in values) else ()  # type: ignore[return-value]


def evaluate_shape(shape: model.Shape, load_mesh: MeshLoader = _default_mesh_loader) -> Solid:
    """Evaluate one placed shape as a solid at unit density, in the link frame."""
    from inertia_kit.errors import MeshError
    from inertia_kit.physics.unions import Part

    pose = _pose(shape.origin)
    if pose is None:
        return Solid(shape, None, None, problem=("invalid-number", "its <origin> is not numeric"))
    geometry = shape.geometry
    if isinstance(geometry, model.Unknown):
        what = f"<{geometry.tag}>" if geometry.tag else "nothing"
        return Solid(
            shape, None, None, problem=("unknown-geometry", f"its <geometry> holds {what}")
        )
    if isinstance(geometry, model.Mesh):
        if geometry.path is None:
            return Solid(shape, None, None, problem=("mesh-not-found", geometry.problem or ""))
        scale = geometry.scale
        if not isinstance(scale, tuple):
            return Solid(
                shape, None, None, problem=("invalid-number", "its mesh scale is not numeric")
            )
        if any(v == 0 for v in scale):
            return Solid(
                shape, None, None, problem=("degenerate", "its mesh scale has a zero factor")
            )
        try:
            solid = load_mesh(geometry.path, scale)
        except MeshError as error:
            kind = {"not-found": "mesh-not-found", "empty": "mesh-empty"}.get(
                error.kind, "mesh-unreadable"
            )
            return Solid(shape, None, None, problem=(kind, error.message))
        unit = solid.mass_properties(density=1.0).transformed(pose)
        corners = _box_corners(solid.bounds) @ pose[:3, :3].T + pose[:3, 3]
        return Solid(shape, unit, corners, mesh=solid)
    if isinstance(geometry, model.Box):
        size = geometry.size
        dims = None if not isinstance(size, tuple) else _positive(size)
        make = lambda d: Part.box(d, pose)  # noqa: E731
    elif isinstance(geometry, model.Cylinder):
        dims = _positive((geometry.radius, geometry.length))
        make = lambda d: Part.cylinder(*d, pose)  # noqa: E731
    elif isinstance(geometry, model.Capsule):
        dims = _positive((geometry.radius, geometry.length))
        make = lambda d: Part.capsule(*d, pose)  # noqa: E731
    else:  # Sphere
        dims = _positive((geometry.radius,))
        make = lambda d: Part.sphere(d[0], pose)  # noqa: E731
    if dims is None:
        return Solid(shape, None, None, problem=("invalid-number", "a dimension is not numeric"))
    if dims == ():
        return Solid(shape, None, None, problem=("degenerate", "a dimension is zero or negative"))
    part = make(dims)
    return Solid(shape, part.mass_properties(density=1.0), _box_corners(part.bounds), part=part)


def _box_corners(bounds: NDArray[np.float64]) -> NDArray[np.float64]:
    """(8, 3) corners of an axis-aligned box given as (2, 3) low/high."""
    low, high = np.asarray(bounds, dtype=np.float64)
    pick = np.array([[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)])
    return np.where(pick == 0, low, high)


# --- bounds -----------------------------------------------------------------------------------

# sides of the polygon circumscribed about a cylinder's rims: its corners lie 1/cos(π/64) - 1 =
# 0.12 % outside the circle, so every bound taken over them holds and is within 0.25 % of tight
RIM_SIDES = 64

# a declared moment this far above a hard bound (relative) is impossible, not rounding: values
# are often written with 3–4 significant digits
BOUND_RTOL = 0.01


def _unit_directions(count: int = 256) -> NDArray[np.float64]:
    """(count + 6, 3) unit vectors: the six axis directions and a Fibonacci sphere."""
    i = np.arange(count) + 0.5
    polar = np.arccos(1.0 - 2.0 * i / count)
    azimuth = np.pi * (1.0 + 5.0**0.5) * i
    sphere = np.column_stack(
        (np.cos(azimuth) * np.sin(polar), np.sin(azimuth) * np.sin(polar), np.cos(polar))
    )
    return np.concatenate((np.eye(3), -np.eye(3), sphere))


_DIRECTIONS = _unit_directions()


@dataclass(frozen=True, eq=False)
class Hull:
    """
    A convex set that contains a geometry: the convex hull of balls ``B(points[i], radii[i])``.

    Boxes are their 8 corners; spheres one ball and capsules two; cylinders the corners of
    polygons circumscribed about their rims; meshes the 8 corners of their bounding box. So the
    set always contains the solid, and a maximum of a convex function over it (a distance, a
    support value) is an upper bound of the same maximum over the solid: bounds derived here
    never understate what the geometry allows.

    Attributes
    ----------
    points : (k, 3) float
      Ball centres, link frame, m.
    radii : (k,) float
      Ball radii, m (zero for plain points).
    """

    points: NDArray[np.float64]
    radii: NDArray[np.float64] | None = None

    def __post_init__(self) -> None:
        points = np.asarray(self.points, dtype=np.float64)
        if points.ndim != 2 or points.shape[1] != 3 or len(points) == 0:
            raise ValueError(f"points must be (k, 3) with k > 0, got shape {points.shape}")
        radii = np.zeros(len(points)) if self.radii is None else np.asarray(self.radii, float)
        if radii.shape != (len(points),):
            raise ValueError(f"radii must be ({len(points)},), got shape {radii.shape}")
        object.__setattr__(self, "points", points)
        object.__setattr__(self, "radii", radii)

    @classmethod
    def of_part(cls, part: Part) -> Hull:
        """The hull of a placed primitive or mesh part (see the class docstring)."""
        rotation, offset = part.pose[:3, :3], part.pose[:3, 3]
        if part.kind == "sphere":
            return cls(offset[None, :], np.array([part.dimensions[0]]))
        if part.kind == "capsule":
            radius, length = part.dimensions
            ends = np.array([[0.0, 0.0, -0.5 * length], [0.0, 0.0, 0.5 * length]])
            return cls(ends @ rotation.T + offset, np.full(2, radius))
        if part.kind == "cylinder":
            radius, length = part.dimensions
            angles = 2.0 * np.pi * np.arange(RIM_SIDES) / RIM_SIDES
            corner = radius / np.cos(np.pi / RIM_SIDES)
            ring = np.column_stack((corner * np.cos(angles), corner * np.sin(angles)))
            rims = np.concatenate(
                [np.column_stack((ring, np.full(RIM_SIDES, z))) for z in (-0.5, 0.5)]
            )
            rims[:, 2] *= length
            return cls(rims @ rotation.T + offset)
        return cls(_box_corners(part.bounds) if part.kind == "mesh" else _part_corners(part))

    @staticmethod
    def union(hulls: list[Hull]) -> Hull:
        """A hull containing every one of ``hulls`` (the hull of their union)."""
        if len(hulls) == 1:
            return hulls[0]
        return Hull(
            np.concatenate([h.points for h in hulls]),
            np.concatenate([h.radii for h in hulls]),  # type: ignore[misc]
        )

    @property
    def bounds(self) -> NDArray[np.float64]:
        """(2, 3) lowest and highest corner of an axis-aligned box around the hull, m."""
        radii = self.radii[:, None]  # type: ignore[index]
        return np.array([(self.points - radii).min(axis=0), (self.points + radii).max(axis=0)])

    def support(self, directions: ArrayLike) -> NDArray[np.float64]:
        """
        Support function: the largest ``u · x`` over the hull for each direction ``u``.

        Parameters
        ----------
        directions : (n, 3) float
          Unit vectors, link frame.

        Returns
        -------
        support : (n,) float
          m
        """
        u = np.atleast_2d(np.asarray(directions, dtype=np.float64))
        return (u @ self.points.T + self.radii).max(axis=1)

    def farthest(self, point: ArrayLike) -> float:
        """The largest distance from ``point`` (3,) to the hull, m: the ``r_max`` about a point."""
        offsets = self.points - np.asarray(point, dtype=np.float64)
        return float((np.linalg.norm(offsets, axis=1) + self.radii).max())

    def farthest_from_axes(self, point: ArrayLike, axes: ArrayLike) -> NDArray[np.float64]:
        """
        The largest distance from each axis through ``point`` to the hull, m.

        Parameters
        ----------
        point : (3,) float
          A point on every axis (the centre of mass), link frame, m.
        axes : (n, 3) float
          Unit axis directions.

        Returns
        -------
        r_max : (n,) float
          m; a mass ``m`` inside the hull has at most ``m · r_max²`` about each axis.
        """
        q = self.points - np.asarray(point, dtype=np.float64)
        a = np.atleast_2d(np.asarray(axes, dtype=np.float64))
        along = a @ q.T  # (n, k)
        perpendicular = np.sqrt(np.maximum((q * q).sum(axis=1) - along**2, 0.0))
        return (perpendicular + self.radii).max(axis=1)

    def spread(self, point: ArrayLike, directions: ArrayLike) -> NDArray[np.float64]:
        """
        Bhatia–Davis bound of the second moment per unit mass along each direction.

        For a mass ``m`` inside the hull with centre of mass ``c``, ``∫ (u·(x - c))² dm ≤
        m (h(u) - u·c)(u·c + h(-u))``, with ``h`` the support function: the variance of a
        quantity between bounds is largest for two point masses at the bounds.

        Returns
        -------
        spread : (n,) float
          m²; negative when ``point`` lies outside the hull's extent along a direction (no
          distribution inside the hull has that centre of mass).
        """
        u = np.atleast_2d(np.asarray(directions, dtype=np.float64))
        centre = u @ np.asarray(point, dtype=np.float64)
        return (self.support(u) - centre) * (centre + self.support(-u))

    def moment_bound(self, point: ArrayLike, frame: ArrayLike) -> NDArray[np.float64]:
        """
        The largest moment of inertia per unit mass that any distribution inside the hull with
        its centre of mass at ``point`` can have about each axis of ``frame``.

        The smaller of two valid bounds: the squared distance to the farthest point of the hull
        from the axis, and the Bhatia–Davis bounds of the second moments along the frame's other
        two axes (``I_x = ∫ y² + z² dm``).

        Parameters
        ----------
        point : (3,) float
          Centre of mass, link frame, m.
        frame : (3, 3) float
          Orthonormal axes as columns.

        Returns
        -------
        bound : (3,) float
          m² (multiply by the mass for kg·m²).
        """
        axes = np.asarray(frame, dtype=np.float64).T
        by_distance = self.farthest_from_axes(point, axes) ** 2
        spread = self.spread(point, axes)
        if (spread < 0).any():
            return by_distance
        by_spread = spread.sum() - spread
        return np.minimum(by_distance, by_spread)

    def distance_outside(self, point: ArrayLike) -> float:
        """
        A lower bound of the distance from ``point`` (3,) to the hull, m: 0 when inside.

        ``u · p - h(u)`` over a fixed set of directions (and the one from the hull's centre to
        the point) never exceeds the true distance, so a positive value proves ``point`` is
        outside.
        """
        p = np.asarray(point, dtype=np.float64)
        towards = p - self.points.mean(axis=0)
        norm = np.linalg.norm(towards)
        directions = _DIRECTIONS if not norm > 0 else np.vstack((_DIRECTIONS, towards / norm))
        return max(float((directions @ p - self.support(directions)).max()), 0.0)

    def half_widths(self, point: ArrayLike, directions: ArrayLike) -> NDArray[np.float64]:
        """How far the hull reaches from ``point`` along each direction (support minus u·p), m."""
        u = np.atleast_2d(np.asarray(directions, dtype=np.float64))
        return self.support(u) - u @ np.asarray(point, dtype=np.float64)


def _part_corners(part: Part) -> NDArray[np.float64]:
    from inertia_kit.physics.tessellate import half_extents

    signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)
    local = signs * half_extents(part.kind, part.dimensions)
    return local @ part.pose[:3, :3].T + part.pose[:3, 3]


def _part_contains(part: Part, point: NDArray[np.float64], tol: float) -> bool | None:
    """Exact point-in-primitive test in the part's own frame; ``None`` for a mesh."""
    local = part.pose[:3, :3].T @ (point - part.pose[:3, 3])
    if part.kind == "box":
        return bool((np.abs(local) <= 0.5 * np.array(part.dimensions) + tol).all())
    if part.kind == "sphere":
        return bool(np.linalg.norm(local) <= part.dimensions[0] + tol)
    if part.kind == "cylinder":
        radius, length = part.dimensions
        return bool(np.hypot(*local[:2]) <= radius + tol and abs(local[2]) <= 0.5 * length + tol)
    if part.kind == "capsule":
        radius, length = part.dimensions
        axial = np.clip(local[2], -0.5 * length, 0.5 * length)
        return bool(np.linalg.norm(local - np.array([0.0, 0.0, axial])) <= radius + tol)
    return None


@dataclass(frozen=True)
class TensorComparison:
    """
    How a declared inertia tensor compares with an expected one, axis by axis, in link axes.

    ``ratios[i]`` is the generalised eigenvalue ``λ`` of ``I_declared v = λ I_expected v``: the
    ratio of the two moments about ``axes[i]``. They are the stationary values of
    ``nᵀ I_declared n / nᵀ I_expected n`` over all axes ``n``, so the largest and smallest are
    the largest and smallest ratio of moments about any axis: a tensor written for the wrong
    axes (same eigenvalues) shows up, and so does a wrong value about an axis of symmetry.

    Attributes
    ----------
    ratios : (3,) float
      Ascending.
    axes : (3, 3) float
      Unit axes (rows), link frame.
    """

    ratios: NDArray[np.float64]
    axes: NDArray[np.float64]

    @property
    def worst(self) -> int:
        """Index of the ratio farthest from 1 (by factor)."""
        return int(np.argmax(np.abs(np.log(self.ratios))))

    @property
    def factor(self) -> float:
        """The largest factor between the two moments about any axis (≥ 1)."""
        return float(np.exp(np.abs(np.log(self.ratios)).max()))


def compare_tensors(declared: ArrayLike, expected: ArrayLike) -> TensorComparison | None:
    """
    Compare two inertia tensors (3, 3) kg·m² in the same axes through generalised eigenvalues.

    Returns ``None`` unless both are symmetric positive definite (the expected one must be; a
    declared one that is not is another rule's finding).
    """
    a = np.asarray(declared, dtype=np.float64)
    b = np.asarray(expected, dtype=np.float64)
    if (
        a.shape != (3, 3)
        or b.shape != (3, 3)
        or not (np.isfinite(a).all() and np.isfinite(b).all())
    ):
        return None
    a, b = 0.5 * (a + a.T), 0.5 * (b + b.T)
    try:
        lower = np.linalg.cholesky(b)
        np.linalg.cholesky(a)
    except np.linalg.LinAlgError:
        return None
    inverse = np.linalg.inv(lower)
    # eigh: symmetric input; L⁻¹ A L⁻ᵀ has the generalised eigenvalues of (A, B = L Lᵀ)
    ratios, vectors = np.linalg.eigh(inverse @ a @ inverse.T)
    axes = (inverse.T @ vectors).T
    axes /= np.linalg.norm(axes, axis=1, keepdims=True)
    if not (ratios > 0).all():
        return None
    return TensorComparison(ratios, axes)


@dataclass(frozen=True)
class MomentExcess:
    """
    The axis through a declared centre of mass about which the declared moment comes closest to
    (or goes furthest beyond) the most any distribution inside a hull can have.

    Attributes
    ----------
    axis : (3,) float
      Unit axis, link frame.
    moment : float
      The declared moment about it, kg·m².
    bound : float
      ``mass · bound per unit mass`` (:meth:`Hull.moment_bound`), kg·m².
    r_max : float
      The farthest the hull reaches from the axis, m (``bound ≤ mass · r_max²``).
    """

    axis: NDArray[np.float64]
    moment: float
    bound: float
    r_max: float

    @property
    def ratio(self) -> float:
        return self.moment / self.bound if self.bound > 0 else math.inf


def moment_excess(declared: MassProperties, hull: Hull) -> MomentExcess | None:
    """
    The worst axis of ``declared`` against the hard bound of ``hull`` (see :class:`MomentExcess`).

    Checks the link axes and the declared principal axes (distance and Bhatia–Davis bounds) and
    a fixed set of further directions (distance bound); when a link axis is beyond the bound it
    is reported in preference, since its moment is a value written in the file.

    Returns ``None`` unless the mass is positive and everything is finite.
    """
    mass, com, tensor = declared.mass, declared.com, declared.inertia
    if not (mass > 0 and np.isfinite(com).all() and np.isfinite(tensor).all()):
        return None
    tensor = 0.5 * (tensor + tensor.T)
    candidates: list[MomentExcess] = []
    for frame in (np.eye(3), declared.principal_axes):
        bounds = mass * hull.moment_bound(com, frame)
        reach = hull.farthest_from_axes(com, frame.T)
        for i in range(3):
            axis = frame[:, i]
            candidates.append(
                MomentExcess(axis, float(axis @ tensor @ axis), float(bounds[i]), float(reach[i]))
            )
    reach = hull.farthest_from_axes(com, _DIRECTIONS)
    moments = np.einsum("ij,jk,ik->i", _DIRECTIONS, tensor, _DIRECTIONS)
    with np.errstate(divide="ignore", invalid="ignore"):
        worst = int(np.argmax(moments / (mass * reach**2)))
    candidates.append(
        MomentExcess(
            _DIRECTIONS[worst],
            float(moments[worst]),
            float(mass * reach[worst] ** 2),
            float(reach[worst]),
        )
    )
    named = [c for c in candidates[:3] if c.ratio > 1.0]
    return max(named or candidates, key=lambda c: c.ratio)


def axis_name(axis: ArrayLike, tol: float = 1e-3) -> str | None:
    """``x``, ``y`` or ``z`` when the unit ``axis`` (3,) is (anti)parallel to a link axis."""
    a = np.abs(np.asarray(axis, dtype=np.float64))
    index = int(np.argmax(a))
    return "xyz"[index] if a[index] >= 1.0 - tol else None


def evaluate_geometry(
    shapes: tuple[model.Shape, ...], kind: str | None, load_mesh: MeshLoader = _default_mesh_loader
) -> Geometry:
    """The solids of ``shapes`` and, when all are usable, their union at unit density."""
    solids = tuple(evaluate_shape(shape, load_mesh) for shape in shapes)
    if not solids or any(s.unit is None for s in solids):
        return Geometry(kind, solids, None)
    if len(solids) == 1:
        return Geometry(kind, solids, solids[0].unit)
    parts = [s.part for s in solids if s.part is not None]
    meshes = [s.unit for s in solids if s.part is None]
    overlap = 0.0
    unit = None
    if len(parts) > 1:
        from inertia_kit.physics.unions import union

        try:
            result = union(parts, density=1.0)
            unit, overlap = result.mass_properties, result.overlap_volume
        except ValueError:
            unit = None
    if unit is None and parts:
        unit = sum(s.part.mass_properties(density=1.0) for s in solids if s.part is not None)
    # meshes are added whole: their overlaps with other shapes are not removed
    total = sum(meshes, unit) if unit is not None else sum(meshes)
    return Geometry(kind, solids, total, overlap)


# --- links and robots -------------------------------------------------------------------------


class LinkAnalysis:
    """A link with its place in the tree, its declared values and its geometry (lazily)."""

    def __init__(
        self,
        link: model.Link,
        parent: model.Joint | None,
        children: tuple[model.Joint, ...],
        load_mesh: MeshLoader = _default_mesh_loader,
    ):
        self.link = link
        self.name = link.name
        self.parent = parent
        self.children = children
        self._load_mesh = load_mesh
        # the robot this link belongs to, set by RobotAnalysis (None for a link analysed alone)
        self.robot: RobotAnalysis | None = None

    @property
    def moves(self) -> bool:
        """Child of a non-fixed joint (revolute, continuous, prismatic, floating, planar)."""
        return self.parent is not None and self.parent.type != "fixed"

    @functools.cached_property
    def declared(self) -> MassProperties | None:
        return declared(self.link)

    @functools.cached_property
    def collision(self) -> Geometry:
        return evaluate_geometry(self.link.collisions, "collision", self._load_mesh)

    @functools.cached_property
    def visual(self) -> Geometry:
        return evaluate_geometry(self.link.visuals, "visual", self._load_mesh)

    def mesh_kind_solids(self, kinds: tuple[str, ...] = ("visual", "collision")) -> Iterator[Solid]:
        """
        The solids of each of ``kinds`` (``visual``, ``collision``) that has at least one mesh
        shape; kinds without a mesh are not evaluated, so no mesh rule reads what it need not.
        """
        for kind in kinds:
            shapes = self.link.visuals if kind == "visual" else self.link.collisions
            if any(isinstance(s.geometry, model.Mesh) for s in shapes):
                yield from getattr(self, kind).solids

    @property
    def geometry(self) -> Geometry:
        """The geometry mass comes from: collision shapes, else visual ones."""
        if self.link.collisions:
            return self.collision
        if self.link.visuals:
            return self.visual
        return Geometry(None, (), None)

    @functools.cached_property
    def envelope(self) -> Hull | None:
        """
        A convex set containing all the link's geometry, collision and visual: where its mass
        can be at most. ``None`` without geometry, or when any shape yields no solid (a partial
        envelope would understate what is possible).
        """
        hulls = [g.hull for g in (self.collision, self.visual) if g.solids]
        if not hulls or any(h is None for h in hulls):
            return None
        return Hull.union(hulls)  # type: ignore[arg-type]

    @functools.cached_property
    def excess(self) -> MomentExcess | None:
        """
        The declared tensor against the hard bound of :attr:`envelope` (see
        :func:`moment_excess`); ``None`` without a declared value or an envelope.
        """
        if self.declared is None or self.envelope is None:
            return None
        return moment_excess(self.declared, self.envelope)

    @property
    def mass_share(self) -> float:
        """The link's mass as a fraction of its fixed-joint group's (see RobotAnalysis)."""
        return 1.0 if self.robot is None else self.robot.mass_share(self.name)

    @property
    def bases(self) -> tuple[Geometry, ...]:
        """
        Every usable geometry of the link, collision first then visual: the shapes a rule may
        compare declared values with (one that matches either is not suspicious).
        """
        found = []
        for shapes, name in ((self.link.collisions, "collision"), (self.link.visuals, "visual")):
            if shapes:
                geometry = getattr(self, name)
                if geometry.unit is not None and geometry.unit.mass > 0:
                    found.append(geometry)
        return tuple(found)

    @property
    def expected(self) -> MassProperties | None:
        """The geometry's mass properties for the declared mass (uniform density)."""
        if self.declared is None:
            return None
        return self.geometry.at_mass(self.declared.mass)


def _memoised(load_mesh: MeshLoader) -> MeshLoader:
    """One load per (mesh, scale) for one robot: visual and collision often name the same file."""
    from inertia_kit.errors import MeshError

    results: dict[tuple[str, tuple[float, float, float]], object] = {}

    def load(path: str, scale: tuple[float, float, float]) -> MeshSolid:
        key = (path, tuple(scale))
        if key not in results:
            try:
                results[key] = load_mesh(path, scale)
            except MeshError as error:
                results[key] = error
        result = results[key]
        if isinstance(result, MeshError):
            raise result
        return result  # type: ignore[return-value]

    return load


class RobotAnalysis:
    """All links of a robot, with tree relations and fixed-joint groups."""

    def __init__(self, robot: model.Robot, load_mesh: MeshLoader = _default_mesh_loader):
        self.robot = robot
        load_mesh = _memoised(load_mesh)
        parents: dict[str, model.Joint] = {}
        children: dict[str, list[model.Joint]] = {}
        for joint in robot.joints:
            if joint.child is not None:
                parents.setdefault(joint.child, joint)
            if joint.parent is not None:
                children.setdefault(joint.parent, []).append(joint)
        self.links = tuple(
            LinkAnalysis(
                link, parents.get(link.name), tuple(children.get(link.name, ())), load_mesh
            )
            for link in robot.links
        )
        self.by_name = {}
        for link in self.links:
            link.robot = self
            self.by_name.setdefault(link.name, link)

    def group_of(self, name: str) -> tuple[LinkAnalysis, ...]:
        """
        The links welded to ``name`` by fixed joints (what simulators lump into one body),
        ``name`` included; cycles and unknown names are tolerated.
        """
        seen: dict[str, LinkAnalysis] = {}
        stack = [name]
        while stack:
            current = stack.pop()
            if current in seen or current not in self.by_name:
                continue
            link = self.by_name[current]
            seen[current] = link
            if link.parent is not None and link.parent.type == "fixed" and link.parent.parent:
                stack.append(link.parent.parent)
            stack.extend(j.child for j in link.children if j.type == "fixed" and j.child)
        return tuple(seen.values())

    def mass_share(self, name: str) -> float:
        """
        The link's declared mass as a fraction of its fixed-joint group's (1.0 for a link alone
        or a group without mass): what its own values weigh in the body a simulator lumps.
        """
        link = self.by_name.get(name)
        mass = None if link is None else declared_mass(link.link)
        total = self.group_mass(name)
        if mass is None or total <= 0:
            return 1.0
        return mass / total

    def group_mass(self, name: str) -> float:
        """Total declared mass of ``name``'s fixed-joint group (finite positive masses only)."""
        return sum((declared_mass(link.link) or 0.0 for link in self.group_of(name)), 0.0)


def analyse(robot: model.Robot, load_mesh: MeshLoader = _default_mesh_loader) -> RobotAnalysis:
    return RobotAnalysis(robot, load_mesh)
