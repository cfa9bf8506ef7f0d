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
# Drake's URDF parser
DESCRIPTION_FORMATS = ("urdf",)
SUMMARY = (
    "Drake replaces an invalid tensor by a water-density sphere, refuses what its parser cannot "
    "read (numbers, shapes, meshes, collision meshes that are not .obj/.vtk/.gltf), and fails at "
    "the first simulation step on a joint whose outboard links have no inertia along its motion"
)

HELP = {
    "robot": 'name the robot (<robot name="...">): Drake names the model after it',
    "number": "write each <inertial> value as one plain number (Drake reads `2kg` as 2 and "
    "refuses `nan`, `inf`, `1e999` and empty values)",
    "tiny": "the mass is below 1e-320 kg: write the real mass, or remove the <inertial> of a "
    "massless frame",
    "world": "remove the <inertial> from the link `world`: it stands for the world, which "
    "has no mass",
    "sphere": "write a physically valid tensor about the centre of mass (every principal moment "
    "≥ 0, A + B ≥ C) and a mass > 0",
    "geometry": "give the shape its dimensions, each > 0 (a sphere's radius ≥ 0), or remove the "
    "element",
    "mesh-missing": "point the mesh at an existing file (a `package://` URI needs the package in "
    "Drake's package map)",
    "mesh": "convert the collision mesh to .obj (e.g. with trimesh or meshlab) and reference "
    "that file; visual meshes may stay as they are",
    "joint": "give the joint a non-zero <axis>, a type Drake knows (revolute, continuous, "
    "prismatic, fixed, planar, floating; ball, screw and universal as <drake:joint>), "
    "lower ≤ upper, velocity ≥ 0 and damping ≥ 0",
    "friction": "model the joint's friction another way (Drake's joint friction is ignored; "
    "damping is kept), or remove the attribute",
    "floating": "leave the link unattached (Drake makes every unattached link a free body) or "
    "give it a joint Drake models",
    "singular": "give the link (or a link outboard of it) mass and inertia about the joint's "
    "motion; a massless frame belongs on a fixed joint",
}


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    # imported here: the engine model loads only when its engine is chosen (start-up)
    from inertia_kit.engines import drake

    for event in drake.events(robot):
        yield ctx.engine_finding(event, HELP[event.kind])
