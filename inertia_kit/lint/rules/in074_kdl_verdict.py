"""IN074 kdl-verdict: what kdl_parser (robot_state_publisher, MoveIt, KDL solvers) ignores."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.engines.vocabulary import Verdict, verdict_expected, verdict_message
from inertia_kit.lint.findings import Finding, Severity, severity_of
from inertia_kit.lint.rules import RuleContext

CODE = "IN074"
NAME = "kdl-verdict"
ENGINE = "kdl"
SEVERITY = Severity.WARNING
SCOPE = "robot"
SUMMARY = (
    "KDL ignores the root link's inertia, and turns floating and planar joints into fixed ones"
)
OPTIONS: dict[str, type] = {}
DEFAULTS: dict[str, object] = {}

KDL_JOINTS = ("fixed", "revolute", "continuous", "prismatic")


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    roots = [link for link in robot.links if link.parent is None]
    if len(roots) == 1 and roots[0].link.inertial is not None:
        root = roots[0]
        inertial = root.link.inertial
        message = (
            f"The root link {root.name} has an inertia specified in the URDF, but KDL does not "
            "support a root link with an inertia.  As a workaround, you can add an extra dummy "
            "link to your URDF."
        )
        yield ctx.finding(
            verdict_message(
                ENGINE, Verdict.CHANGES, message, f"ignores the inertia of root link `{root.name}`"
            ),
            inertial.source,
            link=root.name,
            expected=verdict_expected(ENGINE, Verdict.CHANGES, message),
            severity=severity_of(Verdict.CHANGES),
            help="add a massless root link (e.g. `base_footprint`) joined to this one by a fixed "
            "joint",
        )
    for joint in robot.robot.joints:
        if joint.type in KDL_JOINTS or not joint.type:
            continue
        message = f"Converting unknown joint type of joint '{joint.name}' into a fixed joint"
        yield ctx.finding(
            verdict_message(
                ENGINE,
                Verdict.CHANGES,
                message,
                f"welds link `{joint.child}`: its {joint.type} joint `{joint.name}` becomes fixed",
            ),
            joint.source,
            link=joint.child,
            joint=joint.name,
            expected=verdict_expected(ENGINE, Verdict.CHANGES, message, joint_type=joint.type),
            severity=severity_of(Verdict.CHANGES),
            help="KDL models only revolute, continuous, prismatic and fixed joints",
        )
