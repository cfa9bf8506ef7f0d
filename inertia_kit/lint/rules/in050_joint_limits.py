"""IN050 joint-limits: a joint's ``<limit>`` is missing, incomplete or impossible."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.description import model
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt

CODE = "IN050"
NAME = "joint-limits"
SEVERITY = Severity.ERROR
SCOPE = "robot"
# URDF's <limit>; MJCF's ranges are optional and in the compiler's angle unit
DESCRIPTION_FORMATS = ("urdf",)
SUMMARY = (
    "a revolute/prismatic joint without `<limit>`, a limit without effort or velocity, "
    "lower > upper, or effort/velocity ≤ 0"
)
OPTIONS = (Option("allow_zero", bool, False, "accept effort and velocity of 0"),)

LIMITED = ("revolute", "prismatic")
_URDFDOM = {
    "revolute": "Joint [{}] is of type REVOLUTE but it does not specify limits",
    "prismatic": "Joint [{}] is of type PRISMATIC without limits",
}


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    for joint in robot.robot.joints:
        if joint.type in LIMITED:
            if joint.limit is None:
                yield _finding(
                    ctx,
                    joint,
                    f"{joint.type} joint has no <limit>",
                    joint.source,
                    'add <limit lower="..." upper="..." effort="..." velocity="..."/> '
                    f"({'rad, rad' if joint.type == 'revolute' else 'm, m'}, "
                    f"{'N·m, rad/s' if joint.type == 'revolute' else 'N, m/s'})",
                    detail="urdfdom (so ROS, Gazebo) and PyBullet refuse the file "
                    f'("{_URDFDOM[joint.type].format(joint.name)}")',
                )
                continue
            yield from _range(ctx, joint, joint.limit)
        if joint.type in (*LIMITED, "continuous") and joint.limit is not None:
            yield from _effort_velocity(ctx, joint, joint.limit)


def _finding(
    ctx: RuleContext,
    joint: model.Joint,
    text: str,
    source: model.Source,
    help: str,
    severity: Severity | None = None,
    detail: str | None = None,
):
    return ctx.finding(
        f"joint `{joint.name}`: {text}",
        source,
        joint=joint.name or None,
        link=joint.child,
        help=help,
        severity=severity,
        detail=detail,
    )


def _range(ctx: RuleContext, joint: model.Joint, limit: model.Limit) -> Iterator[Finding]:
    lower, upper = limit.lower, limit.upper
    unit = "rad" if joint.type == "revolute" else "m"
    if lower is None or upper is None:
        missing = " and ".join(n for n, v in (("lower", lower), ("upper", upper)) if v is None)
        verb = "default" if lower is None and upper is None else "defaults"
        yield _finding(
            ctx,
            joint,
            f"<limit> has no {missing}, so the joint moves in "
            f"[{fmt(lower if isinstance(lower, float) else 0.0)}, "
            f"{fmt(upper if isinstance(upper, float) else 0.0)}] {unit}",
            limit.source,
            "write both lower and upper; a joint that must not move is a fixed joint",
            severity=Severity.WARNING,
            detail=f"{missing}: {'both' if verb == 'default' else 'it'} {verb} to 0 in urdfdom",
        )
        return
    if isinstance(lower, float) and isinstance(upper, float) and lower > upper:
        yield _finding(
            ctx,
            joint,
            f"lower = {fmt(lower)} {unit} is above upper = {fmt(upper)} {unit}",
            limit.source,
            "swap lower and upper; for a joint without limits write a continuous joint "
            '(revolute) or a wide range (prismatic: lower="-1e3" upper="1e3")',
            detail="no position satisfies the limits; PyBullet reads this as 'no limits', other "
            "engines clamp the joint to one end or reject the range",
        )


def _effort_velocity(ctx: RuleContext, joint: model.Joint, limit: model.Limit) -> Iterator[Finding]:
    revolute = joint.type != "prismatic"
    units = {"effort": "N·m" if revolute else "N", "velocity": "rad/s" if revolute else "m/s"}
    zero = []
    for name in ("effort", "velocity"):
        value = getattr(limit, name)
        if value is None:
            yield _finding(
                ctx,
                joint,
                f"<limit> has no {name}",
                limit.source,
                f"give the actuator's {name} limit in {units[name]} (from its datasheet)",
                detail=f'urdfdom refuses the file ("joint limit: no {name}")',
            )
        elif isinstance(value, float) and value < 0:
            yield _finding(
                ctx,
                joint,
                f"{name} = {fmt(value)} {units[name]} is negative",
                limit.source,
                f"give the {name} limit as a positive number in {units[name]}",
                detail="a limit is a magnitude",
            )
        elif isinstance(value, float) and value == 0:
            zero.append(name)
    # a mimic joint is driven through the joint it follows; CAD exporters write 0 as "unknown"
    if not zero or joint.mimic is not None or ctx.option("allow_zero"):
        return
    what = []
    if "effort" in zero:
        what.append(
            "Gazebo clamps the joint's force to ±effort, so nothing can drive it (only a "
            "negative effort means unlimited there)"
        )
    if "velocity" in zero:
        what.append(
            "a speed limit of 0 holds the joint still wherever limits are enforced, while "
            "MoveIt reads 0 as unlimited"
        )
    values = " and ".join(f"{name} = 0 {units[name]}" for name in zero)
    claim = "nothing can drive it" if "effort" in zero else "it is held still"
    yield _finding(
        ctx,
        joint,
        f"{values}: {claim}",
        limit.source,
        f"give the actuator's {' and '.join(zero)} limit"
        f"{'s' if len(zero) > 1 else ''} from its datasheet "
        f"({', '.join(units[name] for name in zero)}); a passive joint takes a real bound "
        "too (or set allow_zero)",
        severity=Severity.WARNING,
        detail="; ".join(what),
    )
