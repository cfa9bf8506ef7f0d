"""
Each link's frame in the world in the zero pose (every joint at 0): the joint origins composed
from each root down the tree.

Every root (a link no joint names as child, several when the tree is broken into pieces) is at
the identity. A joint whose ``<origin>`` is not numeric places its child at its parent's frame;
a link that is only reached through a cycle, or whose parent is unknown, stands at the identity.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from inertia_kit.description import model
from inertia_kit.engines.lumping import joint_pose


def zero_pose(robot: model.Robot) -> dict[str, NDArray[np.float64]]:
    """
    ``link name -> (4, 4)`` transform mapping link coordinates to world coordinates, with every
    joint at 0, for every link of ``robot`` (the first of a repeated name).
    """
    children: dict[str, list[model.Joint]] = {}
    parented: set[str] = set()
    for joint in robot.joints:
        # a link with two parents keeps its first (the one the model's parent_joint names)
        if joint.parent and joint.child and joint.child not in parented:
            parented.add(joint.child)
            children.setdefault(joint.parent, []).append(joint)
    names = [link.name for link in robot.links]
    poses: dict[str, NDArray[np.float64]] = {}
    starts = [name for name in names if name not in parented]
    # a piece with no root (a cycle) is walked from its first link, at the identity
    for start in starts + names:
        if start in poses:
            continue
        poses[start] = np.eye(4)
        stack = [start]
        while stack:
            current = stack.pop()
            for joint in children.get(current, ()):
                child = joint.child
                if child is None or child in poses:
                    continue
                origin = joint_pose(joint)
                poses[child] = poses[current] if origin is None else poses[current] @ origin
                stack.append(child)
    return poses
