"""IN001 missing-inertial: a body simulators move has no mass in its fixed-joint group."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from inertia_kit.analysis.declared import declared_mass
from inertia_kit.analysis.geometry import Geometry
from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
from inertia_kit.description.model import WORLD
from inertia_kit.lint.findings import Finding, FixRule, Repairs, Safety, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt

CODE = "IN001"
NAME = "missing-inertial"
SEVERITY = Severity.ERROR
SCOPE = "robot"
FIX = FixRule(
    "geometry", Safety.UNSAFE, Repairs.MISSING, "give the link the mass properties of its geometry"
)
SUMMARY = (
    "a link that moves (child of a non-fixed joint) or has collision geometry, or the root above "
    "moving links, has no mass in its fixed-joint group"
)
OPTIONS = (
    # True: the root is free unless a fixed joint welds it to a `world` link, as Gazebo, Drake
    # and PyBullet read a URDF; False: the simulator fixes the base (MuJoCo's URDF import,
    # PyBullet's useFixedBase, Drake's WeldFrames), so a massless root frame is fine there
    Option(
        "floating_base",
        bool,
        True,
        "the root is free unless welded to a `world` link: a massless root group above moving "
        "links is flagged (false: the simulator fixes the base)",
    ),
    # IN022's floor: a base group lighter than this over its geometry is a massless base
    Option(
        "min_base_density",
        float,
        50.0,
        "a root group whose declared mass over the volume of its largest shape is below this, "
        "kg/m³, is a base without mass (IN022's floor: foam is 30, wood 500)",
    ),
)

DENSITY = 1000.0  # kg/m³: water, MuJoCo's default geom density, inertia-fill's default
#: a shape wider than this, m, is not a robot base's: a mesh in other units (IN031's band)
MAX_EXTENT = 5.0


def _top(group: tuple[LinkAnalysis, ...]) -> LinkAnalysis | None:
    """The member simulators make the body of: the root, or the child of a non-fixed joint."""
    return next((m for m in group if m.parent is None or m.parent.type != "fixed"), None)


def _site(top: LinkAnalysis, group: tuple[LinkAnalysis, ...]) -> LinkAnalysis:
    """Where the `<inertial>` belongs: the body link if it has geometry, else a shaped member."""
    ordered = (top, *(m for m in group if m is not top))
    for test in (lambda m: m.link.collisions, lambda m: m.link.visuals):
        found = next((m for m in ordered if test(m)), None)
        if found is not None:
            return found
    return top


def _geometry_values(geometry: Geometry) -> tuple[str, dict | None]:
    """The geometry's mass properties at 1000 kg/m³, as message text and ``expected``."""
    if geometry.unit is None or not geometry.volume > 0:
        return "", None
    mass = DENSITY * geometry.volume
    body = geometry.at_mass(mass)
    if body is None:
        return "", None
    inertia = body.inertia
    payload = {
        "density": DENSITY,
        "volume": geometry.volume,
        "mass": mass,
        "com": [float(v) for v in body.com],
        "ixx": float(inertia[0, 0]),
        "ixy": float(inertia[0, 1]),
        "ixz": float(inertia[0, 2]),
        "iyy": float(inertia[1, 1]),
        "iyz": float(inertia[1, 2]),
        "izz": float(inertia[2, 2]),
    }
    text = (
        f"; its {geometry.describe()} holds {fmt(geometry.volume, 4)} m³: {fmt(mass, 4)} kg at "
        f"1000 kg/m³, ixx = {fmt(inertia[0, 0], 4)}, iyy = {fmt(inertia[1, 1], 4)}, "
        f"izz = {fmt(inertia[2, 2], 4)} kg·m² (link axes)"
    )
    return text, payload


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    if robot.robot.format == "mjcf":
        yield from _inferred(robot, ctx)
        return
    floating_base = bool(ctx.option("floating_base"))
    done: set[str] = set()
    for link in robot.links:
        if link.name in done:
            continue
        group = robot.group_of(link.name)
        done.update(m.name for m in group)
        if any(m.name == WORLD for m in group):
            continue  # welded to the world: static, its mass is never used
        top = _top(group)
        if any(m.link.inertial is not None for m in group):
            # a declared mass, or a broken one that IN002/IN003/IN004 report; but a base whose
            # mass is all in a small part welded to it has no mass of its own either
            if top is not None and top.parent is None:
                yield from _light_base(robot, group, top, ctx, floating_base)
            continue
        if top is None:
            continue  # a cycle of fixed joints: IN040's
        collision = any(m.link.collisions for m in group)
        site = _site(top, group)
        welded = [m.name for m in group if m is not site]
        others = (
            ""
            if not welded
            else f"; the links welded to it ({', '.join(f'`{n}`' for n in welded)}) have none "
            "either"
        )
        mujoco = (
            "MuJoCo fills in mass from the collision shapes at 1000 kg/m³"
            if collision
            else "MuJoCo refuses the model (mass and inertia of moving bodies must be larger "
            "than mjMINVAL)"
        )
        if top.parent is not None:
            joint = top.parent
            # the message names the joint; its type, the welded links and the engines are in
            # the detail
            claim = f"moves {'on' if site is top else 'with'} joint `{joint.name}`"
            what = (
                f"it moves on {joint.type} joint `{joint.name}`"
                if site is top
                else f"it is part of the body that {joint.type} joint `{joint.name}` moves"
            )
            engines = (
                f"Gazebo drops it with its joint and every link below it, {mujoco}, PyBullet "
                "gives it 1 kg, Drake makes it massless (singular unless links further out "
                "give it inertia)"
            )
            message = f"link `{site.name}` {claim} but has no `<inertial>`"
        else:
            below = _below(robot, group)
            if not (collision or (floating_base and below)):
                # a massless root frame over moving links, with `floating_base = false`: the
                # simulator is taken to fix the base (MuJoCo, useFixedBase, WeldFrames)
                continue
            where = "is the root" if site is top else f"is welded to the root `{top.name}`"
            what = f"it {where} and {' and '.join(_root_reasons(collision, below))}"
            others += (
                "; no fixed joint attaches it to a `world` link, so the robot's base has no mass"
            )
            engines = _base_engines(robot, top.name, below, len(group))
            message = f"link `{site.name}` {where} but has no `<inertial>`: a massless base"
        text, payload = _geometry_values(site.geometry)
        yield ctx.finding(
            message,
            site.link.source,
            link=site.name,
            expected=payload,
            help=_help(top, site, collision),
            detail=f"{what}{others}: {engines}{text}",
        )


def _root_reasons(collision: bool, below: tuple[str, ...]) -> list[str]:
    """Why a root group is a body simulators move: its collision shapes, the links it carries."""
    return [
        r
        for r, on in (("has collision geometry", collision), ("carries moving links", below))
        if on
    ]


def _volume(link: LinkAnalysis) -> tuple[float, Geometry] | None:
    """
    The smallest volume a link's usable geometries give (collision or visual: the one most in
    favour of a plausible density), and that geometry; ``None`` when it has none, or one is an
    open mesh (its hull overstates the volume) or wider than :data:`MAX_EXTENT` (other units).
    """
    found = []
    for geometry in link.bases:
        if any(s.mesh is not None and not s.mesh.closed for s in geometry.solids):
            return None
        corners = geometry.corners
        with np.errstate(all="ignore"):
            extent = None if corners is None else float(np.ptp(corners, axis=0).max())
        if extent is None or not extent <= MAX_EXTENT:  # not: a NaN extent is not judged
            return None
        found.append((geometry.volume, geometry))
    return min(found, key=lambda item: item[0]) if found else None


def _light_base(
    robot: RobotAnalysis,
    group: tuple[LinkAnalysis, ...],
    top: LinkAnalysis,
    ctx: RuleContext,
    floating_base: bool,
) -> Iterator[Finding]:
    """
    The root group as a massless base when the mass it declares is implausibly light for its
    geometry: under ``min_base_density`` over the volume of its largest shape (the union of
    the group's shapes holds at least that much, so the group's density is lower still), and
    that shape's link declares no mass (one that does is IN022's).
    """
    if any(m.name == WORLD for m in group):
        return
    below = _below(robot, group)
    collision = any(m.link.collisions for m in group)
    if not (collision or (floating_base and below)):
        return
    mass = robot.group_mass(top.name)
    if not mass > 0:
        return  # no positive mass anywhere: the broken values are IN002/IN003/IN004's
    volumes = [(v, m) for m in group if (v := _volume(m)) is not None]
    if not volumes:
        return
    (volume, geometry), site = max(volumes, key=lambda item: item[0][0])
    floor = float(ctx.option("min_base_density"))
    if site.link.inertial is not None or not volume > 0 or mass / volume >= floor:
        # a base shape that declares a light mass of its own is IN022's (implausible density)
        return
    heavy = [m.name for m in group if (declared_mass(m.link) or 0.0) > 0]
    carried = sum((declared_mass(robot.by_name[n].link) or 0.0 for n in below), 0.0)
    where = "is the root" if site is top else f"is welded to the root `{top.name}`"
    weight = (
        f"Gazebo, Drake and PyBullet simulate a {fmt(mass)} kg base under the "
        f"{fmt(carried)} kg of the links below it"
        if carried > 0
        else f"Gazebo, Drake and PyBullet simulate a {fmt(mass)} kg base"
    )
    text, payload = _geometry_values(site.geometry)
    yield ctx.finding(
        f"link `{site.name}`: the base declares only {fmt(mass)} kg, "
        f"{fmt(mass / volume, 2)} kg/m³ over its {geometry.name()}",
        site.link.source,
        link=site.name,
        expected=payload,
        help=_help(top, site, collision),
        detail=f"it {where} and {' and '.join(_root_reasons(collision, below))}; its "
        f"fixed-joint group declares only {fmt(mass)} kg (in {_names(tuple(heavy))}), "
        f"{fmt(mass / volume, 2)} kg/m³ over its {geometry.describe()} of {fmt(volume, 4)} m³, "
        f"below the plausible {fmt(floor)} kg/m³, so the robot's base has almost no mass: "
        f"{weight}; MuJoCo welds the root to the world, so the base cannot move there{text}",
    )


def _below(robot: RobotAnalysis, group: tuple[LinkAnalysis, ...]) -> tuple[str, ...]:
    """Every link below ``group`` (through its moving joints and beyond), nearest first."""
    members = {m.name for m in group}
    found: list[str] = []
    queue = [j.child for m in group for j in m.children if j.child and j.child not in members]
    while queue:
        name = queue.pop(0)
        if name in found or name in members or name not in robot.by_name:
            continue
        found.append(name)
        queue.extend(j.child for j in robot.by_name[name].children if j.child)
    return tuple(found)


def _names(names: tuple[str, ...], shown: int = 4) -> str:
    """`a`, `b` and `c`; beyond ``shown`` names, `a`, `b`, `c`, `d` and 12 more."""
    quoted = [f"`{n}`" for n in names]
    if len(quoted) > shown:
        return f"{', '.join(quoted[:shown])} and {len(quoted) - shown} more"
    return quoted[0] if len(quoted) == 1 else f"{', '.join(quoted[:-1])} and {quoted[-1]}"


def _base_engines(robot: RobotAnalysis, root: str, below: tuple[str, ...], members: int) -> str:
    """What each engine does with a massless root body (``members`` links welded together)."""
    gazebo = (
        f"Gazebo drops the base and with it every link below it ({_names(below)}), leaving "
        "nothing of the robot to simulate"
        if below
        else "Gazebo drops it, leaving nothing of the robot to simulate"
    )
    carried = sum((declared_mass(robot.by_name[n].link) or 0.0 for n in below), 0.0)
    # measured with drake 1.51: a free body with massive links below simulates (it only lacks
    # its own mass); without mass anywhere the first step is refused, naming the joint of a
    # massless body (of the root itself when nothing is below it)
    if carried > 0:
        drake = (
            "Drake makes it a free body without mass, so the robot moves as if it weighed only "
            f"the {fmt(carried)} kg of the links below it"
        )
    else:
        joint = "connects body …" if below else f"connects body world to body {root}"
        drake = (
            'Drake refuses to step it ("An internal mass matrix associated with the joint that '
            f'{joint} is not positive-definite")'
        )
    pybullet = "gives it 1 kg" if members == 1 else f"gives each of its {members} links 1 kg"
    return (
        f'{gazebo} ("A model must have at least one link"); {drake}; PyBullet {pybullet} '
        "unless loaded with useFixedBase; MuJoCo welds the root to the world, so the base "
        "cannot move there"
    )


def _help(top: LinkAnalysis, site: LinkAnalysis, collision: bool) -> str:
    add = "add an <inertial> with the part's mass and tensor"
    fill = "(`inertia-fill` writes one from the geometry at a density you choose)"
    if top.parent is not None:
        return f"{add} {fill}"
    text = (
        f"add an <inertial> with the base's real mass and tensor to `{site.name}` {fill}; a "
        "base meant to stay fixed hangs from a `world` link by a fixed joint instead"
    )
    if not collision:
        text += (
            " (or set `floating_base = false` when every simulator you use fixes the base "
            "itself: MuJoCo, PyBullet's useFixedBase, Drake's WeldFrames; Gazebo does not)"
        )
    return text


def _inferred(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    """
    MJCF: a body without ``<inertial>`` is not missing anything, MuJoCo infers its mass
    properties from its geoms. Told (info) when the density it weighs them at is MuJoCo's
    default, which nobody chose; a refusal or a geom we cannot weigh is IN070's.
    """
    from inertia_kit.engines.mujoco_inference import compiled, counted

    inference = robot.robot.inference
    if inference is None or inference.from_geometry != "missing":
        return
    bodies = compiled(robot)
    for link in robot.links:
        body = bodies.get(link.name)
        if body is None or not body.inferred or body.mass_properties is None:
            continue
        shapes = [s for s in (*link.link.visuals, *link.link.collisions) if counted(s, inference)]
        weighed = [s for s in shapes if s.mass is None and s.density is None]
        mass = body.mass_properties.mass
        if not weighed or not mass > 0:
            continue
        yield ctx.finding(
            f"link `{link.name}`: no <inertial>; MuJoCo infers {fmt(mass, 4)} kg at the "
            f"default {fmt(DENSITY)} kg/m³",
            link.link.source,
            link=link.name,
            severity=Severity.INFO,
            detail=(
                f"MuJoCo makes the body's mass properties from its geoms "
                f'(inertiafromgeom="auto"): {len(weighed)} of its {len(shapes)} counted geoms '
                f"give no density or mass, so MuJoCo weighs them at its default "
                f"{fmt(DENSITY)} kg/m³ (water; aluminium is 2700, steel 7850, ABS 1050)"
            ),
            help="write the body's <inertial> (its CAD values; `inertia-fill --density D` "
            "writes its geoms' at the material's density), or give its geoms the material's "
            "density (`density=` on the geom or its default class)",
        )
