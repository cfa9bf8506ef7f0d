"""
Hard bounds of a link's mass distribution: a convex set that contains its geometry
(:class:`Hull`), and the most any mass inside it can have about an axis through its centre of
mass (:func:`moment_excess`). Outside them a declared value is impossible (IN023); the
forensics use them to tell a slip from a real but unusual part.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

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
        return cls(box_corners(part.bounds) if part.kind == "mesh" else _part_corners(part))

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


def box_corners(bounds: NDArray[np.float64]) -> NDArray[np.float64]:
    """(8, 3) corners of an axis-aligned box given as (2, 3) low/high."""
    low, high = np.asarray(bounds, dtype=np.float64)
    pick = np.array([[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)])
    return np.where(pick == 0, low, high)


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
        """``moment / bound``; beyond any bound when the bound is 0, unless the moment is not
        positive either (a zero or negative moment is IN010's, never an excess)."""
        if self.bound > 0:
            return self.moment / self.bound
        return math.inf if self.moment > 0 else 0.0


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
