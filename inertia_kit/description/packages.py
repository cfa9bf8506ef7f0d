"""
ROS package and mesh URI resolution without ROS: ``$(find pkg)``, ``package://pkg/...``,
``file://`` URIs and paths relative to the file that names them.

A package is looked up, first hit wins, in

1. explicit package paths (``--package-path``): each entry is a package folder itself or a folder
   holding packages, searched recursively to :data:`MAX_DEPTH` levels;
2. ``ROS_PACKAGE_PATH``, treated the same way;
3. ``AMENT_PREFIX_PATH``: each prefix's ``share/<pkg>`` folder;
4. discovery near the input file: walking up from its folder, a folder whose ``package.xml``
   names the package, a workspace's ``src/`` tree next to an ancestor, or a sibling package.

Within tiers 1, 2 and 4 a ``package.xml`` whose ``<name>`` is the package wins; failing that,
because many published descriptions ship without ``package.xml``, a folder named after the
package counts: an entry itself or a child of an entry (tiers 1 and 2), or an ancestor of the
input (tier 4). Nothing here touches the network, and nothing raises on a missing package.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable, Iterator, Mapping
from pathlib import Path
from urllib.parse import unquote

from inertia_kit.description import safexml

#: How many folder levels below a package path entry (or a workspace ``src/``) are searched.
MAX_DEPTH = 5
#: Folders visited per search root at most, so that a package path of ``/`` stays bounded.
MAX_FOLDERS = 20_000
#: A ``package.xml`` larger than this is not read.
MAX_PACKAGE_XML_BYTES = 1 << 20

# Folders that colcon, catkin and ament skip, and folders no package lives in.
_IGNORE_MARKERS = ("COLCON_IGNORE", "CATKIN_IGNORE", "AMENT_IGNORE")
_SKIP_NAMES = frozenset({"node_modules", "__pycache__", "build", "install", "log", "devel"})
_FIND = re.compile(r"^\$\(find\s+([^\s)]+)\s*\)(.*)$", re.DOTALL)


def package_name(folder: Path) -> str | None:
    """
    The ``<name>`` in ``folder/package.xml``, or ``None`` when there is no readable one.

    The file is parsed without DTDs, entities or network access, and only up to
    :data:`MAX_PACKAGE_XML_BYTES`.
    """
    from lxml import etree

    manifest = folder / "package.xml"
    try:
        if not manifest.is_file() or manifest.stat().st_size > MAX_PACKAGE_XML_BYTES:
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


class PackageResolver:
    """
    Finds ROS packages and resolves mesh URIs, caching what it has looked up.

    Parameters
    ----------
    package_paths : iterable of str or Path
      Searched first, in order: each a package folder or a folder holding packages.
    start : str or Path, optional
      The input file (or its folder): discovery walks up from here when a package is not on
      any path.
    env : mapping, optional
      The environment to read ``ROS_PACKAGE_PATH`` and ``AMENT_PREFIX_PATH`` from; defaults to
      ``os.environ`` (read once, here).
    """

    def __init__(
        self,
        package_paths: Iterable[str | Path] = (),
        *,
        start: str | Path | None = None,
        env: Mapping[str, str] | None = None,
    ):
        env = os.environ if env is None else env
        self.package_paths = tuple(Path(p) for p in package_paths)
        self.ros_package_path = _split_path(env.get("ROS_PACKAGE_PATH", ""))
        self.ament_prefix_path = _split_path(env.get("AMENT_PREFIX_PATH", ""))
        self.start = None if start is None else _folder_of(Path(start))
        self._names: dict[Path, str | None] = {}
        self._indexes: dict[Path, dict[str, Path]] = {}
        self._found: dict[tuple[str, Path | None], Path | None] = {}

    # --- packages ---------------------------------------------------------------------------

    def find(self, name: str, near: str | Path | None = None) -> Path | None:
        """
        The folder of package ``name``, or ``None``.

        ``near`` (a file or folder) is where discovery starts; the resolver's ``start`` is
        tried after it.
        """
        near_dir = None if near is None else _folder_of(Path(near))
        key = (name, near_dir)
        if key not in self._found:
            self._found[key] = self._find(name, near_dir)
        return self._found[key]

    def _find(self, name: str, near: Path | None) -> Path | None:
        for entries in (self.package_paths, self.ros_package_path):
            found = self._in_entries(name, entries)
            if found is not None:
                return found
        for prefix in self.ament_prefix_path:
            share = prefix / "share" / name
            if share.is_dir():
                return share
        for origin in dict.fromkeys(p for p in (near, self.start) if p is not None):
            found = self._discover(name, origin)
            if found is not None:
                return found
        return None

    def _in_entries(self, name: str, entries: tuple[Path, ...]) -> Path | None:
        for entry in entries:
            found = self._index(entry).get(name)
            if found is not None:
                return found
        # The fallback for descriptions published without package.xml.
        for entry in entries:
            if entry.name == name and entry.is_dir() and self._name(entry) is None:
                return entry
            child = entry / name
            if child.is_dir() and self._name(child) is None:
                return child
        return None

    def _discover(self, name: str, origin: Path) -> Path | None:
        folder = origin.absolute()
        for ancestor in (folder, *folder.parents):
            own = self._name(ancestor)
            if own == name or (own is None and ancestor.name == name):
                return ancestor
            if self._name(ancestor / name) == name:
                return ancestor / name
            src = ancestor / "src"
            if src.is_dir():
                found = self._index(src).get(name)
                if found is not None:
                    return found
        return None

    def _name(self, folder: Path) -> str | None:
        if folder not in self._names:
            self._names[folder] = package_name(folder)
        return self._names[folder]

    def _index(self, root: Path) -> dict[str, Path]:
        """``package name -> folder`` below ``root``; the shallowest, then first sorted, wins."""
        if root not in self._indexes:
            index: dict[str, Path] = {}
            for folder in _walk(root):
                name = self._name(folder)
                if name is not None:
                    index.setdefault(name, folder)
            self._indexes[root] = index
        return self._indexes[root]

    # --- URIs -------------------------------------------------------------------------------

    def resolve_uri(self, uri: str, base_dir: str | Path) -> tuple[Path | None, str | None]:
        """
        The file a mesh ``filename`` names, or why there is none.

        Parameters
        ----------
        uri : str
          ``package://pkg/rel``, ``file:///abs``, ``file://rel``, ``$(find pkg)/rel``, an
          absolute path, or a path relative to ``base_dir``.
        base_dir : str or Path
          The folder of the file that names the URI.

        Returns
        -------
        path : Path or None
          The resolved file, also when it does not exist (``problem`` then says so).
        problem : str or None
          What went wrong and what to do about it; ``None`` when ``path`` is an existing file.
          Never raises.
        """
        base = Path(base_dir)
        text = uri.strip()
        if not text:
            return None, "empty mesh filename"
        package_uri = text.startswith("package://")
        find = _FIND.match(text)
        if package_uri or find:
            if package_uri:
                package, _, rest = unquote(text[len("package://") :]).partition("/")
            else:
                package, rest = find.group(1), find.group(2).lstrip("/")
            if not package:
                return None, f"`{uri}` names no package"
            folder = self.find(package, base)
            if folder is None:
                return None, (
                    f"package `{package}` not found (searched --package-path, ROS_PACKAGE_PATH, "
                    f"AMENT_PREFIX_PATH and the folders above {base}): pass "
                    f"--package-path DIR with the package folder or a folder that holds it"
                )
            return _existing(folder / rest, f" (package `{package}` is {folder})")
        if text.startswith("file:"):
            rest = unquote(text[len("file:") :])
            if rest.startswith("//"):
                rest = rest[2:]
                if rest.startswith("localhost/"):
                    rest = rest[len("localhost") :]
            path = Path(rest)
            return _existing(path if path.is_absolute() else base / path, "")
        scheme = re.match(r"^([A-Za-z][A-Za-z0-9+.-]*)://", text)
        if scheme:
            return None, (
                f"`{scheme.group(1)}://` URIs are not resolved (nothing is fetched): use "
                f"package://, file:// or a path relative to the file"
            )
        path = Path(text)
        return _existing(path if path.is_absolute() else base / path, "")


def resolve_uri(
    uri: str, base_dir: str | Path, resolver: PackageResolver | None = None
) -> tuple[Path | None, str | None]:
    """:meth:`PackageResolver.resolve_uri` with a default resolver started at ``base_dir``."""
    if resolver is None:
        resolver = PackageResolver(start=base_dir)
    return resolver.resolve_uri(uri, base_dir)


def _existing(path: Path, context: str) -> tuple[Path, str | None]:
    path = Path(os.path.normpath(path))
    if path.is_file():
        return path, None
    if path.exists():
        return path, f"{path} is not a file{context}"
    return path, f"{path} does not exist{context}"


def _walk(root: Path) -> Iterator[Path]:
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
            if depth == MAX_DEPTH or (folder / "package.xml").is_file():
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
                if any((path / marker).exists() for marker in _IGNORE_MARKERS):
                    continue
                following.append(path)
        level = following
        if not level:
            return


def _split_path(value: str) -> tuple[Path, ...]:
    return tuple(Path(p) for p in value.split(os.pathsep) if p.strip())


def _folder_of(path: Path) -> Path:
    return path if path.is_dir() else path.parent
