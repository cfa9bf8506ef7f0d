"""
ROS package and mesh URI resolution without ROS: ``$(find pkg)``, ``package://pkg/...``,
``file://`` URIs and paths relative to the file that names them, as ROS, Pinocchio and PyBullet
users have them.

A package is looked for by every rule below, in this order (:data:`RULES`); each rule may give
candidate folders:

1. ``package-path``: the explicit package paths (``--package-path``). Each entry is a package
   folder itself or a folder holding packages, searched to :data:`MAX_DEPTH` levels; a
   ``package.xml`` whose ``<name>`` is the package wins, and, because many published
   descriptions ship without one, a folder named after the package with no ``package.xml``
   counts (the entry itself or a child of it);
2. ``ros-package-path``: ``ROS_PACKAGE_PATH``, treated the same way;
3. ``ament``: ``share/<pkg>`` of every install prefix whose ament resource index
   (``share/ament_index/resource_index/packages/<pkg>``) registers the package: prefixes of
   ``AMENT_PREFIX_PATH`` (where a ``share/<pkg>`` folder also counts without the index, as
   before ament), prefixes given as a package path (the prefix or its ``share`` folder), and
   prefixes found above the file;
4. ``enclosing-package``: walking up from the file, a folder whose ``package.xml`` names the
   package or that is named like it (whatever its ``package.xml`` says), a sibling package, or
   a workspace's ``src/`` tree next to an ancestor.

A ``package://pkg/rest`` URI resolves to the first candidate holding ``rest``. When no candidate
does, it is taken as PyBullet and Pinocchio take it, ``package://`` stripped:

5. ``next-to-file``: ``pkg/rest`` relative to the file (PyBullet);
6. ``search-path``: ``pkg/rest`` under each package path, ``ROS_PACKAGE_PATH`` entry and ament
   prefix's ``share`` folder (PyBullet's search path, Pinocchio's package directories).

A relative path takes rules 5 and 6 itself. When candidates disagree, the one where the mesh
file exists wins; when none has it, the first is reported, with every place searched. Nothing
here touches the network, and nothing raises on a missing package or file.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from urllib.parse import unquote

from inertia_kit.description import safexml

#: How many folder levels below a package path entry (or a workspace ``src/``) are searched.
MAX_DEPTH = 5
#: Folders visited per search root at most, so that a package path of ``/`` stays bounded.
MAX_FOLDERS = 20_000
#: A ``package.xml`` larger than this is not read.
MAX_PACKAGE_XML_BYTES = 1 << 20
#: Where an install prefix registers its packages (ament_index_python, ``get_package_prefix``).
AMENT_INDEX = Path("share", "ament_index", "resource_index", "packages")

#: The rules in the order they are tried: ``id -> (label, what it searches)``. ``report``
#: names the rule that resolved each mesh by its id; messages use the label.
RULES: dict[str, tuple[str, str]] = {
    "package-path": (
        "--package-path",
        "each entry: the package itself, a package below it (by package.xml name, "
        f"{MAX_DEPTH} levels), or a folder named like the package without package.xml",
    ),
    "ros-package-path": ("ROS_PACKAGE_PATH", "each entry, as --package-path"),
    "ament": (
        "ament index",
        "PREFIX/share/PKG of each install prefix whose share/ament_index/resource_index/"
        "packages/PKG registers the package: AMENT_PREFIX_PATH, a prefix given as "
        "--package-path (or its share folder), a prefix above the file",
    ),
    "enclosing-package": (
        "enclosing package",
        "above the file: a folder whose package.xml names the package or named like it, "
        "a sibling package, a workspace src/ tree",
    ),
    "next-to-file": (
        "next to the file",
        "a relative path, or a package:// URI with package:// stripped (PyBullet), relative "
        "to the file that names it",
    ),
    "search-path": (
        "search path",
        "the same under each --package-path entry, ROS_PACKAGE_PATH entry and ament prefix's "
        "share folder (PyBullet's search path, Pinocchio's package directories)",
    ),
    "absolute": ("absolute path", "an absolute path or a file:// URI"),
}

# Folders that colcon, catkin and ament skip, and folders no package lives in.
_IGNORE_MARKERS = ("COLCON_IGNORE", "CATKIN_IGNORE", "AMENT_IGNORE")
_SKIP_NAMES = frozenset({"node_modules", "__pycache__", "build", "install", "log", "devel"})
_FIND = re.compile(r"^\$\(find\s+([^\s)]+)\s*\)(.*)$", re.DOTALL)
_SCHEME = re.compile(r"^([A-Za-z][A-Za-z0-9+.-]*)://")


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


@dataclass(frozen=True)
class Candidate:
    """A folder that one rule gives for a package: ``how`` says why (for messages)."""

    folder: Path
    rule: str
    how: str

    def describe(self) -> str:
        return f"{RULES[self.rule][0]}, {self.how}"


@dataclass(frozen=True)
class Lookup:
    """
    What the rules found for one package, in the order searched: each place is a
    :class:`Candidate` or, where a rule's search gave nothing, a string saying so
    (``"ROS_PACKAGE_PATH: not set"``), so that a message can name every place searched.
    """

    name: str
    places: tuple[Candidate | str, ...]

    @property
    def candidates(self) -> tuple[Candidate, ...]:
        """The candidate folders by precedence, each once (under the first rule giving it)."""
        return tuple(p for p in self.places if isinstance(p, Candidate))


@dataclass(frozen=True)
class Resolution:
    """
    Where a mesh URI led.

    Attributes
    ----------
    path : Path or None
      The resolved file; when ``problem`` is set, the first place it was expected (or ``None``).
    problem : str or None
      Why there is no file, and what to do; ``None`` when ``path`` is an existing file.
    rule : str or None
      The :data:`RULES` id that resolved it; ``None`` when nothing did.
    how : str
      The resolving rule in words (``package `arm` is /ws/arm (package.xml names it)``).
    searched : tuple of str
      Every place looked at, in order, each as ``label: place``; on success, those before the
      one that held the file.
    """

    path: Path | None
    problem: str | None
    rule: str | None = None
    how: str = ""
    searched: tuple[str, ...] = ()


class PackageResolver:
    """
    Finds ROS packages and resolves mesh URIs, caching what it has looked up.

    Parameters
    ----------
    package_paths : iterable of str or Path
      Searched first, in order: each a package folder or a folder holding packages; also
      PyBullet's search path for relative meshes.
    start : str or Path, optional
      The input file (or its folder): discovery walks up from here after the folder of the
      file that names a package.
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
        self._lookups: dict[tuple[str, Path | None], Lookup] = {}
        self._prefixes: dict[tuple[Path, ...], tuple[tuple[Path, str], ...]] = {}
        # folders ``$(find)`` gave: a path below one is labelled with the rule that chose it
        self._finds: dict[Path, Lookup] = {}

    # --- packages ---------------------------------------------------------------------------

    def find(self, name: str, near: str | Path | None = None, rest: str = "") -> Path | None:
        """
        The folder of package ``name``, or ``None``.

        ``near`` (a file or folder) is where discovery starts; the resolver's ``start`` is
        tried after it. With ``rest`` (what follows ``$(find pkg)/``), the first candidate
        that holds it wins, as for a mesh; otherwise the first candidate.
        """
        lookup = self.lookup(name, near)
        found = lookup.candidates
        if not found:
            return None
        chosen = found[0]
        rest = rest.strip("/")
        if rest:
            chosen = next((c for c in found if exists(c.folder / rest)), chosen)
        self._finds.setdefault(_normal(chosen.folder.absolute()), lookup)
        return chosen.folder

    def lookup(self, name: str, near: str | Path | None = None) -> Lookup:
        """Every candidate folder for package ``name``, by rule, and where nothing was."""
        near_dir = None if near is None else _folder_of(Path(near))
        key = (name, near_dir)
        if key not in self._lookups:
            self._lookups[key] = self._lookup(name, near_dir)
        return self._lookups[key]

    def _lookup(self, name: str, near: Path | None) -> Lookup:
        places: list[Candidate | str] = []
        seen: set[Path] = set()

        def add(hits: Iterable[Candidate], miss: str) -> None:
            found = False
            for candidate in hits:
                found = True
                folder = _normal(candidate.folder.absolute())
                if folder not in seen:
                    seen.add(folder)
                    places.append(candidate)
            if not found:
                places.append(miss)

        origins = self._origins(near)
        if not self.package_paths:
            places.append("--package-path: none given")
        for entry in self.package_paths:
            add(self._in_entry(name, entry, "package-path"), f"--package-path {entry}: no `{name}`")
        if not self.ros_package_path:
            places.append("ROS_PACKAGE_PATH: not set")
        for entry in self.ros_package_path:
            add(
                self._in_entry(name, entry, "ros-package-path"),
                f"ROS_PACKAGE_PATH {entry}: no `{name}`",
            )
        prefixes = ", ".join(str(p) for p, _ in self._ament_prefixes(origins))
        add(
            self._ament(name, origins),
            f"ament index: `{name}` not registered under {prefixes}"
            if prefixes
            else "ament index: no prefix (AMENT_PREFIX_PATH not set, none given or above the file)",
        )
        above = " or ".join(str(o.absolute()) for o in origins)
        add(
            (c for origin in origins for c in self._enclosing(name, origin)),
            f"enclosing package: no `{name}` above {above}"
            if above
            else "enclosing package: no file",
        )
        return Lookup(name, tuple(places))

    def _origins(self, near: Path | None) -> tuple[Path, ...]:
        """Where walks up start: ``near``, then ``start`` unless its walk is part of near's."""
        origins: list[Path] = []
        for origin in (near, self.start):
            if origin is None:
                continue
            origin = _normal(origin.absolute())
            if not any(origin == o or origin in o.parents for o in origins):
                origins.append(origin)
        return tuple(origins)

    def _in_entry(self, name: str, entry: Path, rule: str) -> Iterator[Candidate]:
        found = self._index(entry).get(name)
        if found is not None:
            yield Candidate(found, rule, f"package.xml names it, in {entry}")
        # the fallback for descriptions published without package.xml
        for folder in (entry, entry / name):
            if folder.name == name and is_dir(folder) and self._name(folder) is None:
                yield Candidate(folder, rule, "folder named like the package, no package.xml")

    def _ament(self, name: str, origins: tuple[Path, ...]) -> Iterator[Candidate]:
        for prefix, where in self._ament_prefixes(origins):
            share = prefix / "share" / name
            if is_file(prefix / AMENT_INDEX / name) and is_dir(share):
                yield Candidate(
                    share, "ament", f"registered in the ament index of {where} {prefix}"
                )
            elif where == "AMENT_PREFIX_PATH" and is_dir(share):
                yield Candidate(share, "ament", f"share folder of AMENT_PREFIX_PATH {prefix}")

    def _ament_prefixes(self, origins: tuple[Path, ...]) -> tuple[tuple[Path, str], ...]:
        """Install prefixes, each with where it came from: AMENT_PREFIX_PATH, given, above."""
        key = origins
        if key not in self._prefixes:
            prefixes = [(p, "AMENT_PREFIX_PATH") for p in self.ament_prefix_path]
            for entry in self.package_paths:
                if is_dir(entry / AMENT_INDEX):
                    prefixes.append((entry, "the prefix given"))
                elif entry.name == "share" and is_dir(entry.parent / AMENT_INDEX):
                    prefixes.append((entry.parent, "the prefix given"))
            for origin in origins:
                for ancestor in (origin.absolute(), *origin.absolute().parents):
                    if is_dir(ancestor / AMENT_INDEX):
                        prefixes.append((ancestor, "the prefix above the file"))
            unique: dict[Path, tuple[Path, str]] = {}
            for prefix, where in prefixes:
                unique.setdefault(_normal(prefix), (prefix, where))
            self._prefixes[key] = tuple(unique.values())
        return self._prefixes[key]

    def _enclosing(self, name: str, origin: Path) -> Iterator[Candidate]:
        folder = origin.absolute()
        for ancestor in (folder, *folder.parents):
            own = self._name(ancestor)
            if own == name:
                yield Candidate(ancestor, "enclosing-package", "its package.xml names it")
            elif ancestor.name == name:
                named = "" if own is None else f" (its package.xml says `{own}`)"
                yield Candidate(
                    ancestor, "enclosing-package", f"folder named like the package{named}"
                )
            if self._name(ancestor / name) == name:
                yield Candidate(ancestor / name, "enclosing-package", f"a package in {ancestor}")
            src = ancestor / "src"
            if is_dir(src):
                found = self._index(src).get(name)
                if found is not None:
                    yield Candidate(found, "enclosing-package", f"in the workspace {src}")

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

    def search_path(self, near: str | Path | None = None) -> tuple[tuple[Path, str], ...]:
        """
        Folders a relative mesh path is looked up under after the file's own folder (rule
        ``search-path``), each with its label: the package paths, ``ROS_PACKAGE_PATH``, and the
        ``share`` folder of each ament prefix.
        """
        near_dir = None if near is None else _folder_of(Path(near))
        origins = self._origins(near_dir)
        folders = [(p, "--package-path") for p in self.package_paths]
        folders += [(p, "ROS_PACKAGE_PATH") for p in self.ros_package_path]
        folders += [(p / "share", "ament prefix") for p, _ in self._ament_prefixes(origins)]
        unique: dict[Path, tuple[Path, str]] = {}
        for folder, label in folders:
            unique.setdefault(_normal(folder), (folder, label))
        return tuple(unique.values())

    # --- URIs -------------------------------------------------------------------------------

    def resolve_uri(self, uri: str, base_dir: str | Path) -> tuple[Path | None, str | None]:
        """:meth:`resolve` as ``(path, problem)``."""
        found = self.resolve(uri, base_dir)
        return found.path, found.problem

    def resolve(self, uri: str, base_dir: str | Path) -> Resolution:
        """
        The file a mesh ``filename`` names, by which rule, or why there is none.

        Parameters
        ----------
        uri : str
          ``package://pkg/rest``, ``file:///abs``, ``file://rel``, ``$(find pkg)/rest``, an
          absolute path, or a path relative to ``base_dir``.
        base_dir : str or Path
          The folder of the file that names the URI.

        Returns
        -------
        resolution : Resolution
          Never raises.
        """
        base = Path(base_dir)
        text = uri.strip()
        if not text:
            return Resolution(None, "empty mesh filename")
        package_uri = text.startswith("package://")
        find = _FIND.match(text)
        if package_uri or find:
            if package_uri:
                stripped = unquote(text[len("package://") :])
                package, _, rest = stripped.partition("/")
            else:
                stripped = ""  # $(find) is ROS only: nothing to strip for PyBullet
                package, rest = find.group(1), find.group(2).lstrip("/")
            return self._package(uri, package, rest, stripped, base)
        if text.startswith("file:"):
            rest = unquote(text[len("file:") :])
            if rest.startswith("//"):
                rest = rest[2:]
                if rest.startswith("localhost/"):
                    rest = rest[len("localhost") :]
            path = Path(rest)
            if path.is_absolute():
                return self._absolute(path)
            return self._relative(rest, base, search=False)
        scheme = _SCHEME.match(text)
        if scheme:
            return Resolution(
                None,
                f"`{scheme.group(1)}://` URIs are not resolved (nothing is fetched): use "
                f"package://, file:// or a path relative to the file",
            )
        if Path(text).is_absolute():
            return self._absolute(Path(text))
        return self._relative(text, base, search=True)

    def _package(self, uri: str, package: str, rest: str, stripped: str, base: Path) -> Resolution:
        searched: list[str] = []
        first: tuple[Path, Candidate] | None = None
        for place in self.lookup(package, base).places if package else ():
            if isinstance(place, str):
                searched.append(place)
                continue
            path = _normal(place.folder / rest)
            if is_file(path):
                how = f"package `{package}` is {place.folder} ({place.how})"
                return Resolution(path, None, place.rule, how, tuple(searched))
            first = first or (path, place)
            searched.append(f"{place.describe()}: {path}")
        if stripped.strip("/"):
            found = self._relative(stripped.lstrip("/"), base, search=True, stripped=True)
            if found.problem is None:
                return Resolution(
                    found.path, None, found.rule, found.how, (*searched, *found.searched)
                )
            searched += found.searched
        if not package:
            return Resolution(None, f"`{uri}` names no package", searched=tuple(searched))
        if first is None:
            return Resolution(
                None,
                f"package `{package}` not found: pass --package-path DIR with the package "
                "folder or a folder that holds it",
                searched=tuple(searched),
            )
        path, candidate = first
        what = "is not a file" if exists(path) else "does not exist"
        return Resolution(
            path,
            f"{path} {what} (package `{package}` is {candidate.folder}, {candidate.describe()})",
            searched=tuple(searched),
        )

    def _relative(
        self, text: str, base: Path, *, search: bool, stripped: bool = False
    ) -> Resolution:
        """Rules ``next-to-file`` then (with ``search``) ``search-path``."""
        how = "package:// stripped, as PyBullet and Pinocchio read it; " if stripped else ""
        places = [(base, "next-to-file", "next to the file")]
        if search:
            places += [
                (folder, "search-path", f"search path ({label})")
                for folder, label in self.search_path(base)
            ]
        searched: list[str] = []
        first: Path | None = None
        for folder, rule, label in places:
            path = _normal(folder / text)
            if is_file(path):
                return Resolution(path, None, rule, f"{how}{label}", tuple(searched))
            first = first or path
            searched.append(f"{label}: {path}")
        what = "is not a file" if exists(first) else "does not exist"
        return Resolution(first, f"{first} {what}", searched=tuple(searched))

    def _absolute(self, path: Path) -> Resolution:
        path = _normal(path)
        # a path ``$(find pkg)`` produced: named by the rule that found the package, and
        # looked up in the package's other candidates when the chosen one does not hold it
        for folder, lookup in self._finds.items():
            if path.is_relative_to(folder):
                rest = path.relative_to(folder)
                for candidate in lookup.candidates:
                    found = _normal(candidate.folder.absolute() / rest)
                    if is_file(found):
                        how = f"$(find {lookup.name}) is {candidate.folder} ({candidate.how})"
                        return Resolution(found, None, candidate.rule, how)
                break
        if is_file(path):
            return Resolution(path, None, "absolute", "absolute path")
        what = "is not a file" if exists(path) else "does not exist"
        return Resolution(path, f"{path} {what}", searched=(f"absolute path: {path}",))


def resolve_uri(
    uri: str, base_dir: str | Path, resolver: PackageResolver | None = None
) -> tuple[Path | None, str | None]:
    """:meth:`PackageResolver.resolve_uri` with a default resolver started at ``base_dir``."""
    if resolver is None:
        resolver = PackageResolver(start=base_dir)
    return resolver.resolve_uri(uri, base_dir)


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


def _normal(path: Path) -> Path:
    return Path(os.path.normpath(path))


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


def _split_path(value: str) -> tuple[Path, ...]:
    return tuple(Path(p) for p in value.split(os.pathsep) if p.strip())


def _folder_of(path: Path) -> Path:
    return path if is_dir(path) else path.parent
