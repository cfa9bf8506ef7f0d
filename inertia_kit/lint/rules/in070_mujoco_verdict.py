"""IN070 mujoco-verdict: what MuJoCo's URDF import and compiler do with each link."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.rules import RuleContext

CODE = "IN070"
NAME = "mujoco-verdict"
SEVERITY = Severity.ERROR  # a refusal; a silent change is a warning
SCOPE = "robot"
# MuJoCo's URDF import; an MJCF model is judged as MuJoCo compiles it
DESCRIPTION_FORMATS = ("urdf",)
SUMMARY = (
    "MuJoCo refuses the model (with its own message) or silently changes a link: `--engine mujoco`"
)
ENGINE = "mujoco"

HELP = {
    "parse": "write the `<inertial>` completely: `<mass value>` and all six `<inertia>` "
    "attributes as plain numbers",
    "mesh": "give MuJoCo a binary STL or an OBJ (e.g. `trimesh` can convert), at a path "
    "relative to the URDF (no package://), or a primitive collision shape",
    "body": "write a physically possible tensor about the centre of mass "
    "(`inertia-fill --fix invalid`), or a positive collision size",
    "fuse": "give the welded links a tensor (not point masses), or the moving link one",
    "minval": "give the moving link an `<inertial>` with positive mass and moments, or weld "
    "a link that has them to it",
    "root": "add a floating joint from a `world` link if the robot should move freely, and "
    "keep the root massless (its mass counts for nothing in MuJoCo)",
    "clamp": "write the link's real (positive) mass",
    "inertiafromgeom": "write the link's `<inertial>` (`inertia-fill` computes one from the "
    "geometry at a density you choose)",
}


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    # imported here: the engine model loads only when its engine is chosen (start-up)
    from inertia_kit.engines import mujoco

    for event in mujoco.events(robot):
        yield ctx.engine_finding(event, HELP[event.kind])
