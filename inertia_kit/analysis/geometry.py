"""
A link's geometry as solids: each ``<visual>``/``<collision>`` shape evaluated at unit density
in the link frame (:func:`evaluate_shape`), and the shapes of one kind together, their overlaps
counted once (:func:`evaluate_geometry`).

Geometry-derived values (DESIGN.md): the link's ``<collision>`` shapes, else its ``<visual>``
ones, each placed by its origin, meshes scaled as URDF says, at uniform density, overlaps of
primitives counted once (solid union).
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.bounds import Hull, box_corners
from inertia_kit.analysis.describe import describe_geometry
from inertia_kit.description import model
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.numbers import MIN_LENGTH

if TYPE_CHECKING:
    from inertia_kit.physics.meshes import MeshSolid
    from inertia_kit.physics.unions import Part


@dataclass(frozen=True, eq=False)
class Solid:
    """
    One ``<visual>``/``<collision>`` shape evaluated as a solid in the link frame.

    ``unit`` is its mass properties at 1 kg/m³ (so ``unit.mass`` is its volume); ``None``
    with ``problem`` set when the shape yields none: ``(kind, message)`` with kind one of
    ``invalid-number``, ``incomplete-geometry`` (a size absent), ``degenerate``,
    ``unknown-geometry``, ``mesh-not-found``, ``mesh-unreadable``, ``mesh-empty``.
    """

    shape: model.Shape
    unit: MassProperties | None
    corners: NDArray[np.float64] | None  # (8, 3) corners of its own bounding box, link frame
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
            return Hull.of_box(self.corners)
        return None


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

    def same_solids(self, other: Geometry) -> bool:
        """
        Whether ``other`` holds the very solids this does: the same mesh solids (one load,
        visual and collision naming one file at one scale) placed alike. What a judgment
        computes from one holds for the other; primitives are not compared (cheap to judge).
        """
        if len(self.solids) != len(other.solids) or not self.solids:
            return False
        return all(
            a.mesh is not None
            and a.mesh is b.mesh
            and a.part is None
            and b.part is None
            and a.unit is not None
            and b.unit is not None
            and a.unit.mass == b.unit.mass
            and np.array_equal(a.unit.com, b.unit.com)
            and np.array_equal(a.unit.inertia, b.unit.inertia)
            and a.corners is not None
            and b.corners is not None
            and np.array_equal(a.corners, b.corners)
            for a, b in zip(self.solids, other.solids, strict=True)
        )

    def at_mass(self, mass: float) -> MassProperties | None:
        """The geometry's mass properties for a total mass, at uniform density."""
        if self.unit is None or not self.unit.mass > 0 or not mass > 0:
            return None
        return self.unit.with_mass(mass)

    def describe(self) -> str:
        """``collision cylinder (r = 0.05 m, l = 0.3 m)`` or ``2 collision shapes (...)``."""
        parts = [describe_geometry(s.shape.geometry) for s in self.solids]
        if len(parts) == 1:
            return f"{self.kind} {parts[0]}"
        return f"{len(parts)} {self.kind} shapes ({'; '.join(parts)})"

    def name(self, kind: bool = True, possessive: bool = False) -> str:
        """
        The geometry named in a few words, for a one-line message (:meth:`describe` gives its
        dimensions): ``collision cylinder``, ``visual mesh``, ``2 collision shapes``; without
        ``kind``: ``cylinder``, ``2 shapes``; ``possessive``: ``cylinder's``, ``2 shapes'``.
        """
        what = f"{self.kind} " if kind and self.kind else ""
        if len(self.solids) == 1:
            shape = type(self.solids[0].shape.geometry).__name__.lower()
            shape = what + ("shape" if shape == "unknown" else shape)
            return f"{shape}'s" if possessive else shape
        return f"{len(self.solids)} {what}shapes" + ("'" if possessive else "")


MeshLoader = Callable[[str, tuple[float, float, float]], "MeshSolid"]


def default_mesh_loader(path: str, scale: tuple[float, float, float]) -> MeshSolid:
    """A mesh as a solid, through the on-disk cache."""
    # the on-disk cache: re-linting an unchanged mesh reads a 1 kB entry, not the mesh
    from inertia_kit.physics.mesh_cache import cached_mesh_solid

    return cached_mesh_solid(path, scale)


def _pose(origin: model.Origin) -> NDArray[np.float64] | None:
    from inertia_kit.physics.frames import transform

    if not isinstance(origin.xyz, tuple) or not isinstance(origin.rpy, tuple):
        return None
    return transform(origin.xyz, origin.rpy)


# the size attributes each of URDF's primitives (and the capsule) must have
SIZES: dict[type, tuple[str, ...]] = {
    model.Box: ("size",),
    model.Cylinder: ("radius", "length"),
    model.Sphere: ("radius",),
    model.Capsule: ("radius", "length"),
    model.Ellipsoid: ("radii",),
}


def absent_sizes(geometry: model.Geometry) -> tuple[str, ...]:
    """The size attributes the shape lacks (``radius`` of ``<sphere/>``), in URDF's order."""
    return tuple(name for name in SIZES.get(type(geometry), ()) if getattr(geometry, name) is None)


def _thin(values: tuple[float, ...]) -> str | None:
    """Why dimensions (m) make no solid: zero or negative, or thinner than an atom."""
    if not all(v > 0 for v in values):
        return "a dimension is zero or negative"
    thinnest = min(values)
    if thinnest < MIN_LENGTH:
        return (
            f"a dimension of {fmt(thinnest)} m is below {fmt(MIN_LENGTH)} m, the size of an "
            "atom: no solid is that thin"
        )
    return None


def _overflows(unit: MassProperties) -> bool:
    return not (
        np.isfinite(unit.mass) and np.isfinite(unit.com).all() and np.isfinite(unit.inertia).all()
    )


def _not_numeric(geometry: model.Geometry) -> str:
    """``its <cylinder length> is '1e-320' (IN004)``: the attributes that are not usable."""
    bad = [v for v in vars(geometry).values() if isinstance(v, model.Invalid)]
    if not bad:
        return "a dimension is not numeric"
    tag = type(geometry).__name__.lower()
    what = ", ".join(f"its <{tag} {v.attribute}> is {v.text!r}" for v in bad)
    return f"{what}, not a usable number (IN004)"


_OVERFLOW = "its volume or moments overflow double precision: the shape is far too large"


def _weighed(mesh: model.Mesh, solid: MeshSolid) -> MassProperties:
    """
    A mesh's unit mass properties in its own frame: as its format's engine weighs it when the
    format says how (MJCF's ``<mesh inertia>``: MuJoCo's ``legacy`` over-counts a non-convex
    mesh, ``convex`` takes its hull), else (URDF, and a ``shell``, which weighs the surface's
    area) the solid it encloses; that solid too when MuJoCo refuses the mesh (IN070 says so).
    """
    if mesh.inertia is not None and mesh.inertia != "shell" and mesh.path is not None:
        from inertia_kit.physics.mujoco_mesh_inertia import file_mass_properties

        weighed = file_mass_properties(mesh.path, mesh.inertia, mesh.scale)
        if weighed is not None:
            return weighed
    return solid.mass_properties(density=1.0)


def evaluate_shape(shape: model.Shape, load_mesh: MeshLoader = default_mesh_loader) -> Solid:
    """Evaluate one placed shape as a solid at unit density, in the link frame."""
    from inertia_kit.errors import MeshError
    from inertia_kit.physics.unions import Part

    pose = _pose(shape.origin)
    # an <origin> that is not a number (IN004's) hides no problem of the shape itself
    unplaced = Solid(shape, None, None, problem=("invalid-number", "its <origin> is not numeric"))
    geometry = shape.geometry
    if isinstance(geometry, model.Unknown):
        what = f"holds <{geometry.tag}>" if geometry.tag else "is empty"
        message = "there is no <geometry>" if geometry.absent else f"its <geometry> {what}"
        return Solid(shape, None, None, problem=("unknown-geometry", message))
    absent = absent_sizes(geometry)
    if absent:
        tag = type(geometry).__name__.lower()
        message = f"its <{tag}> has no {' and no '.join(absent)}"
        return Solid(shape, None, None, problem=("incomplete-geometry", message))
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
        # a usable scale on usable file coordinates can still overflow: checked below
        with np.errstate(over="ignore", invalid="ignore"):
            try:
                solid = load_mesh(geometry.path, scale)
            except MeshError as error:
                kind = {
                    "not-found": "mesh-not-found",
                    "empty": "mesh-empty",
                    "overflow": "degenerate",
                }.get(error.kind, "mesh-unreadable")
                return Solid(shape, None, None, problem=(kind, error.message))
            if pose is None:
                return unplaced
            unit = _weighed(geometry, solid).transformed(pose)
            corners = box_corners(solid.bounds) @ pose[:3, :3].T + pose[:3, 3]
        if _overflows(unit) or not np.isfinite(corners).all():
            return Solid(shape, None, None, problem=("degenerate", _OVERFLOW))
        thinnest = float(np.min(solid.bounds[1] - solid.bounds[0]))
        if thinnest < MIN_LENGTH or unit.mass < MIN_LENGTH**3:
            what = (
                f"it is {fmt(thinnest)} m thin, thinner than an atom (1e-10 m)"
                if thinnest < MIN_LENGTH
                else f"it encloses {fmt(unit.mass)} m³, less than an atom (1e-10 m) cubed"
            )
            return Solid(shape, None, None, problem=("mesh-empty", f"{what}: no solid"))
        return Solid(shape, unit, corners, mesh=solid)
    if isinstance(geometry, model.Box):
        size = geometry.size
        dims = size if isinstance(size, tuple) else None
        make = lambda d: Part.box(d, pose)  # noqa: E731
    elif isinstance(geometry, model.Cylinder):
        dims = (geometry.radius, geometry.length)
        make = lambda d: Part.cylinder(*d, pose)  # noqa: E731
    elif isinstance(geometry, model.Capsule):
        dims = (geometry.radius, geometry.length)
        make = lambda d: Part.capsule(*d, pose)  # noqa: E731
    elif isinstance(geometry, model.Ellipsoid):
        radii = geometry.radii
        dims = radii if isinstance(radii, tuple) else None
        make = lambda d: Part.ellipsoid(d, pose)  # noqa: E731
    else:  # Sphere
        dims = (geometry.radius,)
        make = lambda d: Part.sphere(d[0], pose)  # noqa: E731
    if dims is None or not all(isinstance(v, float) for v in dims):
        return Solid(shape, None, None, problem=("invalid-number", _not_numeric(geometry)))
    thin = _thin(dims)  # type: ignore[arg-type]
    if thin is not None:
        return Solid(shape, None, None, problem=("degenerate", thin))
    if pose is None:
        return unplaced
    part = make(dims)
    unit = part.mass_properties(density=1.0)
    corners = box_corners(part.bounds)
    if _overflows(unit) or not np.isfinite(corners).all():
        return Solid(shape, None, None, problem=("degenerate", _OVERFLOW))
    return Solid(shape, unit, corners, part=part)


def evaluate_geometry(
    shapes: tuple[model.Shape, ...],
    kind: str | None,
    load_mesh: MeshLoader = default_mesh_loader,
    *,
    summed: bool = False,
) -> Geometry:
    """
    The solids of ``shapes`` and, when all are usable, their union at unit density, or their
    sum when ``summed`` (as MuJoCo weighs an MJCF body's geoms: overlaps count twice).
    """
    solids = tuple(evaluate_shape(shape, load_mesh) for shape in shapes)
    if not solids or any(s.unit is None for s in solids):
        return Geometry(kind, solids, None)
    if len(solids) == 1:
        return Geometry(kind, solids, solids[0].unit)
    if summed:
        return Geometry(kind, solids, sum(s.unit for s in solids))  # type: ignore[misc]
    parts = [s.part for s in solids if s.part is not None]
    meshes = [s.unit for s in solids if s.part is None]
    overlap = 0.0
    unit = None
    if len(parts) > 1:
        # the on-disk cache, as for meshes: re-linting skips manifold3d for overlapping shapes
        from inertia_kit.physics.union_cache import cached_union

        try:
            result = cached_union(parts, density=1.0)
            unit, overlap = result.mass_properties, result.overlap_volume
        except ValueError:
            unit = None
    if unit is None and parts:
        unit = sum(s.part.mass_properties(density=1.0) for s in solids if s.part is not None)
    # meshes are added whole: their overlaps with other shapes are not removed
    total = sum(meshes, unit) if unit is not None else sum(meshes)
    return Geometry(kind, solids, total, overlap)
