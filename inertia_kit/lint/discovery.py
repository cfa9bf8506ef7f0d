"""
Which files a run lints: the files given, and the robot files (``*.urdf``, ``*.xacro``) of the
folders given, each once.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Iterator
from pathlib import Path

# folders expansion never enters: hidden ones (.git, .venv) and Python caches
_SKIPPED_FOLDERS = ("__pycache__",)


def expand_paths(paths: Iterable[str | Path]) -> Iterator[Path]:
    """
    Files as given; folders searched for ``*.urdf``, ``*.xacro`` (``*.urdf.xacro`` too), in
    sorted order, hidden folders (``.git``) not entered. Each file once.
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
        files.extend(Path(top, name) for name in names if name.endswith((".urdf", ".xacro")))
    return sorted(f for f in files if f.is_file())
