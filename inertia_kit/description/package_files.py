"""
The file-system side of package discovery, for :mod:`.packages`: checks that never raise on a
path the file system refuses, the ``<name>`` in a ``package.xml``, and the bounded
breadth-first walk below a search root that colcon, catkin and ament would make.
"""

from __future__ import annotations

import contextlib
import itertools
import os
from collections.abc import Iterator
from pathlib import Path

from inertia_kit.description import safexml
from inertia_kit.errors import InputError
from inertia_kit.reading import read_regular

#: How many folder levels below a package path entry (or a workspace ``src/``) are searched.
MAX_DEPTH = 5
#: Folders visited per search root at most, so that a package path of ``/`` stays bounded.
MAX_FOLDERS = 20_000
#: Folders visited by all the walks of one package search (a file deep in a tree with a
#: ``src`` folder at every level walks each of them).
MAX_FOLDERS_IN_ALL = 100_000
#: Entries read from one folder at most.
MAX_ENTRIES = 50_000
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
    if not is_file(manifest):
        return None
    try:
        data = read_regular(manifest, MAX_PACKAGE_XML_BYTES)
    except InputError:
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


def walk(root: Path, limit: int = MAX_FOLDERS) -> Iterator[Path]:
    """
    Folders below ``root`` (itself included) breadth-first, at most ``limit`` (and
    :data:`MAX_FOLDERS`) of them; packages are not descended. Each folder is visited once
    however many links lead to it (a link to a parent, a loop of links), and a folder that
    cannot be listed or a link that cannot be followed is passed over.
    """
    limit = min(limit, MAX_FOLDERS)
    level = [root]
    visited = 0
    seen: set[tuple[int, int]] = set()
    with contextlib.suppress(OSError):
        status = root.stat()
        seen.add((status.st_dev, status.st_ino))
    for depth in range(MAX_DEPTH + 1):
        following: list[Path] = []
        for folder in level:
            visited += 1
            if visited > limit:
                return
            yield folder
            if depth == MAX_DEPTH or is_file(folder / "package.xml"):
                continue
            for child in folder_entries(folder):
                if child.name.startswith(".") or child.name in _SKIP_NAMES:
                    continue
                identity = _folder_identity(child)
                if identity is None or identity in seen:
                    continue
                seen.add(identity)
                path = Path(child.path)
                if any(exists(path / marker) for marker in _IGNORE_MARKERS):
                    continue
                following.append(path)
        level = following
        if not level:
            return


def folder_entries(folder: Path, limit: int | None = None) -> list[os.DirEntry]:
    """
    The entries of ``folder`` sorted by name, at most ``limit`` (default :data:`MAX_ENTRIES`)
    of them read, so a folder of a million files stays cheap; none when it cannot be listed.
    """
    try:
        with os.scandir(folder) as scan:
            read = itertools.islice(scan, MAX_ENTRIES if limit is None else limit)
            return sorted(read, key=lambda e: e.name)
    except (OSError, ValueError):
        return []


def entry_is_dir(entry: os.DirEntry) -> bool:
    """Whether ``entry`` is a folder or a link to one; ``False`` for a link that cannot be
    followed (dangling, a loop of links), never raising."""
    try:
        return entry.is_dir(follow_symlinks=True)
    except OSError:
        return False


def entry_is_file(entry: os.DirEntry) -> bool:
    """Whether ``entry`` is a regular file or a link to one, never raising."""
    try:
        return entry.is_file(follow_symlinks=True)
    except OSError:
        return False


def _folder_identity(entry: os.DirEntry) -> tuple[int, int] | None:
    """``(device, inode)`` of the folder ``entry`` is or leads to; ``None``: not a folder."""
    try:
        if not entry.is_dir(follow_symlinks=True):
            return None
        status = entry.stat(follow_symlinks=True)
    except OSError:
        return None
    return status.st_dev, status.st_ino


def split_path(value: str) -> tuple[Path, ...]:
    """The folders of a path list (``ROS_PACKAGE_PATH``), empty entries left out."""
    return tuple(Path(p) for p in value.split(os.pathsep) if p.strip())


def folder_of(path: Path) -> Path:
    """``path`` if it is a folder, else the folder holding it."""
    return path if is_dir(path) else path.parent
