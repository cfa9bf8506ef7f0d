"""IN072 drake-verdict: what Drake's URDF parser and MultibodyPlant do with each link."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.rules import RuleContext

CODE = "IN072"
NAME = "drake-verdict"
ENGINE = "drake"
SEVERITY = Severity.WARNING
SCOPE = "robot"
SUMMARY = (
    "Drake replaces an invalid tensor by a water-density sphere, fails at run time on a "
    "massless moving link, and refuses collision meshes that are not .obj"
)

HELP = {
    "sphere": "write a physically valid tensor about the centre of mass (every principal moment "
    "≥ 0, A + B ≥ C) and a mass > 0",
    "singular": "give the link (or a link welded to it) a mass and inertia; a massless frame "
    "belongs on a fixed joint",
    "mesh": "convert the collision mesh to .obj (e.g. with trimesh or meshlab) and reference "
    "that file; visual meshes may stay as they are",
}


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    # imported here: the engine model loads only when its engine is chosen (start-up)
    from inertia_kit.engines import drake

    for event in drake.events(robot):
        yield ctx.engine_finding(event, HELP[event.kind])
