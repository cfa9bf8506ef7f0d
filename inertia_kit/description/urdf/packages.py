"""
ROS package and mesh URI resolution without ROS: ``$(find pkg)``, ``package://pkg/...``,
``file://`` URIs and paths relative to the file that names them, as ROS, Pinocchio and PyBullet
users have them.

A package is looked for by every rule below, in this order
(:data:`~.package_lookup.RULES`); each rule may give candidate folders:

1. ``package-path``: the explicit package paths (``--package-path``). Each entry is a package
   folder itself or a folder holding packages, searched to
   :data:`~.package_files.MAX_DEPTH` levels; a
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

This module resolves URIs (:class:`PackageResolver`, rules 5 and 6 and the choice among
candidates); finding packages (rules 1 to 4, :data:`~.package_lookup.RULES`) is
:mod:`.package_lookup`; the file checks, ``package.xml`` names and bounded walks are
:mod:`.package_files`. Each name is imported from the module that defines it.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from urllib.parse import unquote

from inertia_kit.description.package_files import exists, is_file, normal
from inertia_kit.description.urdf.package_lookup import Candidate, PackageFinder

_FIND = re.compile(r"^\$\(find\s+([^\s)]+)\s*\)(.*)$", re.DOTALL)
_SCHEME = re.compile(r"^([A-Za-z][A-Za-z0-9+.-]*)://")


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


class PackageResolver(PackageFinder):
    """
    Finds ROS packages and resolves mesh URIs, caching what it has looked up; its parameters
    are :class:`~.package_lookup.PackageFinder`'s.
    """

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
            path = normal(place.folder / rest)
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

        def places() -> Iterator[tuple[Path, str, str]]:
            yield base, "next-to-file", "next to the file"
            if search:  # looked for only past the file's own folder: most meshes are there
                for folder, label in self.search_path(base):
                    yield folder, "search-path", f"search path ({label})"

        searched: list[str] = []
        first: Path | None = None
        for folder, rule, label in places():
            path = normal(folder / text)
            if is_file(path):
                return Resolution(path, None, rule, f"{how}{label}", tuple(searched))
            first = first or path
            searched.append(f"{label}: {path}")
        what = "is not a file" if exists(first) else "does not exist"
        return Resolution(first, f"{first} {what}", searched=tuple(searched))

    def _absolute(self, path: Path) -> Resolution:
        path = normal(path)
        # a path ``$(find pkg)`` produced: named by the rule that found the package, and
        # looked up in the package's other candidates when the chosen one does not hold it
        for folder, lookup in self._finds.items():
            if path.is_relative_to(folder):
                rest = path.relative_to(folder)
                for candidate in lookup.candidates:
                    found = normal(candidate.folder.absolute() / rest)
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
