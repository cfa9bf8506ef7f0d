"""
Hard bounds of a link's mass distribution: a convex set that contains its geometry
(:class:`Hull`), the most any mass inside it can have about an axis through its centre of mass,
and the most it can have as second moment along a direction (:func:`moment_excess`). Outside
them a declared value is impossible (IN023); the forensics use them to tell a slip from a real
but unusual part.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from inertia_kit.physics.mass import MassProperties

if TYPE_CHECKING:
    from inertia_kit.physics.unions import Part

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
    normals : (j, 3) float
      The parts' own axes (a box's face normals, a cylinder's or capsule's axis): where a part
      is thinnest, so where the second-moment bound (:meth:`spread`) is tightest. Only a hint
      of directions to check; no bound depends on them.
    """

    points: NDArray[np.float64]
    radii: NDArray[np.float64] | None = None
    normals: NDArray[np.float64] | None = None

    def __post_init__(self) -> None:
        points = np.asarray(self.points, dtype=np.float64)
        if points.ndim != 2 or points.shape[1] != 3 or len(points) == 0:
            raise ValueError(f"points must be (k, 3) with k > 0, got shape {points.shape}")
        radii = np.zeros(len(points)) if self.radii is None else np.asarray(self.radii, float)
        if radii.shape != (len(points),):
            raise ValueError(f"radii must be ({len(points)},), got shape {radii.shape}")
        normals = np.zeros((0, 3)) if self.normals is None else np.asarray(self.normals, float)
        if normals.ndim != 2 or normals.shape[1] != 3:
            raise ValueError(f"normals must be (j, 3), got shape {normals.shape}")
        object.__setattr__(self, "points", points)
        object.__setattr__(self, "radii", radii)
        object.__setattr__(self, "normals", normals)

    @classmethod
    def of_box(cls, corners: ArrayLike) -> Hull:
        """
        The hull of a box given as its 8 corners in :func:`box_corners`' order (possibly rotated
        and moved), with its three edge directions as :attr:`normals`.
        """
        points = np.asarray(corners, dtype=np.float64)
        edges = points[[4, 2, 1]] - points[0]
        lengths = np.linalg.norm(edges, axis=1)
        keep = lengths > 0
        return cls(points, normals=edges[keep] / lengths[keep, None])

    @classmethod
    def of_part(cls, part: Part) -> Hull:
        """The hull of a placed primitive or mesh part (see the class docstring)."""
        rotation, offset = part.pose[:3, :3], part.pose[:3, 3]
        if part.kind == "sphere":
            return cls(offset[None, :], np.array([part.dimensions[0]]))
        if part.kind == "capsule":
            radius, length = part.dimensions
            ends = np.array([[0.0, 0.0, -0.5 * length], [0.0, 0.0, 0.5 * length]])
            return cls(ends @ rotation.T + offset, np.full(2, radius), rotation[:, 2:].T)
        if part.kind == "cylinder":
            radius, length = part.dimensions
            angles = 2.0 * np.pi * np.arange(RIM_SIDES) / RIM_SIDES
            corner = radius / np.cos(np.pi / RIM_SIDES)
            ring = np.column_stack((corner * np.cos(angles), corner * np.sin(angles)))
            rims = np.concatenate(
                [np.column_stack((ring, np.full(RIM_SIDES, z))) for z in (-0.5, 0.5)]
            )
            rims[:, 2] *= length
            return cls(rims @ rotation.T + offset, normals=rotation[:, 2:].T)
        return cls.of_box(box_corners(part.bounds) if part.kind == "mesh" else _part_corners(part))

    @staticmethod
    def union(hulls: list[Hull]) -> Hull:
        """A hull containing every one of ``hulls`` (the hull of their union)."""
        if len(hulls) == 1:
            return hulls[0]
        return Hull(
            np.concatenate([h.points for h in hulls]),
            np.concatenate([h.radii for h in hulls]),  # type: ignore[misc]
            np.concatenate([h.normals for h in hulls]),  # type: ignore[misc]
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

        For a mass ``m`` inside the hull with centre of mass ``c``, and a unit ``u``::

            uᵀ Σ u = ∫ (u·(x - c))² dm ≤ m (h(u) - u·c)(u·c + h(-u)),

        with ``Σ = ∫ (x - c)(x - c)ᵀ dm = ½ tr(I) E - I`` the central second moment and ``h``
        the support function (:meth:`support`).

        Proof. Let ``t = u·x``, ``a = -h(-u)``, ``b = h(u)`` and ``μ = u·c`` (the mean of ``t``,
        since ``c`` is the centre of mass). Every ``x`` in the hull has ``a ≤ t ≤ b``, so
        ``(b - t)(t - a) ≥ 0`` everywhere and ``∫ (b - t)(t - a) dm ≥ 0``. Expanding with
        ``∫ t dm = m μ`` and ``∫ t² dm = m μ² + uᵀΣu``::

            0 ≤ ∫ (b - t)(t - a) dm = m (b - μ)(μ - a) - uᵀΣu.

        Equality holds exactly when the mass sits where ``(b - t)(t - a) = 0``: on the two
        supporting planes ``t = a`` and ``t = b`` (two point masses at support points, with
        masses that put their centre at ``μ``), so no tighter bound in terms of ``a``, ``b``,
        ``μ`` exists. Every direction gives a valid bound: which directions are checked decides
        only what is found, never whether a finding is right.

        Returns
        -------
        spread : (n,) float
          m²; negative when ``point`` lies outside the hull's extent along a direction (no
          distribution inside the hull has that centre of mass).
        """
        low, high = self.spans(point, directions)
        return high * low

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

    def spans(
        self, point: ArrayLike, directions: ArrayLike
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """
        :meth:`half_widths` along ``-u`` and along ``u``: the same numbers, from one product
        with the points, since negation is exact in floating point (``(-u)·x`` is ``-(u·x)``
        to the bit). The local search of :func:`_along` asks for both sides of every trial.
        """
        u = np.atleast_2d(np.asarray(directions, dtype=np.float64))
        along = u @ self.points.T
        centre = u @ np.asarray(point, dtype=np.float64)
        return (self.radii - along).max(axis=1) + centre, (along + self.radii).max(axis=1) - centre


def _part_corners(part: Part) -> NDArray[np.float64]:
    from inertia_kit.physics.tessellate import half_extents

    signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)
    local = signs * half_extents(part.kind, part.dimensions)
    return local @ part.pose[:3, :3].T + part.pose[:3, 3]


def box_corners(bounds: NDArray[np.float64]) -> NDArray[np.float64]:
    """(8, 3) corners of an axis-aligned box given as (2, 3) low/high."""
    low, high = np.asarray(bounds, dtype=np.float64)
    pick = np.array([[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)])
    return np.where(pick == 0, low, high)


Kind = Literal["about", "along"]


@dataclass(frozen=True)
class MomentExcess:
    """
    The axis through a declared centre of mass about which the declared moment comes closest to
    (or goes furthest beyond) the most any distribution inside a hull can have; or, of kind
    ``along``, the direction along which the declared second moment does.

    Attributes
    ----------
    axis : (3,) float
      Unit axis (or direction), link frame.
    moment : float
      The declared moment about it (``uᵀ I u``), or the declared second moment along it
      (``uᵀ Σ u = ½ tr(I) - uᵀ I u``), kg·m².
    bound : float
      ``mass · bound per unit mass`` (:meth:`Hull.moment_bound`, :meth:`Hull.spread`), kg·m².
    r_max : float
      The farthest the hull reaches from the axis, m (``bound ≤ mass · r_max²``); along a
      direction, the farther of :attr:`sides`.
    kind : {"about", "along"}
      A moment about an axis, or a second moment along a direction.
    sides : (float, float)
      Along a direction: how far the hull reaches from the centre of mass towards ``-u`` and
      ``+u``, m (``bound = mass · sides[0] · sides[1]``); ``(0, 0)`` about an axis.
    """

    axis: NDArray[np.float64]
    moment: float
    bound: float
    r_max: float
    kind: Kind = "about"
    sides: tuple[float, float] = (0.0, 0.0)

    @property
    def ratio(self) -> float:
        """``moment / bound``; beyond any bound when the bound is 0, unless the moment is not
        positive either (a zero or negative moment is IN010's, never an excess)."""
        if self.bound > 0:
            return self.moment / self.bound
        return math.inf if self.moment > 0 else 0.0

    @property
    def weights(self) -> NDArray[np.float64]:
        """
        (3, 3) ``W`` with ``moment = Σᵢⱼ Wᵢⱼ Iᵢⱼ`` for the declared tensor ``I`` (link axes):
        ``u uᵀ`` about an axis, ``½ E - u uᵀ`` along one. How the rounding of the written
        ``<inertia>`` values moves the moment (:mod:`~inertia_kit.analysis.firmness`).
        """
        u = np.asarray(self.axis, dtype=np.float64)
        outer = np.outer(u, u)
        return outer if self.kind == "about" else 0.5 * np.eye(3) - outer


def moment_excess(
    declared: MassProperties, hull: Hull, kind: Kind | None = None
) -> MomentExcess | None:
    """
    The worst axis of ``declared`` against the hard bounds of ``hull`` (see
    :class:`MomentExcess`): of ``kind`` when given, else the moment about an axis when one is
    beyond its bound by more than :data:`BOUND_RTOL` (a value in the file, or near one, reads
    more plainly), else whichever comes closer to (or goes further beyond) its bound.

    About axes (:func:`_about`) and along directions (:func:`_along`); see those for what is
    checked. Returns ``None`` unless the mass is positive and everything is finite (and, for
    ``kind="along"``, the centre of mass lies inside the hull).
    """
    mass, com, tensor = declared.mass, declared.com, declared.inertia
    if not (mass > 0 and np.isfinite(com).all() and np.isfinite(tensor).all()):
        return None
    tensor = 0.5 * tensor + 0.5 * tensor.T  # no overflow near the largest float
    about = None if kind == "along" else _about(declared, tensor, hull)
    if kind is None and about.ratio > 1.0 + BOUND_RTOL:
        return about  # reported in preference to any direction: the search would be wasted
    along = None if kind == "about" else _along(declared, tensor, hull)
    if about is None or along is None:
        return about or along
    if about.ratio > 1.0 + BOUND_RTOL or not along.ratio > about.ratio:
        return about
    return along


def _about(declared: MassProperties, tensor: NDArray[np.float64], hull: Hull) -> MomentExcess:
    """
    The worst axis for the moment about it: the link axes and the declared principal axes
    (distance and Bhatia–Davis bounds) and a fixed set of further directions (distance bound);
    a link axis beyond the bound is reported in preference, since its moment is a value
    written in the file.
    """
    mass, com = declared.mass, declared.com

    def about_axes(frame: NDArray[np.float64]) -> list[MomentExcess]:
        bounds = mass * hull.moment_bound(com, frame)
        reach = hull.farthest_from_axes(com, frame.T)
        return [
            MomentExcess(axis, float(axis @ tensor @ axis), float(bound), float(far))
            for axis, bound, far in zip(frame.T, bounds, reach, strict=True)
        ]

    link_axes = about_axes(np.eye(3))
    named = [c for c in link_axes if c.ratio > 1.0 + BOUND_RTOL]
    if named:  # reported in preference to any other axis: none other is looked at
        return max(named, key=lambda c: c.ratio)
    candidates = [*link_axes, *about_axes(declared.principal_axes)]
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
    return max(candidates, key=lambda c: c.ratio)


# the local search of the worst direction (:func:`_along`): first step and smallest step, rad
_FIRST_STEP = 0.1
_LAST_STEP = 1e-5
_MAX_STEPS = 200
# a centre of mass closer than this to the hull's end, relative to its width, is on it: no
# written value is that precise, and the bound there (nearly 0) is IN021's business
_ON_BOUNDARY = 1e-6


def _along(
    declared: MassProperties, tensor: NDArray[np.float64], hull: Hull
) -> MomentExcess | None:
    """
    The worst direction for the second moment along it, ``uᵀΣu`` against ``m (h(u) - u·c)
    (u·c + h(-u))`` (:meth:`Hull.spread`); ``None`` when ``Σ`` is not positive semidefinite
    (the tensor breaks the triangle inequality: it is no body's at all, IN010's finding, and has
    no second moments to bound) or when the centre of mass is not inside the hull along every
    direction checked, or on its boundary to within a millionth of its width (the bound is then
    void or 0, and a COM outside or at the edge of its geometry is IN021's).

    The bound depends on ``u``, so the worst direction is no eigenvector. Checked: the link
    axes, the principal axes of ``Σ`` (those of ``I``), the hull's part axes
    (:attr:`Hull.normals`: a box's face normals and a cylinder's axis, where a part is
    thinnest and the bound smallest), and 262 directions spread over the sphere (12° apart);
    then a local search on the sphere (a pattern search from the worst of them, steps halved
    from 0.1 rad to 1e-5) climbs to the nearest local maximum of the ratio. An impossible
    second moment comes from a thin direction of the geometry (a wheel's axle, a plate's
    normal), which the part axes give exactly; for several parts the hull's thinnest
    direction lies between theirs, and the search from the best start finds it. Each checked
    direction is a valid bound, so a missed maximum can only hide a finding, never make a
    wrong one. A link axis beyond the bound is reported in preference, as for moments.
    """
    mass, com = declared.mass, declared.com
    with np.errstate(over="ignore", invalid="ignore"):
        second = 0.5 * np.trace(tensor) * np.eye(3) - tensor
    if not np.isfinite(second).all():
        return None  # a tensor near the largest float: no second moment to compare
    if np.linalg.eigvalsh(second)[0] < -1e-12 * float(np.abs(second).max()):
        return None

    def ratios(u: NDArray[np.float64]) -> NDArray[np.float64]:
        low, high = hull.spans(com, u)
        inside = np.minimum(low, high) > _ON_BOUNDARY * (low + high)
        values = np.einsum("ij,jk,ik->i", u, second, u)
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            ratio = values / (mass * low * high)
        return np.where(inside & np.isfinite(ratio), ratio, np.inf)

    axes = np.eye(3)
    starts = np.concatenate((axes, declared.principal_axes.T, hull.normals, _DIRECTIONS))
    found = ratios(starts)
    if not np.isfinite(found).all():
        return None
    best = int(np.argmax(found))
    u, value = starts[best], float(found[best])
    step = _FIRST_STEP
    offsets = np.array([[1, 0], [-1, 0], [0, 1], [0, -1], [1, 1], [1, -1], [-1, 1], [-1, -1]])
    tangent = None
    for _ in range(_MAX_STEPS):
        if step < _LAST_STEP:
            break
        if tangent is None:  # two unit vectors perpendicular to u, again only when u moves
            tangent = offsets @ np.linalg.svd(u[None, :])[2][1:]
        trial = u + step * tangent
        trial /= np.linalg.norm(trial, axis=1)[:, None]
        scores = ratios(trial)
        if not np.isfinite(scores).all():
            return None
        i = int(np.argmax(scores))
        if scores[i] > value:
            u, value, tangent = trial[i], float(scores[i]), None
        else:
            step /= 2.0
    named = [a for a, r in zip(axes, found[:3], strict=True) if r > 1.0 + BOUND_RTOL]
    if named:
        u = max(named, key=lambda a: float(ratios(a[None, :])[0]))
    sides = hull.half_widths(com, np.vstack((-u, u)))
    return MomentExcess(
        u,
        float(u @ second @ u),
        float(mass * sides[0] * sides[1]),
        float(sides.max()),
        "along",
        (float(sides[0]), float(sides[1])),
    )
