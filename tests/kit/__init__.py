"""
The shared test kit: where the repository is, and the builders the tests share.

- ``kit.urdf``: robot texts, one element at a time (links, joints, ``<inertial>`` blocks, boxes,
  cylinders, spheres and meshes as geometry), and a moving link on a base.
- ``kit.moments``: mass and moments of solid boxes, cylinders and spheres, from closed forms.
- ``kit.meshes``: triangles of a box, and the STL and OBJ files written from triangles.

``write`` puts any of them in a file; ``remove_tree`` removes a folder however deep;
``least_cpu`` times a call for the tests that check a command is linear in its input.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parent.parent.parent
EXAMPLES = REPO / "examples"


def remove_tree(path: Path) -> None:
    """
    ``path`` and all below it, without recursion (shutil.rmtree recurses: a folder 1000 deep is
    a RecursionError), unreadable folders included.
    """
    stack = [(os.fspath(path), False)]
    while stack:
        here, emptied = stack.pop()
        if os.path.islink(here) or not os.path.isdir(here):
            if os.path.lexists(here):
                os.unlink(here)
        elif emptied:
            os.rmdir(here)
        else:
            os.chmod(here, 0o700)
            stack.append((here, True))
            with os.scandir(here) as entries:
                stack.extend((entry.path, False) for entry in entries)


def write(path: Path, content: str | bytes) -> Path:
    """``content`` written to ``path`` as is (UTF-8, no newline translation), its folder made."""
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(content.encode("utf-8") if isinstance(content, str) else content)
    return path


def least_cpu(
    call: Callable[[], Any], runs: int = 3, before: Callable[[], Any] | None = None
) -> tuple[float, list[Any]]:
    """
    The least CPU time of ``runs`` calls of ``call`` (s), each after ``before`` (untimed: a
    cache to clear), and what each call returned: the linearity tests compare 8 times an input
    against it once, the least of a few runs being steady on a busy machine.
    """
    least, results = float("inf"), []
    for _ in range(runs):
        if before is not None:
            before()
        began = time.process_time()
        results.append(call())
        least = min(least, time.process_time() - began)
    return least, results
