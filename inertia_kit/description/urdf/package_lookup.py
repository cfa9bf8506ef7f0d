"""
Finding ROS packages, for :mod:`.packages` (whose docstring gives the order): :data:`RULES`, every
resolution rule by id, and the four that give candidate folders for a package (package paths,
``ROS_PACKAGE_PATH``, the ament index, the enclosing package), tried in order by
:class:`PackageFinder`, which caches what it has read; and the folders a relative mesh path is
searched under (rule ``search-path``).
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path

from inertia_kit.description.package_files import (
    AMENT_INDEX,
    MAX_DEPTH,
    MAX_FOLDERS_IN_ALL,
    exists,
    folder_of,
    is_dir,
    is_file,
    normal,
    package_name,
    split_path,
    walk,
)

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


class PackageFinder:
    """
    Finds ROS packages, caching what it has looked up (:class:`~.packages.PackageResolver`
    adds mesh URIs).

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
        self.ros_package_path = split_path(env.get("ROS_PACKAGE_PATH", ""))
        self.ament_prefix_path = split_path(env.get("AMENT_PREFIX_PATH", ""))
        self.start = None if start is None else folder_of(Path(start))
        self._names: dict[Path, str | None] = {}
        self._indexes: dict[Path, dict[str, Path]] = {}
        self._folders_left = MAX_FOLDERS_IN_ALL  # what the walks may still visit, together
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
        self._finds.setdefault(normal(chosen.folder.absolute()), lookup)
        return chosen.folder

    def lookup(self, name: str, near: str | Path | None = None) -> Lookup:
        """Every candidate folder for package ``name``, by rule, and where nothing was."""
        near_dir = None if near is None else folder_of(Path(near))
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
                folder = normal(candidate.folder.absolute())
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
            origin = normal(origin.absolute())
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
                unique.setdefault(normal(prefix), (prefix, where))
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
            for folder in walk(root, self._folders_left):
                self._folders_left -= 1
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
        near_dir = None if near is None else folder_of(Path(near))
        origins = self._origins(near_dir)
        folders = [(p, "--package-path") for p in self.package_paths]
        folders += [(p, "ROS_PACKAGE_PATH") for p in self.ros_package_path]
        folders += [(p / "share", "ament prefix") for p, _ in self._ament_prefixes(origins)]
        unique: dict[Path, tuple[Path, str]] = {}
        for folder, label in folders:
            unique.setdefault(normal(folder), (folder, label))
        return tuple(unique.values())
