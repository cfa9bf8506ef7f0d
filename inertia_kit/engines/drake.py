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
from dataclasses import replace
from pathlib import PurePosixPath

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
from inertia_kit.description import model
from inertia_kit.engines import articulated
from inertia_kit.engines import drake_parser as parser
from inertia_kit.engines import drake_reading as reading
from inertia_kit.engines.drake_parser import WATER, plausible_sphere
from inertia_kit.engines.vocabulary import Event, Verdict, event
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.frames import rpy_matrix, transform

ENGINE = "drake"
VERSION = reading.VERSION
PROXIMITY_MESHES = (".obj", ".vtk", ".gltf")
ROTATES = {"revolute": True, "continuous": True, "prismatic": False, "planar": True}
TRANSLATES = {"revolute": False, "continuous": False, "prismatic": True, "planar": True}


# --- events ----------------------------------------------------------------------------------


def events(robot: RobotAnalysis) -> Iterator[Event]:
    """
    In Drake's order: ``robot`` (it has no name); per link ``number``/``tiny`` (the
    ``<inertial>`` is refused), ``world`` (its ``<inertial>`` ignored), ``sphere`` (replaced),
    ``geometry``/``mesh-missing``/``mesh`` (a shape or mesh refused); per joint ``friction``
    (ignored), ``joint`` (refused) or ``floating`` (left out); then ``singular`` (the first
    simulation step fails). Refusals carry ``first``: the one Drake reports.
    """
    found = [
        *_robot_events(robot),
        *_link_events(robot),
        *_joint_events(robot),
        *_singular_events(robot),
    ]
    first = next((e for e in found if e.verdict is Verdict.REFUSES), None)
    for found_event in found:
        if found_event.verdict is Verdict.REFUSES:
            facts = {**found_event.facts, "first": found_event is first}
            found_event = replace(found_event, facts=facts)
        yield found_event


def _robot_events(robot: RobotAnalysis) -> Iterator[Event]:
    """``UrdfParser::Parse``: the model's name is the robot's (``AddModels`` gives no other)."""
    if robot.robot.name is None:
        yield event(
            ENGINE,
            Verdict.REFUSES,
            "robot",
            "refuses the model",
            "Your robot must have a name attribute or a model name must be specified.",
            robot.robot.source,
            claim="the <robot> has no name",
            why="Drake names the model after the <robot>",
        )


def _link_events(robot: RobotAnalysis) -> Iterator[Event]:
    for link in robot.links:
        inertial = link.link.inertial
        if inertial is not None and link.name == model.WORLD:
            yield event(
                ENGINE,
                Verdict.CHANGES,
                "world",
                "ignores its <inertial>",
                'A URDF file declared the "world" link and then attempted to assign mass '
                "properties (via the <inertial> tag). Only geometries, <collision> and <visual>, "
                "can be assigned to the world link. The <inertial> tag is being ignored.",
                link.link.source,
                link=link.name,
                claim="the world has no mass",
                why="Drake takes the link `world` for its world body, which has no mass",
            )
        elif inertial is not None:
            yield from _inertial_events(link.name, inertial)
        for shape in (*link.link.visuals, *link.link.collisions):
            yield from _shape_events(link.name, shape)


def _inertial_events(link: str, inertial: model.Inertial) -> Iterator[Event]:
    read = parser.read_inertial(inertial)
    if read.kind == "refused":
        tiny = read.message == reading.ZERO_RADIUS
        mass = inertial.mass
        if tiny:
            shown = f"mass {fmt(mass)} kg" if isinstance(mass, float) else "its mass"
            claim = f"{shown}, too small for its stand-in sphere"
            why = (
                "Drake makes a water-density sphere of the link's mass for every <inertial> (its "
                f"stand-in for an invalid one); the sphere of link `{link}` has radius 0"
            )
        else:
            claim = "a value in its <inertial> is not one number"
            why = f"Drake cannot read a value in the <inertial> of link `{link}`"
        yield event(
            ENGINE,
            Verdict.REFUSES,
            "tiny" if tiny else "number",
            "refuses the model",
            read.message,
            read.source or inertial.source,
            link=link,
            claim=claim,
            why=why,
        )
    elif read.kind == "sphere":
        m, radius, moment = plausible_sphere(read.mass)
        invalid = (
            "its mass is not > 0"
            if read.message == reading.NON_POSITIVE_MASS
            else "its tensor is not physically valid"
        )
        yield event(
            ENGINE,
            Verdict.CHANGES,
            "sphere",
            "replaces its inertia",
            reading.flatten(read.message or ""),
            inertial.source,
            link=link,
            claim=f"{fmt(m)} kg water sphere, {fmt(moment, 4)} kg·m² per axis",
            why=f"The <inertial> of link `{link}` is invalid ({invalid}): Drake replaces it by "
            f"a solid sphere of {fmt(WATER)} kg/m³: {fmt(m)} kg, radius {fmt(radius, 4)} m, "
            f"moment {fmt(moment, 4)} kg·m² about each axis",
            mass=m,
            radius=radius,
            ixx=moment,
            iyy=moment,
            izz=moment,
        )


def _shape_events(link: str, shape: model.Shape) -> Iterator[Event]:
    """``ParseVisual``/``ParseCollision``: the first refusal of one shape, if any."""
    geometry = shape.geometry
    where = f"the {shape.kind} {parser.describe(geometry)} of link `{link}`"
    try:
        refusal = parser.shape_refusal(link, shape)
    except parser.Refused as refused:
        refusal = ("geometry", refused.message, refused.source)
    if refusal is not None:
        kind, message, source = refusal
        what, claim, why = "refuses the model", None, f"Drake cannot build {where}"
        if kind == "mesh-missing":
            claim = f"{shape.kind} mesh {_short(geometry)} not found"
            why = f"Drake finds no file for {where}" + (
                " (its words depend on the packages its package map holds)"
                if message is None
                else ""
            )
        else:
            what = f"refuses the model at its {shape.kind} {_short(geometry)}"
        yield event(
            ENGINE,
            Verdict.REFUSES,
            kind,
            what,
            message,
            source or geometry.source,
            link=link,
            claim=claim,
            why=why,
        )
        return
    if shape.kind != "collision" or not isinstance(geometry, model.Mesh):
        return
    found = parser.drake_path(geometry) or geometry.path
    if not found:
        return
    path = os.path.normpath(os.path.abspath(found))
    suffix = PurePosixPath(path).suffix.lower()
    if suffix in PROXIMITY_MESHES:
        return
    yield event(
        ENGINE,
        Verdict.REFUSES,
        "mesh",
        "refuses the model",
        f"MakeConvexHull only applies to .obj, .vtk, and .gltf meshes; unsupported extension "
        f"'{suffix}' for geometry data: {path}.",
        geometry.source,
        link=link,
        claim=f"{suffix or 'extension-less'} collision mesh, not .obj/.vtk/.gltf",
        why="With a SceneGraph Drake makes each collision mesh its convex hull, which it "
        f"computes from .obj, .vtk or .gltf files only: it refuses the collision mesh `{path}` "
        f"of link `{link}`",
        mesh=path,
    )


def _short(geometry: model.Geometry) -> str:
    """A shape as the one-line message names it: ``<box>``, a mesh by its file's name."""
    if isinstance(geometry, model.Mesh):
        name = PurePosixPath(geometry.filename.replace("\\", "/")).name
        return f"`{name or geometry.filename}`"
    return parser.describe(geometry)


def _joint_events(robot: RobotAnalysis) -> Iterator[Event]:
    known = {link.name for link in robot.links}
    for joint in robot.robot.joints:
        if not joint.name or joint.parent not in known or joint.child not in known:
            continue  # a broken tree: IN040
        read = parser.read_joint(joint)
        if read.friction != 0:
            yield event(
                ENGINE,
                Verdict.CHANGES,
                "friction",
                f"ignores its friction ({fmt(read.friction)})",
                reading.FRICTION,
                read.dynamics,
                link=joint.child,
                joint=joint.name,
                subject=f"joint `{joint.name}`",
                why=f"MultibodyPlant has no joint friction: Drake drops the friction "
                f"{fmt(read.friction)} of joint `{joint.name}` (it keeps the damping)",
            )
        if read.refusal is not None:
            message, source = read.refusal
            yield event(
                ENGINE,
                Verdict.REFUSES,
                "joint",
                "refuses the model",
                message,
                source or joint.source,
                link=joint.child,
                joint=joint.name,
                subject=f"joint `{joint.name}`",
                claim=_joint_claim(joint, message),
                why=f"Drake cannot build the {joint.type or 'untyped'} joint `{joint.name}` "
                f"from `{joint.parent}` to `{joint.child}`",
            )
        elif joint.type == "floating":
            yield event(
                ENGINE,
                Verdict.CHANGES,
                "floating",
                "makes it a free body",
                f"Joint '{joint.name}' specified as type floating which is not supported by "
                f"MultibodyPlant.  Leaving '{joint.child}' as a free body.",
                joint.source,
                link=joint.child,
                joint=joint.name,
                claim="its floating joint is left out",
                why=f"MultibodyPlant has no floating joint: Drake leaves out the joint "
                f"`{joint.name}`, and link `{joint.child}` becomes a free body, moved by nothing "
                "but gravity and contact",
            )


def _joint_claim(joint: model.Joint, message: str) -> str:
    """What Drake's refusal of a joint says, in a few words."""
    if message == reading.JOINT_LIMITS:
        return "lower limit above upper"
    if message == reading.VELOCITY_LIMITS:
        return "negative velocity limit"
    if message.endswith("damping must be nonnegative."):
        return "negative damping"
    if message.endswith("axis is zero.  Don't do that."):
        return "zero axis"
    if "custom joint type" in message:
        return f"a {joint.type} joint must be a <drake:joint>"
    if "has unrecognized type" in message:
        return f"unknown type `{joint.type}`"
    return "an unreadable value"


# --- forward dynamics ------------------------------------------------------------------------


def _spatial_inertia(link: LinkAnalysis) -> NDArray[np.float64]:
    """The body's spatial inertia about its origin in its own axes, as Drake has it."""
    inertial = link.link.inertial
    if inertial is None or link.name == model.WORLD:
        return np.zeros((6, 6))
    read = parser.read_inertial(inertial)
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
            pose = _child_pose(poses, joint)
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


def _child_pose(
    poses: dict[str, NDArray[np.float64]], joint: model.Joint
) -> NDArray[np.float64] | None:
    """The child link's pose at rest from its parent's (``None`` if that is not placed)."""
    parent = poses.get(joint.parent or "")
    if parent is None:
        return None
    try:
        xyz, rpy = parser.origin(joint.origin)
        return parent @ transform(xyz, rpy)
    except (parser.Refused, ValueError):
        return None


def _axis(joint: model.Joint | None) -> NDArray[np.float64] | None:
    if joint is None:
        return None
    try:
        axis = np.array(parser.vector(joint.axis, "xyz") or (1.0, 0.0, 0.0), dtype=np.float64)
    except parser.Refused:
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
        claim = {
            (True, False): "no inertia about its joint axis",
            (False, True): "no mass along its joint axis",
        }.get((rotates, translates), "no mass or inertia along its joint's motion")
        inertial = link.link.inertial
        yield event(
            ENGINE,
            Verdict.REFUSES,
            "singular",
            "fails at the first step",
            reading.singular_hinge(inboard, link.name, rotates, translates),
            inertial.source if inertial is not None else link.link.source,
            link=link.name,
            joint=joint.name,
            claim=claim,
            why=f"Forward dynamics stops at joint `{joint.name}`: neither link `{link.name}` "
            f"nor anything outboard of it has {motion}",
        )
