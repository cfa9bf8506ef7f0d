"""
Whether a file is an MJCF model: its root element is ``<mujoco>``. Light on purpose: every file
the command line looks at is asked, and the MJCF reader is imported only for those that are.
"""

from __future__ import annotations

import re


def is_mjcf(data: bytes) -> bool:
    """Whether the text's root element is ``<mujoco>`` (read from its first element)."""
    match = re.search(rb"<\s*([A-Za-z_][\w.:-]*)", _skip_prolog(data))
    return match is not None and match.group(1).split(b":")[-1] == b"mujoco"


def _skip_prolog(data: bytes) -> bytes:
    """The text after its declaration, comments and doctype: the first element comes next."""
    text = data[:65536]
    while True:
        stripped = text.lstrip()
        if stripped.startswith(b"<?"):
            end = stripped.find(b"?>")
        elif stripped.startswith(b"<!--"):
            end = stripped.find(b"-->")
        elif stripped.startswith(b"<!"):
            end = stripped.find(b">")
        else:
            return stripped
        if end < 0:
            return b""
        text = stripped[end + 2 :]
