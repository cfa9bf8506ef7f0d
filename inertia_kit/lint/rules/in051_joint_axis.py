"""IN051 joint-axis: a moving joint's ``<axis>`` is zero or not a unit vector."""

from __future__ import annotations

import math
from collections.abc import Iterator

from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt, xml_number

CODE = "IN051"
NAME = "joint-axis"
SEVERITY = Severity.ERROR
SCOPE = "robot"
# URDF's <axis>; MuJoCo normalises an MJCF joint's axis
DESCRIPTION_FORMATS = ("urdf",)
SUMMARY = "a moving joint's `<axis>` is zero (error) or not of unit length (warning)"
OPTIONS = (
    Option("tolerance", float, 1e-3, "the allowed difference between the axis length and 1"),
)

# joints whose motion is defined by the axis (a floating joint ignores it)
AXIS_TYPES = ("revolute", "continuous", "prismatic", "planar")
# below this length an axis has no direction that rounding can be trusted with
ZERO = 1e-9


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    tolerance = float(ctx.option("tolerance"))
    for joint in robot.robot.joints:
        axis = joint.axis
        if joint.type not in AXIS_TYPES or not isinstance(axis, tuple):
            continue  # no <axis>: URDF means (1, 0, 0); non-numeric: IN004's business
        length = math.sqrt(sum(v * v for v in axis))
        written = " ".join(fmt(v) for v in axis)
        if length < ZERO:
            yield ctx.finding(
                f"joint `{joint.name}`: axis `{written}` has no direction",
                joint.source,
                detail='Gazebo (SDFormat) and Drake refuse it, MuJoCo too ("axis too small"), '
                "KDL divides by its length (NaN poses)",
                joint=joint.name or None,
                link=joint.child,
                help="give the unit vector of the joint's rotation (revolute, continuous), "
                "translation (prismatic) or plane normal (planar) in the joint frame",
            )
            continue
        if abs(length - 1.0) <= tolerance:
            continue
        unit = " ".join(xml_number(v / length, 6) for v in axis)
        yield ctx.finding(
            f"joint `{joint.name}`: axis `{written}` has length {fmt(length, 4)}, not 1",
            joint.source,
            detail="Gazebo (SDFormat), Drake, MuJoCo and KDL normalise it, but PyBullet and "
            "urdfdom users (robot_state_publisher plugins, IK solvers) take it as written, so "
            f"the joint moves {fmt(length, 4)} times as far per unit of position",
            joint=joint.name or None,
            link=joint.child,
            expected={"axis": [v / length for v in axis], "length": length},
            help=f'write the unit vector: <axis xyz="{unit}"/>',
            severity=Severity.WARNING,
        )
