"""
Mass properties of the solid union of overlapping parts at uniform density.

A link's collision shapes may overlap, and summing their mass properties counts the overlap
twice. :func:`union` counts it once:

``union = Σ exact_i - (Σ tessellated_i - tessellated_union)``

One overlap has a closed form and is taken exactly, before any tessellation: a cylinder with a
sphere of its radius centred on each end cap is a capsule (robot descriptions build capsules
so, URDF having none: franka_ros' self-collision links), and the three parts are counted as
that capsule.

The bracket is the volume integral of the overlaps, computed on tessellations with manifold3d;
for two parts it is the integral of their intersection, which manifold3d gives directly (fewer
triangles to integrate than the union and both parts, and no difference of large sums).
Each tessellation is built volume-preserving, so its error averages out over every facet, and
outside the overlaps the tessellated terms cancel exactly: the result is exact wherever parts
do not overlap and carries only the (second-order) tessellation error of the overlap regions.
Parts whose bounding boxes touch no other part's never reach manifold3d; the meshes that do
pass through :mod:`.manifolds`.

manifold3d is imported inside the functions that use it, so importing this module stays cheap;
so are :mod:`.manifolds` and :mod:`.polyhedra`, which a link of primitives alone never needs.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from inertia_kit.physics import primitives
from inertia_kit.physics.frames import as_transform, inverse
from inertia_kit.physics.mass import MassProperties, second_moment_from_inertia
from inertia_kit.physics.primitives import body_mass
from inertia_kit.physics.tessellate import half_extents, primitive_mesh

if TYPE_CHECKING:
    import manifold3d

    from inertia_kit.physics.volume_moments import VolumeMoments

# segments around each curved primitive's axis: at 96 the overlap of two cylinders or of a
# cylinder and a sphere is within 1e-5 of the closed form, for ~10 ms per union
DEFAULT_SEGMENTS = 96

# an overlap of tessellations below this fraction of their volume is round-off, not overlap
OVERLAP_NOISE = 1e-10


def _readonly(array: NDArray) -> NDArray:
    array.flags.writeable = False
    return array


@dataclass(frozen=True, eq=False)
class Part:
    """
    One solid placed in a parent frame (a link frame): its exact mass properties and how to
    tessellate it.

    Build parts with the constructors :meth:`box`, :meth:`cylinder`, :meth:`sphere`,
    :meth:`capsule`, :meth:`ellipsoid` and :meth:`mesh`, which check their dimensions.

    Attributes
    ----------
    kind : str
      ``box``, ``cylinder``, ``sphere``, ``capsule``, ``ellipsoid`` or ``mesh``.
    dimensions : tuple of float
      The constructor's lengths, m: box ``size`` (x, y, z); cylinder and capsule
      ``(radius, length)``; sphere ``(radius,)``; ellipsoid ``radii`` (a, b, c); mesh ``()``.
    unit : MassProperties
      Exact mass properties at unit density (1 kg/m³, so ``mass`` is the volume in m³), in
      the part's own frame.
    pose : (4, 4) float
      Rigid transform from the part's frame to the parent frame (a URDF ``<origin>``).
    vertices : (m, 3) float or None
      Mesh vertices in the part's frame, m (meshes only).
    faces : (n, 3) int or None
      Vertex indices of each triangle, counter-clockwise seen from outside (meshes only).
    """

    kind: str
    dimensions: tuple[float, ...]
    unit: MassProperties
    pose: NDArray[np.float64] = field(default_factory=lambda: np.eye(4))
    vertices: NDArray[np.float64] | None = field(default=None, repr=False)
    faces: NDArray[np.int64] | None = field(default=None, repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "pose", _readonly(as_transform(self.pose).copy()))

    # --- constructors -------------------------------------------------------------------

    @classmethod
    def box(cls, size: ArrayLike, pose: ArrayLike | None = None) -> Part:
        """Box centred on its frame; ``size`` (3,) full edge lengths along x, y, z, m."""
        unit = primitives.box(size, density=1.0)
        return cls("box", _lengths(size), unit, _pose(pose))

    @classmethod
    def cylinder(cls, radius: float, length: float, pose: ArrayLike | None = None) -> Part:
        """Cylinder along z centred on its frame; ``radius`` and ``length`` in m."""
        unit = primitives.cylinder(radius, length, density=1.0)
        return cls("cylinder", (float(radius), float(length)), unit, _pose(pose))

    @classmethod
    def sphere(cls, radius: float, pose: ArrayLike | None = None) -> Part:
        """Sphere centred on its frame; ``radius`` in m."""
        unit = primitives.sphere(radius, density=1.0)
        return cls("sphere", (float(radius),), unit, _pose(pose))

    @classmethod
    def capsule(cls, radius: float, length: float, pose: ArrayLike | None = None) -> Part:
        """Capsule along z; ``length`` is the cylinder between the hemisphere centres, m."""
        unit = primitives.capsule(radius, length, density=1.0)
        return cls("capsule", (float(radius), float(length)), unit, _pose(pose))

    @classmethod
    def ellipsoid(cls, radii: ArrayLike, pose: ArrayLike | None = None) -> Part:
        """Ellipsoid centred on its frame; ``radii`` (3,) semi-axes along x, y, z, m."""
        unit = primitives.ellipsoid(radii, density=1.0)
        return cls("ellipsoid", _lengths(radii), unit, _pose(pose))

    @classmethod
    def mesh(
        cls, vertices: ArrayLike, faces: ArrayLike | None = None, pose: ArrayLike | None = None
    ) -> Part:
        """
        A solid bounded by a closed triangle mesh.

        Parameters
        ----------
        vertices : (m, 3) float, or (n, 3, 3) float when ``faces`` is None
          Vertex coordinates in the part's frame, m; without ``faces``, a triangle soup whose
          triangles share vertices by exact coordinates.
        faces : (n, 3) int, optional
          Vertex indices of each triangle, counter-clockwise seen from outside.
        pose : (4, 4) float, optional
          Part frame to parent frame; default identity.

        Raises
        ------
        ValueError
          On bad shapes, non-finite coordinates, a surface that is not closed even after
          manifold3d merges its open edges, or one that bounds no positive volume.
        """
        from inertia_kit.physics.manifolds import closed_mesh
        from inertia_kit.physics.polyhedra import integrate

        points, triangles = closed_mesh(vertices, faces)
        moments = integrate(points[triangles]).moments
        if not moments.volume > 0:
            raise ValueError(
                f"mesh bounds no positive volume ({moments.volume:.6g} m³): "
                "its triangles are wound inside-out"
            )
        unit = moments.mass_properties(density=1.0)
        return cls("mesh", (), unit, _pose(pose), _readonly(points), _readonly(triangles))

    # --- derived values -----------------------------------------------------------------

    @property
    def volume(self) -> float:
        """Exact volume, m³."""
        return self.unit.mass

    def mass_properties(
        self, *, density: float | None = None, mass: float | None = None
    ) -> MassProperties:
        """Exact mass properties in the parent frame (exactly one of ``density``, ``mass``)."""
        return self.unit.with_mass(body_mass(self.volume, density, mass)).transformed(self.pose)

    def transformed(self, matrix: ArrayLike) -> Part:
        """The same part in a grandparent frame: ``matrix`` (4, 4) maps parent to grandparent."""
        return replace(self, pose=as_transform(matrix) @ self.pose)

    @property
    def bounds(self) -> NDArray[np.float64]:
        """(2, 3) lowest and highest corner of a box containing the part in the parent frame, m."""
        if self.vertices is not None:
            points = self.vertices
        else:
            half = half_extents(self.kind, self.dimensions)
            signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
            points = signs * half
        placed = points @ self.pose[:3, :3].T + self.pose[:3, 3]
        return np.array([placed.min(axis=0), placed.max(axis=0)])

    def tessellation(
        self, segments: int = DEFAULT_SEGMENTS
    ) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
        """
        A closed triangle mesh of the part in the parent frame, with the part's exact volume.

        Curved surfaces are polygons scaled so that every cross-section keeps its exact area
        (and the meridian arcs their exact area moment): the volume is exact and the facet
        error averages out locally. Boxes and meshes are reproduced exactly.

        Parameters
        ----------
        segments : int
          Segments around each curved primitive's axis (at least 8); meridians get a quarter
          as many per quarter circle.

        Returns
        -------
        vertices : (m, 3) float
          m
        faces : (n, 3) int
          Counter-clockwise seen from outside.
        """
        if self.vertices is not None:
            points, faces = self.vertices, self.faces
        else:
            points, faces = primitive_mesh(self.kind, self.dimensions, _segments(segments))
        return points @ self.pose[:3, :3].T + self.pose[:3, 3], faces  # type: ignore[return-value]

    def to_manifold(self, segments: int = DEFAULT_SEGMENTS) -> manifold3d.Manifold:
        """:meth:`tessellation` as a ``manifold3d.Manifold``."""
        from inertia_kit.physics.manifolds import as_manifold

        return as_manifold(*self.tessellation(segments))


@dataclass(frozen=True)
class UnionResult:
    """
    The solid union of parts at uniform density.

    Attributes
    ----------
    mass_properties : MassProperties
      Of the union, in the parts' parent frame.
    volume : float
      Union volume, m³.
    parts_volume : float
      Sum of the parts' exact volumes, m³.
    overlap_volume : float
      ``parts_volume - volume``: what a plain sum counts twice (or more), m³.
    exact : bool
      True when no parts overlap (or there is one), or only as a capsule's cylinder and end
      spheres do: the value is exact, free of tessellation error.
    """

    mass_properties: MassProperties
    volume: float
    parts_volume: float
    overlap_volume: float
    exact: bool


def union(
    parts: Iterable[Part],
    *,
    density: float | None = None,
    mass: float | None = None,
    segments: int = DEFAULT_SEGMENTS,
) -> UnionResult:
    """
    Mass properties of the solid union of ``parts`` at uniform density.

    Parameters
    ----------
    parts : iterable of Part
      In one parent frame.
    density : float, optional
      kg/m³.
    mass : float, optional
      kg, spread uniformly over the union. Give exactly one of ``density`` and ``mass``.
    segments : int
      Tessellation of curved primitives inside overlaps (see :meth:`Part.tessellation`).

    Returns
    -------
    UnionResult
      Exact when no parts overlap (``exact``); otherwise the error is that of the tessellated
      overlap regions only: below 1e-4 of the union's mass and inertia at the default
      segments, 5e-5 for two coincident ellipsoids, ~1e-6 for typical partial overlaps.

    Raises
    ------
    ValueError
      No parts, not exactly one of ``density`` and ``mass``, a non-positive result, too few
      segments, or manifold3d failing on the union.
    TypeError
      An item of ``parts`` is not a :class:`Part`.
    """
    parts = tuple(parts)
    if not parts:
        raise ValueError("union of no parts: give at least one Part")
    for part in parts:
        if not isinstance(part, Part):
            raise TypeError(f"union takes Part values, got {type(part).__name__}")
    if (density is None) == (mass is None):
        raise ValueError("give exactly one of density (kg/m³) or mass (kg)")
    segments = _segments(segments)

    parts_volume = float(sum(part.volume for part in parts))
    parts = capsules(parts)
    summed = sum(part.unit.transformed(part.pose) for part in parts)
    unit, overlap = summed, parts_volume - float(sum(part.volume for part in parts))
    # parts whose boxes meet no other box add the same tessellation to both sides: skip them
    exact = True
    group = overlapping([part.bounds for part in parts])
    if group:
        corrected = _overlap_corrected(summed, [parts[i] for i in group], segments)
        if corrected is not None:
            unit, tessellated = corrected
            overlap += tessellated
            exact = False
    volume = parts_volume if overlap == 0.0 else unit.mass
    properties = unit.with_mass(body_mass(volume, density, mass))
    return UnionResult(properties, volume, parts_volume, overlap, exact=exact)


#: how near a sphere must be to a cylinder's end cap's centre, and its radius to the
#: cylinder's, relative to the cylinder's size, to make a capsule with it: rounding, not design
CAPSULE_RTOL = 1e-9


def capsules(parts: tuple[Part, ...]) -> tuple[Part, ...]:
    """
    ``parts`` with every cylinder that has a sphere of its radius centred on each end cap
    replaced, with those two spheres, by the capsule they make (its exact mass properties, in
    the cylinder's frame); the other parts as they are, in order.
    """
    spheres = [i for i, part in enumerate(parts) if part.kind == "sphere"]
    if len(spheres) < 2:
        return parts
    used: set[int] = set()
    replaced: dict[int, Part] = {}
    for index, part in enumerate(parts):
        if part.kind != "cylinder":
            continue
        radius, length = part.dimensions
        tolerance = CAPSULE_RTOL * (radius + length)
        to_part = inverse(part.pose)
        ends = []
        for end in (0.5 * length, -0.5 * length):
            for i in spheres:
                if i in used or i in ends:
                    continue
                centre = to_part[:3, :3] @ parts[i].pose[:3, 3] + to_part[:3, 3]
                if abs(parts[i].dimensions[0] - radius) <= tolerance and np.all(
                    np.abs(centre - (0.0, 0.0, end)) <= tolerance
                ):
                    ends.append(i)
                    break
        if len(ends) == 2:
            used.update(ends)
            replaced[index] = Part.capsule(radius, length, part.pose)
    if not replaced:
        return parts
    return tuple(replaced.get(i, part) for i, part in enumerate(parts) if i not in used)


# --- the overlap correction -------------------------------------------------------------


def overlapping(bounds: list[NDArray[np.float64]]) -> list[int]:
    """Indices of the boxes whose interior meets another box's interior."""
    low = np.array([b[0] for b in bounds])
    high = np.array([b[1] for b in bounds])
    meets = np.all((low[:, None] < high[None, :]) & (low[None, :] < high[:, None]), axis=2)
    np.fill_diagonal(meets, False)
    return [int(i) for i in np.flatnonzero(meets.any(axis=1))]


def _overlap_corrected(
    summed: MassProperties, group: list[Part], segments: int
) -> tuple[MassProperties, float] | None:
    """
    ``summed - (Σ tessellated_i - tessellated_union)`` over the parts of ``group``, at unit
    density, and the overlap volume; None when the tessellations do not overlap.
    """
    import manifold3d

    from inertia_kit.physics.manifolds import manifold_moments

    corners = np.array([part.bounds for part in group])
    origin = 0.5 * (corners[:, 0].min(axis=0) + corners[:, 1].max(axis=0))
    solids = [part.to_manifold(segments) for part in group]
    if len(solids) == 2:  # Σ tessellated_i - tessellated_union is their intersection
        shared = manifold_moments(
            _boolean(solids, manifold3d.OpType.Intersect, "intersect"), origin
        )
        tessellated = float(sum(part.volume for part in group))  # tessellations keep volume
        overlap, terms = shared.volume, [shared.negated()]
    else:
        pieces = [manifold_moments(solid, origin) for solid in solids]
        merged = manifold_moments(_boolean(solids, manifold3d.OpType.Add, "unite"), origin)
        tessellated = sum(piece.volume for piece in pieces)
        overlap, terms = tessellated - merged.volume, [merged, *(p.negated() for p in pieces)]
    if overlap <= OVERLAP_NOISE * tessellated:
        return None
    total = _as_moments(summed, origin)
    for term in terms:  # in this order: the same sums, to the bit, as each branch had
        total = total + term
    return total.mass_properties(density=1.0), float(overlap)


def _boolean(
    solids: list[manifold3d.Manifold], operation: manifold3d.OpType, verb: str
) -> manifold3d.Manifold:
    import manifold3d

    result = manifold3d.Manifold.batch_boolean(solids, operation)
    if result.status() != manifold3d.Error.NoError:
        raise ValueError(f"manifold3d failed to {verb} the parts: {result.status().name}")
    return result


def _as_moments(unit: MassProperties, origin: NDArray[np.float64]) -> VolumeMoments:
    """Volume integrals about ``origin`` of a body at unit density (mass = volume)."""
    from inertia_kit.physics.volume_moments import VolumeMoments

    offset = unit.com - origin
    second = second_moment_from_inertia(unit.inertia) + unit.mass * np.outer(offset, offset)
    return VolumeMoments(unit.mass, unit.mass * offset, second, origin)


# --- input checks -----------------------------------------------------------------------


def _pose(pose: ArrayLike | None) -> NDArray[np.float64]:
    return np.eye(4) if pose is None else as_transform(pose)


def _lengths(values: ArrayLike) -> tuple[float, ...]:
    return tuple(float(v) for v in np.asarray(values, dtype=np.float64))


def _segments(segments: int) -> int:
    if isinstance(segments, bool) or int(segments) != segments or segments < 8:
        raise ValueError(f"segments must be an integer of at least 8, got {segments!r}")
    return int(segments)
