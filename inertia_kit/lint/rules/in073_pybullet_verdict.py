"""IN073 pybullet-verdict: what PyBullet's loadURDF does with each link's mass and inertia."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext

CODE = "IN073"
NAME = "pybullet-verdict"
ENGINE = "pybullet"
SEVERITY = Severity.WARNING
SCOPE = "robot"
# PyBullet's URDF loader
DESCRIPTION_FORMATS = ("urdf",)
SUMMARY = (
    "PyBullet gives a link without <inertial> 1 kg, and recomputes every tensor from the "
    "collision shapes' bounding box unless URDF_USE_INERTIA_FROM_FILE"
)
OPTIONS = (
    Option(
        "factor",
        float,
        2.0,
        "how far the computed tensor may differ from the declared one",
        minimum=1.0,
    ),
    Option("use_inertia_from_file", bool, False, "predict a load with URDF_USE_INERTIA_FROM_FILE"),
)

HELP = {
    "no-inertial": "give the link an <inertial>, or merge it into its parent "
    "(URDF_MERGE_FIXED_LINKS) if it is a fixed frame",
    "zeroed": "write a tensor whose principal moments are ≥ 0 and satisfy A + B ≥ C",
    "recomputed": "load with flags=p.URDF_USE_INERTIA_FROM_FILE to use the declared tensor "
    "(pybullet_quickstartguide: loadURDF flags)",
}


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    # imported here: the engine model loads only when its engine is chosen (start-up)
    from inertia_kit.engines import pybullet

    factor = float(ctx.option("factor"))
    from_file = bool(ctx.option("use_inertia_from_file"))
    for event in pybullet.events(robot, factor=factor, inertia_from_file=from_file):
        yield ctx.engine_finding(event, HELP[event.kind])
