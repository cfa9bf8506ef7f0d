"""IN070 mujoco-verdict: what MuJoCo's compiler (and its URDF import) do with each link."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.rules import RuleContext

CODE = "IN070"
NAME = "mujoco-verdict"
SEVERITY = Severity.ERROR  # a refusal; a silent change is a warning
SCOPE = "robot"
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


#: what to do about what MuJoCo's compiler does with a body of an MJCF model
HELP_MJCF = {
    "body": "write a physically possible tensor about the centre of mass in the body's "
    "<inertial> (`inertia-fill --fix invalid` computes one from the geoms)",
    "minval": "give the moving body an <inertial> with positive mass and moments, or geoms "
    "with a density",
    "bound": "write the body's real mass and tensor; the compiler's bounds are for dummies",
    "balance": "write the body's real tensor (the geoms' at the right density) instead of "
    "leaving balanceinertia to invent one",
    "inertiafromgeom": 'drop inertiafromgeom="true" from <compiler> if the <inertial> '
    "elements are right, or delete them if the geoms are",
    "legacy": 'set inertia="exact" on the <mesh> (or "convex" if it is meant as its hull), '
    "or write the body's <inertial>",
    "visual": 'give the visual geom density="0" (or its class), or take its group out of '
    "inertiagrouprange",
}


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    # imported here: the engine model loads only when its engine is chosen (start-up)
    from inertia_kit.engines import mujoco

    helps = HELP_MJCF if robot.robot.format == "mjcf" else HELP
    for event in mujoco.events(robot):
        yield ctx.engine_finding(event, helps[event.kind])
