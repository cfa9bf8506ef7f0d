"""IN025 missing-collision: a link with mass and visual geometry has no collision geometry."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.declared import declared_mass
from inertia_kit.analysis.describe import geometry_summary
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.description.model import WORLD
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt

CODE = "IN025"
NAME = "missing-collision"
SEVERITY = Severity.WARNING
SCOPE = "link"
# URDF's collision elements; an MJCF geom is both
DESCRIPTION_FORMATS = ("urdf",)
SUMMARY = "a link with mass and visual geometry has no `<collision>`"
OPTIONS = (
    Option(
        "min_mass_share", float, 0.01, "skip links lighter than this share of their fixed group"
    ),
)


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    element = link.link
    if element.collisions or not element.visuals or element.inertial is None:
        return
    mass = declared_mass(element)
    # a massless (or invalid-mass) frame is decoration: IN001/IN002/IN004 speak about its mass
    if mass is None:
        return
    # a placeholder mass on a frame welded to a real body (a 0.1 g marker) is decoration too
    if link.mass_share < float(ctx.option("min_mass_share")):
        return
    # simulators weld fixed-joint groups into one body: a collision shape anywhere in it counts
    if link.robot is not None and link.robot.group_fact(link.name, "collision", _any_collision):
        return
    yield ctx.finding(
        f"link `{link.name}` has {fmt(mass)} kg and a visual shape but no <collision>",
        element.source,
        link=link.name,
        detail=f"{_consequence(link)} ({geometry_summary(element)})",
        help="add a <collision> element: the visual geometry, or a simpler box, cylinder or "
        "convex mesh around it",
    )


def _any_collision(group: tuple[LinkAnalysis, ...]) -> bool:
    return any(member.link.collisions for member in group)


def _consequence(link: LinkAnalysis) -> str:
    """What a body without a surface does, by its place in the robot (once per group)."""
    if link.robot is None:
        return _group_consequence((link,))
    return link.robot.group_fact(link.name, "without a surface", _group_consequence)


def _group_consequence(group: tuple[LinkAnalysis, ...]) -> str:
    top = next((m for m in group if m.parent is None or m.parent.type != "fixed"), group[0])
    if any(m.name == WORLD for m in group):
        return "it is fixed to the world, so it stays put, but other bodies pass through it"
    if top.parent is None or top.parent.type == "floating":
        what = "the robot's free base (not welded to a `world` link)"
        if top.parent is not None:
            what = f"a free body (floating joint `{top.parent.name}`)"
        return (
            f"it is {what}: it falls through the floor unless other links hold it up, and "
            "passes through other bodies"
        )
    if any(j.type != "fixed" for m in group for j in m.children):
        return (
            "held by its joints it does not fall, but it makes no contact: the floor, other "
            "bodies and the robot's own links pass through it"
        )
    return (
        "it ends a chain (a foot, wheel, finger or tool), so it sinks through the floor and "
        "passes through whatever it should touch"
    )
