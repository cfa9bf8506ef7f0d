"""
Which files a run lints: the files given, and the robot files (``*.urdf``, ``*.xacro``) of the
folders given, each once.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable, Iterator
from pathlib import Path

# folders expansion never enters: hidden ones (.git, .venv) and Python caches
_SKIPPED_FOLDERS = ("__pycache__",)
#: a robot file's name, case ignored: the folder walk and the pre-commit hooks' `files:` pattern
#: (.pre-commit-hooks.yaml, checked equal by a test) pick the same files (`GEN.URDF` too)
ROBOT_FILE = r"(?i)\.(urdf|xacro)$"
_ROBOT_FILE = re.compile(ROBOT_FILE)


def expand_paths(paths: Iterable[str | Path]) -> Iterator[Path]:
    """
    Files as given; folders searched for ``*.urdf``, ``*.xacro`` (``*.urdf.xacro`` too; case
    ignored, :data:`ROBOT_FILE`), in sorted order, hidden folders (``.git``) not entered. Each
    file once.
    """
    seen: set[str] = set()
    for entry in paths:
        path = Path(entry)
        found = _robot_files(path) if path.is_dir() else [path]
        for file in found:
            key = os.path.normcase(os.path.abspath(file))
            if key not in seen:
                seen.add(key)
                yield file


def _robot_files(folder: Path) -> list[Path]:
    files = []
    for top, folders, names in os.walk(folder):
        folders[:] = sorted(
            f for f in folders if not f.startswith(".") and f not in _SKIPPED_FOLDERS
        )
        files.extend(Path(top, name) for name in names if _ROBOT_FILE.search(name))
    return sorted(f for f in files if f.is_file())
