"""IN074 kdl-verdict: what kdl_parser (robot_state_publisher, MoveIt, KDL solvers) ignores."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.rules import RuleContext

CODE = "IN074"
NAME = "kdl-verdict"
ENGINE = "kdl"
SEVERITY = Severity.WARNING
SCOPE = "robot"
# KDL reads URDF only
DESCRIPTION_FORMATS = ("urdf",)
SUMMARY = (
    "KDL ignores the root link's inertia, and turns floating and planar joints into fixed ones"
)

HELP = {
    "root-inertia": "add a massless root link (e.g. `base_footprint`) joined to this one by a "
    "fixed joint",
    "joint-type": "KDL models only revolute, continuous, prismatic and fixed joints",
}


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    # imported here: the engine model loads only when its engine is chosen (start-up)
    from inertia_kit.engines import kdl

    for event in kdl.events(robot):
        yield ctx.engine_finding(event, HELP[event.kind])
