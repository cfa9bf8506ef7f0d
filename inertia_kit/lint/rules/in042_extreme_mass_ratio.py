"""IN042 extreme-mass-ratio: two bodies joined by a moving joint differ hugely in mass."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.fault import densest, density_excess, lightest
from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
from inertia_kit.engines.shares import NEGLIGIBLE
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt

CODE = "IN042"
NAME = "extreme-mass-ratio"
SEVERITY = Severity.WARNING
SCOPE = "robot"
SUMMARY = "the bodies on the two sides of a moving joint differ in mass by more than a ratio"
OPTIONS = (
    Option(
        "max_ratio", float, 1000.0, "the largest ratio of the masses on the two sides of a joint"
    ),
)


def _body(robot: RobotAnalysis, name: str) -> str:
    """``link`` or ``link (+ 2 welded links)``: what a simulator lumps into one body."""
    others = len(robot.group_of(name)) - 1
    if others <= 0:
        return f"`{name}`"
    return f"`{name}` (with {others} welded link{'s' if others > 1 else ''})"


def _ratio(value: float) -> str:
    return f"{value:.0f}" if value >= 100 else fmt(value, 3)


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    limit = float(ctx.option("max_ratio"))
    for joint in robot.robot.joints:
        if joint.type in ("fixed", "") or not joint.parent or not joint.child:
            continue
        if joint.parent not in robot.by_name or joint.child not in robot.by_name:
            continue
        parent, child = robot.group_mass(joint.parent), robot.group_mass(joint.child)
        if not (parent > 0 and child > 0):
            continue  # a massless side is IN001's business
        ratio = max(parent, child) / min(parent, child)
        if not ratio > limit:
            continue
        light, heavy = (
            (joint.child, joint.parent) if child < parent else (joint.parent, joint.child)
        )
        # the light body is named, unless the heavy one's mass is what no material gives
        # its geometry while the light one's is plausible: then that mass slipped
        culprit = _slipped(robot, heavy, light)
        cause = ""
        if culprit is not None:
            cause = (
                f"; `{culprit.name}` is the likely slip: its {fmt(culprit.declared.mass, 4)} kg "
                f"is {fmt(_density(culprit), 4)} kg/m³ over its geometry, no material"
            )
        # else the light body's link too light for any material is at fault; without either
        # the ratio is the joint's, not a link's: the finding blames neither (a heavy body of
        # plausible density beside a light one of plausible density, either may be wrong)
        named = culprit.name if culprit is not None else _too_light(robot, light)
        likely = "" if culprit is None else f" (likely `{culprit.name}`'s mass)"
        yield ctx.finding(
            f"joint `{joint.name}`: `{light}` weighs {fmt(min(parent, child), 4)} kg, "
            f"1/{_ratio(ratio)} of `{heavy}` at {fmt(max(parent, child), 4)} kg{likely}",
            joint.source,
            detail=f"{_body(robot, light)} weighs {fmt(min(parent, child), 4)} kg, "
            f"1/{_ratio(ratio)} of {_body(robot, heavy)} at {fmt(max(parent, child), 4)} kg "
            f"(beyond 1/{_ratio(limit)}): the joint's equations are ill-conditioned, so solvers "
            "jitter, drift or need tiny time steps" + cause,
            joint=joint.name or None,
            link=named,
            expected={
                "ratio": ratio,
                "parent_mass": parent,
                "child_mass": child,
                "max_ratio": limit,
            },
            help=(
                f"check both masses (grams for kilograms?); if they are real, give `{light}` "
                "at least its share of motor, cabling and housing, or weld it to its neighbour "
                "with a fixed joint"
                if culprit is None
                else f"check `{culprit.name}`'s mass against its part (grams for kilograms?); the "
                "ratio may then be right"
            ),
        )


def _density(link: LinkAnalysis) -> float:
    """The least of the link's densities over its geometries (the one IN022 would let pass)."""
    assert link.declared is not None
    return link.declared.mass / max(b.volume for b in link.bases)


def _slipped(robot: RobotAnalysis, heavy: str, light: str) -> LinkAnalysis | None:
    """
    The link of the heavy body whose density is beyond any material (analysis.fault) when
    no link of the light body's is: the mass that slipped. ``None`` when unclear.
    """
    # once per group: a base welded to thousands of links is on every one of its joints
    found = robot.group_fact(heavy, "densest weighing", _densest_weighing)
    if found is None:
        return None
    if robot.group_fact(light, "any density excess", _any_excess):
        return None
    return found[0]


def _too_light(robot: RobotAnalysis, light: str) -> str | None:
    """The link of the light body whose density is furthest below any material's, if any."""
    found = lightest(_weighing(robot.group_of(light)))
    return None if found is None else found[0].name


def _weighing(group: tuple[LinkAnalysis, ...]) -> tuple[LinkAnalysis, ...]:
    # a member with a share of the body's mass below 1 % cannot have set its weight (HyQ's
    # 1e-6 kg foot frames welded to a 0.88 kg lower leg; Go1's 1 g IMU frame welded to a trunk
    # whose mass was typed in grams)
    return tuple(m for m in group if m.mass_share >= NEGLIGIBLE)


def _densest_weighing(group: tuple[LinkAnalysis, ...]) -> tuple[LinkAnalysis, float] | None:
    return densest(_weighing(group))


def _any_excess(group: tuple[LinkAnalysis, ...]) -> bool:
    return any(density_excess(m) for m in _weighing(group))
