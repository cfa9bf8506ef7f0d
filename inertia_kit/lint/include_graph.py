"""
Which robots of a repository read which files: the include graph that lets a hook lint the
robots that include a changed xacro fragment.

A repository's robot files are found by the folder walk ``inertia-lint`` does (``*.urdf``,
``*.xacro``, hidden folders skipped). Each is classed by a cheap first pass on its text: a file
that is no xacro at work, or names neither ``include`` nor ``load_yaml``, reads no other file,
so it includes nothing and is not expanded. Every other file is expanded with xacro as the
linter would expand it (the same ``--xacro-arg`` values and package paths; ``$(find pkg)``
resolved by the package resolver), and the files the expansion read (the xacro sandbox records
each one) are its includes, direct and indirect. A file whose expansion makes links is a robot;
a fragment includes nobody's robot. A file xacro refuses counts as a robot that reads the file
the error names (a fragment the change broke) and, if it was a robot before, what it read
then: linted for those files, it reports the error.

The first pass picks no robots by name: includes are often computed
(``$(find ${pkg})/urdf/${name}.xacro``), so a file's text cannot say what it includes; the
on-disk cache (:mod:`.include_cache`) keeps a warm run to one ``stat`` per file read. When a
run asks only for the includers of some files (``wanted``: the files a hook or a user gives),
a robot whose includes are all written out and reach none of them
(:mod:`~inertia_kit.description.urdf.xacro_includes`) cannot be one, and is not expanded: a
robot given to the linter no longer costs the expansion of every other robot of its
repository.
"""

from __future__ import annotations

import functools
import os
import time
from collections.abc import Callable, Collection, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from inertia_kit.description.xacro_limits import XacroLimits
    from inertia_kit.lint.include_cache import Entry, Stamp


@dataclass
class IncludeGraph:
    """
    The robots of one repository (``root``) and the files each read, by real path.
    ``scanned`` and ``reused`` count the files expanded in this run and taken from the cache;
    ``passed`` those left unexpanded because they cannot include a wanted file.
    """

    root: Path
    robots: dict[str, tuple[str, ...]] = field(default_factory=dict)
    scanned: int = 0
    reused: int = 0
    passed: int = 0  # robots not expanded: their includes as written reach no wanted file

    def includers(self, file: str | Path) -> list[str]:
        """The robots (real paths, sorted) that read ``file``, ``file`` itself left out."""
        key = real(file)
        return sorted(robot for robot, read in self.robots.items() if robot != key and key in read)


def real(path: str | Path) -> str:
    """The path a file is known by in the graph: absolute, symbolic links resolved."""
    return os.path.realpath(os.path.abspath(path))


def include_graph(
    root: str | Path,
    *,
    xacro_args: Mapping[str, str] | None = None,
    package_paths: Sequence[str | Path] = (),
    xacro_limits: XacroLimits | None = None,
    cache_dir: str | Path | None = None,
    wanted: Collection[str | Path] | None = None,
) -> IncludeGraph:
    """
    The include graph of the repository at ``root``, from the cache where the files are as
    they were (each robot file's size and mtime, and those of every file it read), re-scanned
    where they are not; the cache is then brought up to date.

    ``wanted``: only the includers of these files are asked for. A file to scan whose
    includes, as written, cannot reach one of them (``loader.files_reached``) is not expanded,
    and its closure is kept as a ``static`` entry (:class:`_Reach`): the graph is then complete
    for the wanted files only.
    """
    # the cache (and json) only when a repository is scanned: not for a plain URDF
    from inertia_kit.lint.discovery import expand_paths
    from inertia_kit.lint.include_cache import Entry, load_entries, save_entries

    root = Path(real(root))
    options = {
        "args": dict(sorted((xacro_args or {}).items())),
        "package_paths": [real(p) for p in package_paths],
    }
    cached = load_entries(root, options, cache_dir)
    graph = IncludeGraph(root)
    entries: dict[str, Entry] = {}
    reach = None if wanted is None else _Reach(wanted, package_paths)
    for file in expand_paths([root]):
        key = real(file)
        entry = cached.get(key)
        current = entry is not None and entry.current()
        rules_out = None  # for a static entry: whether its closure rules the file out
        if entry is not None and current and entry.kind == "static":
            rules_out = None if reach is None else reach.rules_out(entry)
            current = bool(rules_out)
        if current:
            graph.reused += 1
        else:
            static = None
            if reach is not None and rules_out is not False:
                static = functools.partial(reach.static_entry, stale=entry)
            entry = _scan(key, xacro_args, package_paths, xacro_limits, static)
            graph.scanned += 1
        if entry is not None and entry.kind == "static":
            graph.passed += 1
        if entry is None:
            continue  # vanished or unreadable between the walk and the scan
        entries[key] = entry
        if entry.kind == "error" and key in cached and cached[key].kind == "robot":
            # a robot the change broke still reads what it read: linted for those files, it
            # tells the error (the stale stamps have it scanned again next time)
            entry = Entry("error", tuple(dict([*entry.reads, *cached[key].reads[1:]]).items()))
        if entry.kind == "robot" or (entry.kind == "error" and len(entry.reads) > 1):
            graph.robots[key] = tuple(read for read, _ in entry.reads)
    storable = _storable(entries)
    if storable != cached:
        save_entries(root, options, storable, cache_dir)
    return graph


class _Reach:
    """
    Which files to scan may include a ``wanted`` file, from their includes as written
    (``loader.files_reached``): a file whose static closure reaches none is not expanded, and
    is recorded as ``static`` (the closure, stamped), which a later run with other wanted files
    answers from without reading them again. Reused only when every wanted file is XML: the
    closures may leave ``load_yaml`` out.
    """

    def __init__(self, wanted: Collection[str | Path], package_paths: Sequence[str | Path]):
        from inertia_kit.description.loader import is_xml

        self.keys = frozenset(real(file) for file in wanted)
        self.xml_only = all(is_xml(key) for key in self.keys)
        self.package_paths = package_paths

    def rules_out(self, entry: Entry) -> bool | None:
        """Whether a current ``static`` entry rules its file out; ``None``: it cannot tell
        (its closure leaves ``load_yaml`` out, and a wanted file is not XML)."""
        if not self.xml_only:
            return None
        robot = entry.reads[0][0]
        return not any(read in self.keys and read != robot for read, _ in entry.reads)

    def static_entry(self, path: str, stale: Entry | None) -> Entry | None:
        """``path``'s static entry when its includes cannot reach a wanted file, else None."""
        from inertia_kit.description.loader import files_reached
        from inertia_kit.lint.include_cache import Entry

        if (
            stale is not None
            and stale.kind != "static"
            and any(read in self.keys for read, _ in stale.reads[1:])
        ):
            return None  # it read one: expanded again, as it may still (or be broken by it)
        found = files_reached(path, self.package_paths, xml_only=self.xml_only)
        if found is None or any(key in self.keys and key != path for key in found):
            return None
        reads = _stamped(found)
        return None if reads is None else Entry("static", reads)


def _scan(
    path: str,
    xacro_args: Mapping[str, str] | None,
    package_paths: Sequence[str | Path],
    xacro_limits: XacroLimits | None,
    static: Callable[[str], Entry | None] | None = None,
) -> Entry | None:
    """What ``path`` is and reads, by its text and (for xacro that includes) its expansion,
    or the entry ``static`` gives a file to expand that need not be."""
    from inertia_kit.description.loader import files_read, needs_expansion, reads_others
    from inertia_kit.description.safexml import read_bounded
    from inertia_kit.errors import InputError
    from inertia_kit.lint.include_cache import Entry, stamp

    own = stamp(path)
    if own is None:
        return None
    try:
        data = read_bounded(path)
    except InputError:
        return None  # the loader tells why
    if not (needs_expansion(data) and reads_others(data)):
        return Entry("plain", ((path, own),))
    if static is not None:
        ruled_out = static(path)
        if ruled_out is not None:
            return ruled_out
    try:
        files, fragment = files_read(
            path, xacro_args=xacro_args, package_paths=package_paths, limits=xacro_limits
        )
    except InputError as error:
        # refused: a fragment that needs its robot's properties (the error is in the file
        # itself: it includes nobody's robot), or a robot an included file breaks, which it
        # then reads (linted for that file, it reports the error); scanned again when it changes
        at_fault = () if error.path is None else _stamped((error.path,)) or ()
        return Entry("error", tuple(dict([(path, own), *at_fault]).items()))
    reads = _stamped((path, *files))  # the input first, each file once
    if reads is None:
        return None
    return Entry("fragment" if fragment else "robot", reads)


def _stamped(files: Iterable[str]) -> tuple[tuple[str, Stamp], ...] | None:
    """Each file read, by real path, with its stamp; ``None`` if one is gone already."""
    from inertia_kit.lint.include_cache import stamp

    reads: dict[str, Stamp] = {}
    for name in files:
        key = real(name)
        found = stamp(key)
        if found is None:
            return None
        reads.setdefault(key, found)
    return tuple(reads.items())


def _storable(entries: Mapping[str, Entry]) -> dict[str, Entry]:
    """
    The entries worth keeping: not those with a file changed in the last two seconds, as a
    second change within the file system's timestamp tick would leave its stamp as it is
    (the mesh cache's rule, :data:`~inertia_kit.physics.mesh_cache.RACY_SECONDS`).
    """
    from inertia_kit.physics.mesh_cache import RACY_SECONDS

    settled = time.time_ns() - RACY_SECONDS * 1e9
    return {
        key: entry
        for key, entry in entries.items()
        if all(found.mtime_ns < settled for _, found in entry.reads)
    }
