"""
Whether a file is xacro, by content. Apart from :mod:`.xacro_expand` so that loading a plain
URDF, which asks this of every file, does not import the expansion machinery (its sandbox,
limits, source map and session hooks).
"""

from __future__ import annotations

import re

_IS_XACRO = re.compile(rb"xmlns:xacro\s*=|<\s*xacro:[A-Za-z_]")


def is_xacro(data: bytes) -> bool:
    """Whether ``data`` is xacro by content: the xacro namespace declared or ``xacro:`` tags."""
    return _IS_XACRO.search(data) is not None
