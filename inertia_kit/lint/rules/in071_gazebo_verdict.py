"""IN071 gazebo-verdict: what SDFormat's URDF converter (Gazebo) does with each link."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.rules import RuleContext

CODE = "IN071"
NAME = "gazebo-verdict"
ENGINE = "gazebo"
SEVERITY = Severity.WARNING
SCOPE = "robot"
# Gazebo reads URDF and SDFormat
DESCRIPTION_FORMATS = ("urdf",)
SUMMARY = (
    "Gazebo (sdformat's URDF converter) drops a massless link with its joint and subtree, "
    "or rejects a lumped body's invalid inertia"
)

HELP = {
    "dropped": "give the link its real <inertial> (inertia-fill computes one from the geometry), "
    "or attach a massless frame with a fixed joint so that it is lumped",
    "old-sdformat": "use a realistic mass (≥ 1e-6 kg), or no <inertial> on a fixed-joint frame",
    "invalid-inertia": "every principal moment must be ≥ 0 and each at most the sum of the other "
    "two (gz-math MassMatrix3::IsValid); recompute the tensor about the centre of mass",
}


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    # imported here: the engine model loads only when its engine is chosen (start-up)
    from inertia_kit.engines import gazebo

    for event in gazebo.events(robot):
        yield ctx.engine_finding(event, HELP[event.kind])
