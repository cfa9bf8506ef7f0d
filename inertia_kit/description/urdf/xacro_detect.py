"""
Whether a file is xacro, by content. Apart from :mod:`.xacro_expand` so that loading a plain
URDF, which asks this of every file, does not import the expansion machinery (its sandbox,
limits, source map and session hooks).
"""

from __future__ import annotations

import re
from typing import Any

_IS_XACRO = re.compile(rb"xmlns:xacro\s*=|<\s*xacro:[A-Za-z_]")


def is_xacro(data: bytes) -> bool:
    """Whether ``data`` is xacro by content: the xacro namespace declared or ``xacro:`` tags."""
    return _IS_XACRO.search(data) is not None


def is_fragment(root: Any) -> bool:
    """
    Whether a xacro file's root (expanded, or as written when nothing in it needs expanding)
    is a ``<robot>`` with no ``<link>`` and no ``<joint>``: macros and properties, materials,
    ``<gazebo>`` or ``<transmission>`` blocks, a placeholder. It only adds to the robots that
    include it: a fragment, whatever tags its top holds. (Another root is not a robot at all,
    and the loader says so.)
    """
    return root.tag == "robot" and not any(child.tag in ("link", "joint") for child in root)
