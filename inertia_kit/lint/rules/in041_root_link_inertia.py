"""IN041 root-link-inertia: the root link carries an ``<inertial>``, which KDL ignores."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt

CODE = "IN041"
NAME = "root-link-inertia"
SEVERITY = Severity.WARNING
SCOPE = "robot"
# KDL reads URDF only
DESCRIPTION_FORMATS = ("urdf",)
SUMMARY = "the root link carries an `<inertial>`: KDL (robot_state_publisher, MoveIt) ignores it"
OPTIONS = (Option("single_link", bool, False, "also flag robots without joints"),)

KDL = (
    "The root link {name} has an inertia specified in the URDF, but KDL does not support a "
    "root link with an inertia."
)


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    urdf = robot.robot
    name = urdf.root
    if name is None:
        return  # no root or several: IN040's business
    if not urdf.joints and not ctx.option("single_link"):
        return  # a single rigid object (a cube, a table) is never a KDL tree
    link = robot.by_name.get(name)
    inertial = None if link is None else link.link.inertial
    if inertial is None:
        return
    mass = inertial.mass if isinstance(inertial.mass, float) else None
    weight = "" if mass is None else f" ({fmt(mass)} kg)"
    root = _new_root(robot, name)
    yield ctx.finding(
        f"root link `{name}` has an <inertial>{weight}, which KDL leaves out",
        inertial.source,
        detail="KDL, so robot_state_publisher, MoveIt's KDL plugins and KDL dynamics, leave it "
        f'out ("{KDL.format(name=name)}"), and MuJoCo\'s URDF import fuses the root with the '
        "world body; Gazebo, Drake and PyBullet keep it, which a floating base needs",
        link=name,
        expected={"root": name, "mass": mass},
        help=f'add a massless root above it: <link name="{root}"/> and <joint '
        f'name="{root}_joint" type="fixed"><parent link="{root}"/><child '
        f'link="{name}"/></joint>; Gazebo and Drake lump the two into one body (PyBullet fixes '
        "a massless base to the world: load a floating robot with "
        "flags=p.URDF_MERGE_FIXED_LINKS)",
    )


def _new_root(robot: RobotAnalysis, root: str) -> str:
    """A name for a root above ``root`` that no link or joint of the robot has yet."""
    taken = {link.name for link in robot.robot.links} | {j.name for j in robot.robot.joints}
    candidates = ("base_footprint", f"{root}_root", *(f"{root}_root{i}" for i in range(2, 100)))
    return next(
        (c for c in candidates if c not in taken and f"{c}_joint" not in taken), f"{root}_root"
    )
