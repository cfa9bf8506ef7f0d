"""
What Drake's URDF parser and ``MultibodyPlant`` do with each link (Drake 1.51.1; the messages
are quoted as its PyPI wheel prints them and checked against it in
``tests/engines/test_drake_matrix.py``).

In Drake's order: the parser reads the links in document order (each link's ``<inertial>``, then
its visuals, then its collisions), then the joints; the first error stops it (``refuses``), a
warning lets it go on (``changes``: an invalid inertia replaced by a water-density sphere, the
``<inertial>`` of the link ``world`` ignored, a ``floating`` joint left out). With a
``SceneGraph`` (as for any simulation) each collision mesh becomes its convex hull, which Drake
computes for ``.obj``, ``.vtk`` and ``.gltf`` files only. Last, forward dynamics (the first
simulation step) runs the articulated-body algorithm and stops at a joint whose outboard bodies
have no inertia along its motion (``engines/articulated.py``).

Assumptions, as a Drake user loads a robot: the root link is welded to the world
(``plant.WeldFrames``), unless it is the link ``world``; the package map resolves the
``package://`` URIs inertia-kit resolves.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterator
from dataclasses import dataclass, replace
from pathlib import PurePosixPath

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
from inertia_kit.description import model
from inertia_kit.engines import articulated
from inertia_kit.engines import drake_reading as reading
from inertia_kit.engines.lumping import written_tensor
from inertia_kit.engines.vocabulary import Event, Verdict, event
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.frames import rpy_matrix, transform

ENGINE = "drake"
VERSION = reading.VERSION
WATER = 1000.0  # kg/m³: detail_common.cc kPlausibleDensity
PROXIMITY_MESHES = (".obj", ".vtk", ".gltf")
ROTATES = {"revolute": True, "continuous": True, "prismatic": False, "planar": True}
TRANSLATES = {"revolute": False, "continuous": False, "prismatic": True, "planar": True}
CUSTOM_JOINTS = ("ball", "screw", "universal", "curvilinear")  # only as <drake:joint>
KNOWN_JOINTS = ("revolute", "continuous", "fixed", "prismatic", "floating", "planar")


def plausible_sphere(mass: float) -> tuple[float, float, float]:
    """
    The solid sphere Drake's ``ParseSpatialInertia`` substitutes for invalid values: mass (the
    declared one if finite and > 0, else 1 kg), radius at 1000 kg/m³, and its moment 2/5 m r².
    """
    m = mass if math.isfinite(mass) and mass > 0 else 1.0
    radius = (3.0 / (4.0 * math.pi) * (m / WATER)) ** (1.0 / 3.0)
    return m, radius, 0.4 * m * radius**2


# --- reading a link's <inertial> as Drake does ---------------------------------------------------


@dataclass(frozen=True)
class Inertia:
    """
    What Drake makes of one ``<inertial>``: ``kind`` is ``massless`` (mass and tensor 0),
    ``valid``, ``sphere`` (replaced) or ``refused`` (``message`` says why, at ``source``).
    ``mass``, ``xyz``, ``rpy`` and ``tensor`` are the values as Drake read them.
    """

    kind: str
    mass: float = 0.0
    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)
    tensor: NDArray[np.float64] | None = None
    message: str | None = None
    source: model.Source | None = None


class _Refused(Exception):
    def __init__(self, message: str, source: model.Source | None):
        super().__init__(message)
        self.message, self.source = message, source


def _scalar(value: model.Number, attribute: str, source: model.Source | None) -> float:
    """A scalar attribute as Drake reads it: a missing one is 0."""
    if value is None:
        return 0.0
    if isinstance(value, model.Invalid):
        numbers = reading.read_numbers(value.text)
        if len(numbers) != 1:
            raise _Refused(reading.scalar_error(attribute, value.text), value.source)
        return numbers[0]
    return float(value)


def _vector(value: model.Vector, attribute: str) -> tuple[float, float, float] | None:
    """A vector attribute as Drake reads it (``None`` when absent)."""
    if value is None:
        return None
    if isinstance(value, model.Invalid):
        numbers = reading.read_numbers(value.text)
        if len(numbers) != 3:
            raise _Refused(reading.vector_error(attribute, value.text), value.source)
        return (numbers[0], numbers[1], numbers[2])
    return value


def _origin(origin: model.Origin) -> tuple[tuple[float, ...], tuple[float, ...]]:
    xyz = _vector(origin.xyz, "xyz") or (0.0, 0.0, 0.0)
    rpy = _vector(origin.rpy, "rpy") or (0.0, 0.0, 0.0)
    return xyz, rpy


def read_inertial(inertial: model.Inertial) -> Inertia:
    """``UrdfParser::ExtractSpatialInertiaAboutBoExpressedInB`` and ``ParseSpatialInertia``."""
    try:
        xyz, rpy = _origin(inertial.origin)
        mass = _scalar(inertial.mass, "value", inertial.mass_source)
        values = [
            _scalar(v, name, inertial.inertia_source)
            for name, v in inertial.tensor_values().items()
        ]
    except _Refused as refused:
        return Inertia("refused", message=refused.message, source=refused.source)
    tensor = written_tensor(values)
    plausible = mass if math.isfinite(mass) and mass > 0 else 1.0
    if 3.0 / (4.0 * math.pi) * (plausible / WATER) == 0.0:  # the sphere is made first, always
        return Inertia("refused", message=reading.ZERO_RADIUS, source=inertial.source)
    read = Inertia("valid", mass, xyz, rpy, tensor)  # type: ignore[arg-type]
    if not reading.could_be_physically_valid(tensor):
        return replace(read, kind="sphere", message=reading.invalid_inertia_message(tensor))
    if mass == 0 and not tensor.any():
        return replace(read, kind="massless")
    if not mass > 0:
        return replace(read, kind="sphere", message=reading.NON_POSITIVE_MASS)
    return read


# --- events ----------------------------------------------------------------------------------


def events(robot: RobotAnalysis) -> Iterator[Event]:
    """
    In Drake's order: per link ``number``/``tiny`` (the ``<inertial>`` is refused), ``world``
    (its ``<inertial>`` ignored), ``sphere`` (replaced), ``geometry``/``mesh-missing``/``mesh``
    (a shape or mesh refused); per joint ``joint`` (refused) or ``floating`` (left out); then
    ``singular`` (forward dynamics fails). Refusals carry ``first``: the one Drake reports.
    """
    found = [*_link_events(robot), *_joint_events(robot), *_singular_events(robot)]
    first = next((e for e in found if e.verdict is Verdict.REFUSES), None)
    for found_event in found:
        if found_event.verdict is Verdict.REFUSES:
            facts = {**found_event.facts, "first": found_event is first}
            found_event = replace(found_event, facts=facts)
        yield found_event


def _link_events(robot: RobotAnalysis) -> Iterator[Event]:
    for link in robot.links:
        inertial = link.link.inertial
        if inertial is not None and link.name == model.WORLD:
            yield event(
                ENGINE,
                Verdict.CHANGES,
                "world",
                "ignores the <inertial> of link `world`: the world body has no mass",
                'A URDF file declared the "world" link and then attempted to assign mass '
                "properties (via the <inertial> tag). Only geometries, <collision> and <visual>, "
                "can be assigned to the world link. The <inertial> tag is being ignored.",
                link.link.source,
                link=link.name,
            )
        elif inertial is not None:
            yield from _inertial_events(link.name, inertial)
        for shape in (*link.link.visuals, *link.link.collisions):
            yield from _shape_events(link.name, shape)


def _inertial_events(link: str, inertial: model.Inertial) -> Iterator[Event]:
    read = read_inertial(inertial)
    if read.kind == "refused":
        yield event(
            ENGINE,
            Verdict.REFUSES,
            "number" if read.message != reading.ZERO_RADIUS else "tiny",
            f"refuses the model at the <inertial> of link `{link}`",
            read.message,
            read.source or inertial.source,
            link=link,
        )
    elif read.kind == "sphere":
        m, radius, moment = plausible_sphere(read.mass)
        yield event(
            ENGINE,
            Verdict.CHANGES,
            "sphere",
            f"replaces the inertia of link `{link}` by a solid sphere of {fmt(WATER)} kg/m³: "
            f"{fmt(m)} kg, radius {fmt(radius, 4)} m, moment {fmt(moment, 4)} kg·m² about "
            "each axis",
            reading.flatten(read.message or ""),
            inertial.source,
            link=link,
            mass=m,
            radius=radius,
            ixx=moment,
            iyy=moment,
            izz=moment,
        )


_SHAPES = {
    model.Box: "Box",
    model.Cylinder: "Cylinder",
    model.Sphere: "Sphere",
    model.Capsule: "Capsule",
}


def _shape_events(link: str, shape: model.Shape) -> Iterator[Event]:
    """``ParseVisual``/``ParseCollision``: the first refusal of one shape, if any."""
    geometry = shape.geometry
    where = f"the {shape.kind} {_describe(geometry)} of link `{link}`"
    try:
        refusal = _shape_refusal(link, shape)
    except _Refused as refused:
        refusal = ("geometry", refused.message, refused.source)
    if refusal is not None:
        kind, message, source = refusal
        what = f"refuses the model at {where}"
        if kind == "mesh-missing" and message is None:
            what = (
                f"refuses the model: {where} is not found (Drake's words depend on the "
                "packages its package map holds)"
            )
        yield event(
            ENGINE, Verdict.REFUSES, kind, what, message, source or geometry.source, link=link
        )
        return
    if shape.kind != "collision" or not isinstance(geometry, model.Mesh) or not geometry.path:
        return
    suffix = PurePosixPath(geometry.path).suffix.lower()
    if suffix in PROXIMITY_MESHES:
        return
    path = os.path.abspath(geometry.path)
    yield event(
        ENGINE,
        Verdict.REFUSES,
        "mesh",
        f"refuses the {suffix or 'extension-less'} collision mesh of link `{link}` (it "
        "computes a collision mesh's convex hull from .obj, .vtk or .gltf only)",
        f"MakeConvexHull only applies to .obj, .vtk, and .gltf meshes; unsupported extension "
        f"'{suffix}' for geometry data: {path}.",
        geometry.source,
        link=link,
        mesh=path,
    )


def _describe(geometry: model.Geometry) -> str:
    if isinstance(geometry, model.Mesh):
        return f"mesh `{geometry.filename}`"
    if isinstance(geometry, model.Unknown):
        return "geometry"
    return f"<{type(geometry).__name__.lower()}>"


Refusal = tuple[str, str | None, model.Source | None]  # kind, Drake's message, where


def _shape_refusal(link: str, shape: model.Shape) -> Refusal | None:
    geometry = shape.geometry
    if isinstance(geometry, model.Unknown) and geometry.source == shape.source:
        if shape.kind == "visual":
            return "geometry", f"Link {link} has a visual element without geometry.", shape.source
        message = f"Link '{link}' has a collision element without geometry"
        return "geometry", message, shape.source
    _origin(shape.origin)
    if isinstance(geometry, model.Unknown):
        if geometry.tag in ("drake:capsule", "drake:ellipsoid"):
            return None  # Drake's own shapes (inertia-kit does not read them)
        message = "Warning: geometry element does not have a recognizable shape type"
        return "geometry", message, geometry.source
    if isinstance(geometry, model.Mesh):
        return _mesh_refusal(geometry)
    name = _SHAPES[type(geometry)]
    dimensions: list[tuple[str, float]] = []
    if isinstance(geometry, model.Box):
        size = _vector(geometry.size, "size")
        if size is None:
            return "geometry", "Missing box attribute: size", geometry.source
        dimensions = list(zip(("width", "depth", "height"), size, strict=True))
    else:
        attributes = ("radius",) if isinstance(geometry, model.Sphere) else ("radius", "length")
        for attribute in attributes:
            value = getattr(geometry, attribute)
            if value is None:
                message = f"Missing {name.lower()} attribute: {attribute}"
                return "geometry", message, geometry.source
            dimensions.append((attribute, _scalar(value, attribute, geometry.source)))
    for dimension, value in dimensions:
        ok = value >= 0 if name == "Sphere" else value > 0
        if not (math.isfinite(value) and ok):
            return "geometry", reading.shape_error(name, dimension, value), None
    return None


def _mesh_refusal(mesh: model.Mesh) -> Refusal | None:
    """``ParseMesh``: the file (``ResolveUri``), then the scale (``ThrowForBadScale``)."""
    if not mesh.filename:
        return None
    if mesh.path is None:
        return "mesh-missing", _missing_mesh(mesh), mesh.source
    scale = mesh.scale
    if isinstance(scale, model.Invalid):
        numbers = reading.read_numbers(scale.text)
        if " " in scale.text:
            if len(numbers) != 3:
                return "geometry", reading.vector_error("scale", scale.text), None
        elif len(numbers) != 1:
            return "geometry", reading.scalar_error("scale", scale.text), mesh.source
        scale = tuple(numbers) if len(numbers) == 3 else (numbers[0],) * 3
    values = (1.0, 1.0, 1.0) if scale is None else scale
    if not all(math.isfinite(v) and abs(v) >= 1e-8 for v in values):
        shown = reading.fmt_eigen_row(values)
        return "geometry", f"Mesh |scale| cannot be < 1e-8 on any axis, given [{shown}].", None
    return None


def _missing_mesh(mesh: model.Mesh) -> str | None:
    """``ResolveUri``'s error for a file that is not there (the package map's when it is one)."""
    uri = mesh.filename
    scheme, separator, rest = uri.partition("://")
    if separator and scheme == "file":
        path = "/" + rest.partition("/")[2].lstrip("/")
    elif separator:
        return None  # package:// and model://: the words depend on the user's package map
    elif uri.startswith("/"):
        path = uri
    else:
        root = os.path.dirname(os.path.abspath(mesh.source.path))
        path = f"{root}/{uri}"
    return f"URI '{uri}' resolved to '{path}' which does not exist."


def _joint_events(robot: RobotAnalysis) -> Iterator[Event]:
    known = {link.name for link in robot.links}
    for joint in robot.robot.joints:
        if not joint.name or joint.parent not in known or joint.child not in known:
            continue  # a broken tree: IN040
        message = None
        try:
            _origin(joint.origin)
            message = _axis_refusal(joint)
        except _Refused as refused:
            message = refused.message
        if message is None and joint.type in CUSTOM_JOINTS:
            message = (
                f"Joint {joint.name} of type {joint.type} is a custom joint type, and should be "
                "a <drake:joint>"
            )
        elif message is None and joint.type not in KNOWN_JOINTS:
            message = f"Joint '{joint.name}' has unrecognized type: '{joint.type}'"
        if message is not None:
            yield event(
                ENGINE,
                Verdict.REFUSES,
                "joint",
                f"refuses the model at joint `{joint.name}`",
                message,
                joint.source,
                link=joint.child,
                joint=joint.name,
            )
        elif joint.type == "floating":
            yield event(
                ENGINE,
                Verdict.CHANGES,
                "floating",
                f"leaves out the floating joint `{joint.name}`: link `{joint.child}` becomes a "
                "free body, moved by nothing but gravity and contact",
                f"Joint '{joint.name}' specified as type floating which is not supported by "
                f"MultibodyPlant.  Leaving '{joint.child}' as a free body.",
                joint.source,
                link=joint.child,
                joint=joint.name,
            )


def _axis_refusal(joint: model.Joint) -> str | None:
    if joint.type in ("fixed", "floating", "ball") or joint.axis is None:
        return None
    axis = _vector(joint.axis, "xyz")
    if axis is not None and math.hypot(*axis) < 1e-8:
        return f"Joint '{joint.name}' axis is zero.  Don't do that."
    return None


# --- forward dynamics ------------------------------------------------------------------------


def _spatial_inertia(link: LinkAnalysis) -> NDArray[np.float64]:
    """The body's spatial inertia about its origin in its own axes, as Drake has it."""
    inertial = link.link.inertial
    if inertial is None or link.name == model.WORLD:
        return np.zeros((6, 6))
    read = read_inertial(inertial)
    if read.kind == "massless":
        return np.zeros((6, 6))
    if read.kind == "refused" or read.tensor is None:
        return np.eye(6)  # unknown until the file is fixed: taken as sound
    com = np.array(read.xyz, dtype=np.float64)
    if read.kind == "sphere":
        m, _, moment = plausible_sphere(read.mass)
        return articulated.spatial_inertia(m, com, moment * np.eye(3))
    rotation = rpy_matrix(read.rpy)
    central = rotation @ read.tensor @ rotation.T
    return articulated.spatial_inertia(read.mass, com, central)


def _motion(joint: model.Joint | None) -> str:
    if joint is None or joint.type == "fixed":
        return "fixed"
    if joint.type in ("revolute", "continuous"):
        return "revolute"
    if joint.type in ("prismatic", "planar"):
        return joint.type
    if joint.type == "floating":
        return "free"
    return "fixed"  # a joint Drake refuses: nothing to say about its dynamics


def _bodies(robot: RobotAnalysis) -> list[articulated.Body]:
    """Drake's bodies at rest, in world axes; the root welded to the world."""
    poses: dict[str, NDArray[np.float64]] = {}
    bodies: list[articulated.Body] = []
    stack = [link for link in reversed(robot.links) if link.parent is None]
    for link in robot.links:  # links of a floating joint start a tree of their own
        if link.parent is not None and link.parent.type == "floating":
            stack.insert(0, link)
    while stack:
        link = stack.pop()
        if link.name in poses:
            continue
        joint = link.parent
        attached = joint is None or joint.type == "floating" or joint.parent == model.WORLD
        pose = np.eye(4) if joint is None or joint.type == "floating" else None
        if pose is None and joint is not None:
            pose = _child_pose(robot, poses, joint)
            if pose is None:
                continue  # an origin Drake refuses, or a parent not placed (a cycle)
        assert pose is not None
        poses[link.name] = pose
        motion = _motion(joint)
        axis = _axis(joint) if motion in ("revolute", "prismatic", "planar") else None
        if axis is None and motion in ("revolute", "prismatic", "planar"):
            motion = "fixed"
        rotation = pose[:3, :3]
        local = _spatial_inertia(link)
        both = np.kron(np.eye(2), rotation)
        if link.name != model.WORLD:
            bodies.append(
                articulated.Body(
                    link.name,
                    None if attached or joint is None else joint.parent,
                    motion,
                    rotation @ axis if axis is not None else np.zeros(3),
                    pose[:3, 3],
                    both @ local @ both.T,
                )
            )
        stack.extend(
            robot.by_name[j.child]
            for j in reversed(link.children)
            if j.child in robot.by_name and j.type != "floating"
        )
    return bodies


def _child_pose(robot, poses, joint: model.Joint) -> NDArray[np.float64] | None:
    parent = poses.get(joint.parent or "")
    if parent is None:
        return None
    try:
        xyz, rpy = _origin(joint.origin)
        return parent @ transform(xyz, rpy)
    except (_Refused, ValueError):
        return None


def _axis(joint: model.Joint | None) -> NDArray[np.float64] | None:
    if joint is None:
        return None
    try:
        axis = np.array(_vector(joint.axis, "xyz") or (1.0, 0.0, 0.0), dtype=np.float64)
    except _Refused:
        return None
    norm = float(np.linalg.norm(axis))
    if not math.isfinite(norm) or norm < 1e-8:
        return None
    return axis / norm


def _singular_events(robot: RobotAnalysis) -> Iterator[Event]:
    with np.errstate(all="ignore"):
        hinges = articulated.hinges(_bodies(robot))
    for hinge in hinges:
        if not hinge.singular:
            continue
        link = robot.by_name[hinge.body]
        joint = link.parent
        assert joint is not None
        free = joint.type == "floating"
        inboard = "world" if free else joint.parent or "world"
        rotates = free or ROTATES.get(joint.type, False)
        translates = free or TRANSLATES.get(joint.type, False)
        motion = {
            (True, False): "inertia about its axis",
            (False, True): "mass along its axis",
        }.get((rotates, translates), "inertia in every direction it moves")
        inertial = link.link.inertial
        yield event(
            ENGINE,
            Verdict.REFUSES,
            "singular",
            f"fails at simulation time on joint `{joint.name}`: neither link `{link.name}` nor "
            f"anything outboard of it has {motion}",
            reading.singular_hinge(inboard, link.name, rotates, translates),
            inertial.source if inertial is not None else link.link.source,
            link=link.name,
            joint=joint.name,
        )
