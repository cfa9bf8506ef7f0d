"""
The bodies each simulator makes of a robot: which links fixed-joint lumping merges into one body,
which links an engine drops, and each body's combined declared mass properties.

Per engine (the sources each rule rests on are in ``rules/IN07*.md``):

- ``gazebo`` (SDFormat's URDF converter, ``parser_urdf.cc``): a fixed joint is lumped into its
  parent unless the joint carries ``<gazebo reference="joint"><preserveFixedJoint>`` (or the
  legacy ``<disableFixedJointLumping>``) or its parent is the link ``world``. After lumping, a
  body with no ``<inertial>`` or a total mass ≤ 0 is not converted: it, its parent joint and
  everything below it are dropped. Lumped collisions are renamed
  ``<body>_fixed_joint_lump__<name>_collision``.
- ``mujoco`` (URDF import, ``compiler/fusestatic`` is on for URDF): every fixed joint is fused;
  the root link's group becomes part of the static ``world`` body.
- ``drake``: no lumping, every link is a body (a fixed joint is a weld); the root link is a free
  body unless it is ``world``.
- ``pybullet``: no lumping unless ``loadURDF(..., flags=URDF_MERGE_FIXED_LINKS)``.
- ``kdl``: no lumping (fixed joints are ``Joint::None`` segments); the root segment carries no
  inertia.

Everything here is pure: it reads the analysis (declared values only) and returns values.
"""

from __future__ import annotations

import math
import weakref
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
from inertia_kit.description import model
from inertia_kit.description.model import WORLD
from inertia_kit.engines.vocabulary import ENGINES
from inertia_kit.physics.frames import inverse, transform
from inertia_kit.physics.mass import MassProperties

LUMP_PREFIX = "_fixed_joint_lump__"  # sdformat parser_urdf.cc kLumpPrefix


# --- declared values of one link and of a group -----------------------------------------------


def positive_mass(link: LinkAnalysis) -> MassProperties | None:
    """The declared values when complete, finite and with mass > 0 (else another rule's)."""
    declared = link.declared
    if declared is None or not (declared.mass > 0 and math.isfinite(declared.mass)):
        return None
    if not np.isfinite(declared.inertia).all():
        return None
    return declared


def written_tensor(values: Iterable[float]) -> NDArray[np.float64]:
    """
    The (3, 3) tensor of the six ``<inertia>`` values as written (in URDF order: ixx ixy ixz
    iyy iyz izz), in the axes of the ``<inertial><origin>``.
    """
    ixx, ixy, ixz, iyy, iyz, izz = values
    return np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])


def joint_pose(joint: model.Joint) -> NDArray[np.float64] | None:
    """(4, 4) parent-link → child-link transform of a joint at rest; ``None`` if not numeric."""
    xyz, rpy = joint.origin.xyz, joint.origin.rpy
    if not isinstance(xyz, tuple) or not isinstance(rpy, tuple):
        return None
    return transform(xyz, rpy)


def combine(
    robot: RobotAnalysis, name: str, crosses: Callable[[model.Joint], bool]
) -> MassProperties | None:
    """
    The sum of the declared mass properties (complete, finite, mass > 0) of ``name`` and every
    link reached from it through joints ``crosses`` accepts (in either direction), in ``name``'s
    frame.

    ``None`` when no member has usable values, or a crossed joint's origin is not numeric.
    """
    return _combined(robot, name, crosses)[0]


def _combined(
    robot: RobotAnalysis, name: str, crosses: Callable[[model.Joint], bool]
) -> tuple[MassProperties | None, dict[str, NDArray[np.float64]]]:
    """:func:`combine`, and the pose of each link reached in ``name``'s frame."""
    poses: dict[str, NDArray[np.float64]] = {name: np.eye(4)}
    stack = [name]
    total: MassProperties | None = None
    while stack:
        current = stack.pop()
        link = robot.by_name.get(current)
        if link is None:
            continue
        pose = poses[current]
        declared = positive_mass(link)
        if declared is not None:
            placed = declared.transformed(pose)
            total = placed if total is None else total + placed
        neighbours = []
        for parent in robot.joints_into.get(current, ()):
            if not (parent.parent and crosses(parent)):
                continue
            origin = joint_pose(parent)
            if origin is None:
                return None, poses
            neighbours.append((parent.parent, pose @ inverse(origin)))
        for joint in link.children:
            if joint.child and crosses(joint):
                origin = joint_pose(joint)
                if origin is None:
                    return None, poses
                neighbours.append((joint.child, pose @ origin))
        for other, other_pose in neighbours:
            if other not in poses:
                poses[other] = other_pose
                stack.append(other)
    return total, poses


def _fixed(joint: model.Joint) -> bool:
    return joint.type == "fixed"


#: robot -> group's first link -> (its lumped body, each member's pose in its frame)
_LUMPED: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def lumped(robot: RobotAnalysis, name: str) -> MassProperties | None:
    """
    The body simulators make of ``name`` and the links welded to it by fixed joints: the sum of
    their declared mass properties (complete, finite, mass > 0), in ``name``'s frame.

    ``None`` when no member has usable values, or a fixed joint's origin is not numeric.

    Each group is summed once, in its first link's frame, and moved to ``name``'s (rules ask
    it of many links of one group: 5000 sums of a welded chain of 5000 links would be
    quadratic).
    """
    group = robot.group_of(name)
    if not group:
        return None
    first = group[0].name
    sums = _LUMPED.setdefault(robot, {})
    if first not in sums:
        sums[first] = _combined(robot, first, _fixed)
    total, poses = sums[first]
    if total is None:  # no mass in the group, or a joint's origin is not a number
        return None
    if name == first:
        return total
    return total.transformed(inverse(poses[name]))


def lumped_without(
    robot: RobotAnalysis, name: str, leaving_out: frozenset[str]
) -> MassProperties | None:
    """
    :func:`lumped` without the links ``leaving_out`` (members whose values are in doubt), in
    ``name``'s frame; ``None`` when no other member has usable values.
    """
    if lumped(robot, name) is None:
        return None
    group = robot.group_of(name)
    _, poses = _LUMPED[robot][group[0].name]
    total: MassProperties | None = None
    for member in group:
        declared = positive_mass(member)
        if member.name in leaving_out or declared is None or member.name not in poses:
            continue
        placed = declared.transformed(poses[member.name])
        total = placed if total is None else total + placed
    return None if total is None else total.transformed(inverse(poses[name]))


# --- bodies -----------------------------------------------------------------------------------


@dataclass(frozen=True)
class Body:
    """
    One rigid body an engine simulates.

    Attributes
    ----------
    name : str
      The engine's name for it: the link the others are lumped into (``world`` for MuJoCo's
      static body).
    links : tuple of str
      The links it is made of, the body's own link first, then the lumped ones depth first.
    joint : str or None
      The joint that moves it; ``None`` for the root (or MuJoCo's world body).
    mass_properties : MassProperties or None
      Combined declared values in the frame of ``links[0]``; ``None`` when no member has
      complete values with mass > 0, or the engine ignores them (KDL's root segment).
    static : bool
      Welded to the world: MuJoCo's world body, Drake's world, KDL's root segment.
    declared_mass : float
      Sum of the finite ``<mass>`` values of the members that have an ``<inertial>``, kg (what
      sdformat tests against 0).
    has_inertial : bool
      At least one member has an ``<inertial>``.
    collisions : tuple of str
      The names the engine gives the body's collision elements (Gazebo: SDFormat names).
    note : str or None
      What the engine does with the body's values besides (e.g. KDL ignores the root inertia).
    """

    name: str
    links: tuple[str, ...]
    joint: str | None
    mass_properties: MassProperties | None
    static: bool = False
    declared_mass: float = 0.0
    has_inertial: bool = False
    collisions: tuple[str, ...] = ()
    note: str | None = None

    @property
    def lumped(self) -> tuple[str, ...]:
        """The links merged into this body (all but its own)."""
        return self.links[1:] if self.name == self.links[0] else self.links


@dataclass(frozen=True)
class Dropped:
    """
    A link an engine does not simulate. ``cause`` is the body link whose missing mass drops it
    (the link itself, or an ancestor); ``joint`` its parent joint, dropped with it.
    """

    link: str
    joint: str | None
    cause: str
    reason: str  # no-inertial | non-positive-mass | ancestor


@dataclass(frozen=True)
class EngineBodies:
    """The bodies one engine simulates for a robot, and the links it drops."""

    engine: str
    bodies: tuple[Body, ...]
    dropped: tuple[Dropped, ...] = ()

    def dropped_link(self, link: str) -> Dropped | None:
        return next((d for d in self.dropped if d.link == link), None)

    def dropped_below(self, cause: str) -> tuple[str, ...]:
        """The links dropped because ``cause`` was (not ``cause`` itself)."""
        return tuple(d.link for d in self.dropped if d.cause == cause and d.link != cause)


def preserved_joints(robot: model.Robot) -> frozenset[str]:
    """
    Fixed joints SDFormat keeps instead of lumping: ``<gazebo reference="joint">`` with
    ``<preserveFixedJoint>true</preserveFixedJoint>`` or ``<disableFixedJointLumping>true…``
    (``true``, ``yes`` or ``1``).
    """
    return frozenset(
        extension.reference
        for extension in robot.extensions
        if extension.reference
        and (extension.flag("preserveFixedJoint") or extension.flag("disableFixedJointLumping"))
    )


def lumping_rule(
    robot: RobotAnalysis, engine: str, *, merge_fixed_links: bool = False
) -> Callable[[model.Joint], bool]:
    """Whether ``engine`` merges a joint's child into its parent's body."""
    if engine == "gazebo":
        preserved = preserved_joints(robot.robot)
        return lambda j: j.type == "fixed" and j.name not in preserved and j.parent != WORLD
    if engine == "mujoco":
        return _fixed
    if engine == "pybullet" and merge_fixed_links:
        return _fixed
    if engine in ENGINES:
        return lambda j: False
    raise ValueError(f"unknown engine {engine!r}; known: {', '.join(ENGINES)}")


def _tree(robot: RobotAnalysis) -> Iterator[LinkAnalysis]:
    """Links depth first from each root, children in document order; each once."""
    seen: set[str] = set()
    roots = [link for link in robot.links if link.parent is None]
    for root in roots + list(robot.links):
        stack = [root]
        while stack:
            link = stack.pop()
            if link.name in seen:
                continue
            seen.add(link.name)
            yield link
            stack.extend(
                robot.by_name[j.child] for j in reversed(link.children) if j.child in robot.by_name
            )


def _members(robot: RobotAnalysis, head: LinkAnalysis, lumps) -> list[LinkAnalysis]:
    """``head`` and the links lumped into it, depth first, children in document order."""
    found, stack, seen = [], [head], set()
    while stack:
        link = stack.pop()
        if link.name in seen:
            continue
        seen.add(link.name)
        found.append(link)
        stack.extend(
            robot.by_name[j.child]
            for j in reversed(link.children)
            if j.child in robot.by_name and lumps(j)
        )
    return found


def _declared_mass(members: list[LinkAnalysis]) -> tuple[float, bool]:
    total, any_inertial = 0.0, False
    for member in members:
        inertial = member.link.inertial
        if inertial is None:
            continue
        any_inertial = True
        if isinstance(inertial.mass, float) and math.isfinite(inertial.mass):
            total += inertial.mass
    return total, any_inertial


def sdf_collision_names(body: str, members: list[LinkAnalysis]) -> tuple[str, ...]:
    """
    The names sdformat's URDF converter gives a lumped body's collisions (``CreateCollisions``):
    ``<name or link>_collision`` (``_<k>`` from the second on), prefixed with
    ``<body>_fixed_joint_lump__`` unless it already starts with the body's name.
    """
    names = []
    k = 0
    for member in members:
        for shape in member.link.collisions:
            base = shape.name or (body if member.name == body else member.name)
            name = f"{base}_collision" + (f"_{k}" if k else "")
            names.append(name if name.startswith(body) else f"{body}{LUMP_PREFIX}{name}")
            k += 1
    return tuple(names)


def simulated_bodies(
    robot: RobotAnalysis, engine: str, *, merge_fixed_links: bool = False
) -> EngineBodies:
    """
    The bodies ``engine`` simulates for ``robot`` (see the module docstring for each policy).

    Parameters
    ----------
    robot : RobotAnalysis
    engine : str
      One of :data:`ENGINES`.
    merge_fixed_links : bool
      PyBullet only: as if loaded with ``URDF_MERGE_FIXED_LINKS``.
    """
    lumps = lumping_rule(robot, engine, merge_fixed_links=merge_fixed_links)
    bodies: list[Body] = []
    dropped: list[Dropped] = []
    gone: set[str] = set()
    placed: set[str] = set()
    for link in _tree(robot):
        if link.name in placed or link.name in gone:
            continue
        members = _members(robot, link, lumps)
        names = tuple(m.name for m in members)
        joint = link.parent
        mass, has_inertial = _declared_mass(members)
        is_root = joint is None or joint.parent not in robot.by_name
        if engine == "gazebo":
            if link.name == WORLD and is_root:
                placed.update(names)
                continue  # the world is not a model link; its children are converted
            if not has_inertial or not mass > 0:
                # CreateSDF returns without recursing: the link, its joint and its subtree
                reason = "no-inertial" if not has_inertial else "non-positive-mass"
                welded_to_world = (
                    joint is not None and joint.parent == WORLD and joint.type == "fixed"
                )
                below = [] if welded_to_world else _subtree(robot, link)
                for name in names:
                    dropped.append(Dropped(name, _parent_name(robot, name), link.name, reason))
                for other in below:
                    if other not in names and other not in gone:
                        dropped.append(
                            Dropped(other, _parent_name(robot, other), link.name, "ancestor")
                        )
                gone.update(names)
                gone.update(below)
                continue
        static = False
        note = None
        properties = combine(robot, link.name, lambda j, names=names: _inside(j, names))
        name = link.name
        if engine == "mujoco" and is_root:
            name, static = WORLD, True
            note = "fused into MuJoCo's static world body (fusestatic)"
        elif engine == "drake" and link.name == WORLD and is_root:
            static = True
        elif engine == "kdl" and is_root:
            static, properties = True, None
            if has_inertial:
                note = "KDL's root segment carries no inertia: the declared values are ignored"
        elif engine == "pybullet" and not has_inertial and len(members) == 1:
            from inertia_kit.engines.pybullet import stand_in  # it reads this module's tensors

            properties = stand_in(link)
            note = "no <inertial>: PyBullet gives it 1 kg, its tensor from the collision shapes"
        bodies.append(
            Body(
                name,
                names,
                None if is_root else joint.name,
                properties,
                static,
                mass,
                has_inertial,
                sdf_collision_names(link.name, members) if engine == "gazebo" else (),
                note,
            )
        )
        placed.update(names)
    return EngineBodies(engine, tuple(bodies), tuple(dropped))


def _inside(joint: model.Joint, names: tuple[str, ...]) -> bool:
    return joint.parent in names and joint.child in names


def _parent_name(robot: RobotAnalysis, name: str) -> str | None:
    link = robot.by_name.get(name)
    return None if link is None or link.parent is None else link.parent.name


def _subtree(robot: RobotAnalysis, head: LinkAnalysis) -> list[str]:
    """Every link below ``head`` (not ``head``), depth first."""
    return [m.name for m in _members(robot, head, lambda j: True)][1:]
