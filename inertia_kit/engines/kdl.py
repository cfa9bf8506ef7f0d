"""
What kdl_parser (robot_state_publisher, MoveIt, the KDL solvers) does with a robot: it ignores
the root link's inertia, and turns the joint types KDL has no segment for into fixed joints.
"""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.engines.vocabulary import Event, Verdict, event
from inertia_kit.physics.formatting import fmt

ENGINE = "kdl"
KDL_JOINTS = ("fixed", "revolute", "continuous", "prismatic")


def events(robot: RobotAnalysis) -> Iterator[Event]:
    """
    What KDL changes: ``root-inertia`` (the single root link's ``<inertial>`` is ignored) and
    ``joint-type`` (a floating or planar joint becomes fixed).
    """
    roots = [link for link in robot.links if link.parent is None]
    if len(roots) == 1 and roots[0].link.inertial is not None:
        root = roots[0]
        message = (
            f"The root link {root.name} has an inertia specified in the URDF, but KDL does not "
            "support a root link with an inertia.  As a workaround, you can add an extra dummy "
            "link to your URDF."
        )
        mass = root.link.inertial.mass
        weight = f" ({fmt(mass)} kg)" if isinstance(mass, float) else ""
        yield event(
            ENGINE,
            Verdict.CHANGES,
            "root-inertia",
            f"ignores the root link's inertia{weight}",
            message,
            root.link.inertial.source,
            link=root.name,
            why=f"kdl_parser leaves out the <inertial> of the root link `{root.name}`{weight}: "
            "the root segment of a KDL tree has no inertia",
        )
    for joint in robot.robot.joints:
        if joint.type in KDL_JOINTS or not joint.type:
            continue
        message = f"Converting unknown joint type of joint '{joint.name}' into a fixed joint"
        yield event(
            ENGINE,
            Verdict.CHANGES,
            "joint-type",
            f"makes its {joint.type} joint fixed",
            message,
            joint.source,
            link=joint.child,
            joint=joint.name,
            why=f"KDL has no {joint.type} joint: the {joint.type} joint `{joint.name}` becomes "
            f"fixed, welding link `{joint.child}` to `{joint.parent}`",
            joint_type=joint.type,
        )
