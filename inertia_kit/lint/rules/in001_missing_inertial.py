"""IN001 missing-inertial: a body simulators move has no mass in its fixed-joint group."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.geometry import Geometry
from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt

CODE = "IN001"
NAME = "missing-inertial"
SEVERITY = Severity.ERROR
SCOPE = "robot"
SUMMARY = (
    "a link that moves (child of a non-fixed joint) or has collision geometry has no mass in its "
    "fixed-joint group"
)
OPTIONS = (
    # False: a massless root frame without collision geometry is taken as a fixed base (the
    # shape KDL asks for); True: the root floats, so its group needs mass whenever links move
    # below it
    Option(
        "floating_base",
        bool,
        False,
        "treat the root as free-floating: a massless root group above moving links is flagged",
    ),
)

DENSITY = 1000.0  # kg/m³: water, MuJoCo's default geom density, inertia-fill's default


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
    floating_base = bool(ctx.option("floating_base"))
    done: set[str] = set()
    for link in robot.links:
        if link.name in done:
            continue
        group = robot.group_of(link.name)
        done.update(m.name for m in group)
        if any(m.name == "world" for m in group):
            continue  # welded to the world: static, its mass is never used
        if any(m.link.inertial is not None for m in group):
            continue  # a declared mass, or a broken one that IN002/IN003/IN004 report
        top = _top(group)
        if top is None:
            continue  # a cycle of fixed joints: IN040's
        collision = any(m.link.collisions for m in group)
        site = _site(top, group)
        welded = [m.name for m in group if m is not site]
        others = (
            ""
            if not welded
            else f", nor do the links welded to it ({', '.join(f'`{n}`' for n in welded)})"
        )
        mujoco = (
            "MuJoCo fills in mass from the collision shapes at 1000 kg/m³"
            if collision
            else "MuJoCo refuses the model (mass and inertia of moving bodies must be larger "
            "than mjMINVAL)"
        )
        if top.parent is not None:
            joint = top.parent
            what = (
                f"moves (on {joint.type} joint `{joint.name}`)"
                if site is top
                else f"is part of the body that {joint.type} joint `{joint.name}` moves"
            )
            engines = (
                f"Gazebo drops it with its joint and every link below it, {mujoco}, PyBullet "
                "gives it 1 kg, Drake makes it massless (singular unless links further out "
                "give it inertia)"
            )
        else:
            moving = any(j.type != "fixed" for m in group for j in m.children)
            if not (collision or (floating_base and moving)):
                # a massless root frame (what KDL asks for) over moving links: the base is
                # taken to be fixed, unless `floating_base` says otherwise
                continue
            where = "is the root" if site is top else f"is welded to the root `{top.name}`"
            reason = "has collision geometry" if collision else "carries moving links"
            what = f"{where} and {reason}"
            others += ", and no fixed joint attaches it to a `world` link"
            engines = (
                "Gazebo drops it and the whole model with it, PyBullet gives it 1 kg unless "
                "loaded with useFixedBase, Drake leaves a massless free body, MuJoCo welds it "
                "to the world"
            )
        text, payload = _geometry_values(site.geometry)
        yield ctx.finding(
            f"link `{site.name}` {what} but has no `<inertial>`{others}: {engines}{text}",
            site.link.source,
            link=site.name,
            expected=payload,
            help="add an <inertial> with the part's mass and tensor (`inertia-fill` writes one "
            "from the geometry at a density you choose); a fixed base can instead hang from a "
            "`world` link by a fixed joint",
        )
