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
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from inertia_kit import model
from inertia_kit.mass import MassProperties

if TYPE_CHECKING:
    from inertia_kit.meshes import MeshSolid
    from inertia_kit.unions import Part


def _finite(value: model.Number) -> float | None:
    return value if isinstance(value, float) else None


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
    from inertia_kit.text import fmt

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
    from inertia_kit.meshes import mesh_solid

    return mesh_solid(path, scale)


def shape_text(geometry: model.Geometry) -> str:
    """A geometry with its dimensions and units, for messages."""
    from inertia_kit.text import fmt

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
    from inertia_kit.frames import transform

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
    from inertia_kit.unions import Part

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
        from inertia_kit.unions import union

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

    @property
    def geometry(self) -> Geometry:
        """The geometry mass comes from: collision shapes, else visual ones."""
        if self.link.collisions:
            return self.collision
        if self.link.visuals:
            return self.visual
        return Geometry(None, (), None)

    @property
    def expected(self) -> MassProperties | None:
        """The geometry's mass properties for the declared mass (uniform density)."""
        if self.declared is None:
            return None
        return self.geometry.at_mass(self.declared.mass)


class RobotAnalysis:
    """All links of a robot, with tree relations and fixed-joint groups."""

    def __init__(self, robot: model.Robot, load_mesh: MeshLoader = _default_mesh_loader):
        self.robot = robot
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

    def group_mass(self, name: str) -> float:
        """Total declared mass of ``name``'s fixed-joint group (finite positive masses only)."""
        total = 0.0
        for link in self.group_of(name):
            inertial = link.link.inertial
            mass = None if inertial is None else inertial.mass
            if isinstance(mass, float) and math.isfinite(mass) and mass > 0:
                total += mass
        return total


def analyse(robot: model.Robot, load_mesh: MeshLoader = _default_mesh_loader) -> RobotAnalysis:
    return RobotAnalysis(robot, load_mesh)
