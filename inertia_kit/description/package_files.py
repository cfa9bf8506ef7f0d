"""
The file-system side of package discovery, for :mod:`.packages`: checks that never raise on a
path the file system refuses, the ``<name>`` in a ``package.xml``, and the bounded
breadth-first walk below a search root that colcon, catkin and ament would make.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path

from inertia_kit.description import safexml

#: How many folder levels below a package path entry (or a workspace ``src/``) are searched.
MAX_DEPTH = 5
#: Folders visited per search root at most, so that a package path of ``/`` stays bounded.
MAX_FOLDERS = 20_000
#: A ``package.xml`` larger than this is not read.
MAX_PACKAGE_XML_BYTES = 1 << 20
#: Where an install prefix registers its packages (ament_index_python, ``get_package_prefix``).
AMENT_INDEX = Path("share", "ament_index", "resource_index", "packages")

# Folders that colcon, catkin and ament skip, and folders no package lives in.
_IGNORE_MARKERS = ("COLCON_IGNORE", "CATKIN_IGNORE", "AMENT_IGNORE")
_SKIP_NAMES = frozenset({"node_modules", "__pycache__", "build", "install", "log", "devel"})


def package_name(folder: Path) -> str | None:
    """
    The ``<name>`` in ``folder/package.xml``, or ``None`` when there is no readable one.

    The file is parsed without DTDs, entities or network access, and only up to
    :data:`MAX_PACKAGE_XML_BYTES`.
    """
    from lxml import etree

    manifest = folder / "package.xml"
    try:
        if not is_file(manifest) or manifest.stat().st_size > MAX_PACKAGE_XML_BYTES:
            return None
        data = manifest.read_bytes()
    except OSError:
        return None
    try:
        root = etree.fromstring(data, safexml.parser())
    except etree.XMLSyntaxError:
        return None
    name = root.find("name")
    if name is None or not (name.text or "").strip():
        return None
    return name.text.strip()


def _check(test: str, path: Path) -> bool:
    try:
        return getattr(path, test)()
    except (OSError, ValueError):  # a name too long for the file system, a NUL byte
        return False


def is_file(path: Path) -> bool:
    """``path.is_file()``, ``False`` for a path the file system refuses (never raises)."""
    return _check("is_file", path)


def is_dir(path: Path) -> bool:
    """``path.is_dir()``, ``False`` for a path the file system refuses (never raises)."""
    return _check("is_dir", path)


def exists(path: Path) -> bool:
    """``path.exists()``, ``False`` for a path the file system refuses (never raises)."""
    return _check("exists", path)


def normal(path: Path) -> Path:
    """``path`` with ``..`` and ``.`` folded, as text (symbolic links are not followed)."""
    return Path(os.path.normpath(path))


def walk(root: Path) -> Iterator[Path]:
    """Folders below ``root`` (itself included) breadth-first; packages are not descended."""
    level = [root]
    visited = 0
    for depth in range(MAX_DEPTH + 1):
        following: list[Path] = []
        for folder in level:
            visited += 1
            if visited > MAX_FOLDERS:
                return
            yield folder
            if depth == MAX_DEPTH or is_file(folder / "package.xml"):
                continue
            try:
                children = sorted(os.scandir(folder), key=lambda e: e.name)
            except OSError:
                continue
            for child in children:
                if (
                    child.name.startswith(".")
                    or child.name in _SKIP_NAMES
                    or not child.is_dir(follow_symlinks=True)
                ):
                    continue
                path = Path(child.path)
                if any(exists(path / marker) for marker in _IGNORE_MARKERS):
                    continue
                following.append(path)
        level = following
        if not level:
            return


def split_path(value: str) -> tuple[Path, ...]:
    """The folders of a path list (``ROS_PACKAGE_PATH``), empty entries left out."""
    return tuple(Path(p) for p in value.split(os.pathsep) if p.strip())


def folder_of(path: Path) -> Path:
    """``path`` if it is a folder, else the folder holding it."""
    return path if is_dir(path) else path.parent
