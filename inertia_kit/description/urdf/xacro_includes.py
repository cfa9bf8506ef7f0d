"""
Which files a xacro robot can include, read from its includes as written, without expanding
it: what lets the include graph (:mod:`inertia_kit.lint.include_graph`) expand only the
robots that may include the files a run asks about.

A xacro expansion reads other files only through ``<xacro:include filename=...>`` and
``load_yaml`` (the include graph's cheap first pass rests on the same fact). When every
include a robot reaches is written out, ``$(find pkg)/path`` or a path, the files it can read
are those includes, followed file to file: a superset of what it reads under any arguments,
as conditionals only leave includes out. :func:`may_include` answers "no" only then, and when
none of them is a file asked about.

What is not written out is not guessed: an include named by a property or an argument
(``${name}.xacro``, ``$(arg file)``), a glob, a file that cannot be read or parsed, a package
the resolver cannot find, or more than :data:`MAX_FILES` files: the robot may include
anything, and is expanded. ``$(find pkg)`` is resolved as the expansion resolves it
(:meth:`~inertia_kit.description.urdf.xacro_session.Session.find`: near the file being read,
then near the robot), and a relative path joined to that file's folder, as xacro joins it. An
include inside a macro is opened while whichever file calls the macro is being read, so its
path is taken from every file the robot reaches.

``load_yaml`` reads data, which includes nothing further and makes no XML element: it cannot
make a robot an includer of an XML file, and is not followed. When a file asked about is not
XML (a YAML file a hook hands over), a robot that reaches a ``load_yaml`` may read it.
"""

from __future__ import annotations

import os
import re
import stat
from collections.abc import Collection, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from lxml import etree

    from inertia_kit.description.urdf.packages import PackageResolver

#: Files followed from one robot before it counts as one that may include anything.
MAX_FILES = 256

_READS_OTHERS = re.compile(rb"include|load_yaml")
# a filename xacro reads as written: ``$(find pkg)`` then a path, or a path; no other ``$``
_FIND = re.compile(r"\$\(find\s+([^\s()$]+)\s*\)([^$]*)")
_GLOB = re.compile(r"[*?\[]")
_HINT = re.compile(r"[^\s\"'$()<>]*")


def reads_others(data: bytes) -> bool:
    """Whether a file's bytes may make xacro read another file: they name ``include`` or
    ``load_yaml``; a file that names neither reads nothing else."""
    return _READS_OTHERS.search(data) is not None


class _Unknown(Exception):
    """An include that is not written out: the robot may read any file."""


def is_xml(path: str) -> bool:
    """Whether the file's first character, past a byte-order mark and blanks, opens a tag (a
    regular file only: opened without blocking, so a named pipe put in its place is no XML)."""
    try:
        descriptor = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except (OSError, ValueError):
        return False
    try:
        if not stat.S_ISREG(os.fstat(descriptor).st_mode):
            return False
        head = os.read(descriptor, 4096)
    except OSError:
        return False
    finally:
        os.close(descriptor)
    return head.removeprefix(b"\xef\xbb\xbf").lstrip().startswith(b"<")


def may_include(
    robot: str,
    wanted: Collection[str],
    package_paths: Sequence[str | Path] = (),
    *,
    xml_only: bool = True,
) -> bool:
    """
    Whether expanding ``robot`` (a real path, as the include graph expands it) may read one of
    ``wanted`` (real paths) other than itself; ``xml_only``: every wanted file is XML
    (:func:`is_xml`), so ``load_yaml`` cannot read one that matters.
    """
    found = reach(robot, package_paths, xml_only=xml_only)
    return found is None or any(key in wanted and key != robot for key in found)


def reach(
    robot: str, package_paths: Sequence[str | Path] = (), *, xml_only: bool = True
) -> tuple[str, ...] | None:
    """
    The real paths of every file expanding ``robot`` may read (``robot`` first), from its
    includes as written; ``None`` when one is not written out. ``xml_only``: ``load_yaml`` is
    not followed (see the module's docstring); otherwise a file that loads YAML gives ``None``.

    An include inside a macro is opened while whichever file calls the macro is the one being
    read: its path is taken from each file the robot reaches (each could be that file), until
    no new file is reached.
    """
    from inertia_kit.description.urdf.packages import PackageResolver

    resolver = PackageResolver(package_paths=tuple(package_paths), start=robot)
    reached = [robot]  # as xacro opens them: a relative include joins the folder of its file
    seen = {robot}
    keys = {robot: None}  # real paths, in the order reached
    in_macros: list[str] = []  # filenames written inside macros
    tried: set[tuple[str, str]] = set()  # (filename, file read when the macro runs)
    done = 0
    try:
        while done < len(reached):
            while done < len(reached):
                file = reached[done]
                done += 1
                targets, specs = _reads(file, robot, resolver, xml_only)
                in_macros.extend(specs)
                for target in targets:
                    _add(target, reached, seen, keys)
            for spec in in_macros:
                for near in list(reached):
                    if (spec, near) not in tried:
                        tried.add((spec, near))
                        target = _written_out(spec, near, robot, resolver)
                        _add(target, reached, seen, keys)
    except _Unknown:
        return None
    return tuple(keys)


def _add(target: str, reached: list[str], seen: set[str], keys: dict[str, None]) -> None:
    """Add ``target`` to the files reached (``_Unknown`` past :data:`MAX_FILES`)."""
    if target in seen:
        return
    if len(reached) >= MAX_FILES:
        raise _Unknown
    seen.add(target)
    reached.append(target)
    keys.setdefault(os.path.realpath(target), None)


def _reads(
    file: str, robot: str, resolver: PackageResolver, xml_only: bool
) -> tuple[list[str], list[str]]:
    """
    The files ``file`` names to read, as xacro would open them while reading ``file``, and the
    filenames written inside its macros (``_Unknown`` when one is not written out, or ``file``
    cannot be read and parsed as the expansion would).
    """
    from inertia_kit.description.safexml import read_bounded
    from inertia_kit.description.xmlparse import fromstring

    try:
        data = read_bounded(file)
    except Exception:
        raise _Unknown from None
    if not reads_others(data):
        return [], []
    if not xml_only and b"load_yaml" in data:
        raise _Unknown  # a YAML file asked about, and a file that may load it
    if b"<!DOCTYPE" in data or b"<!ENTITY" in data:
        raise _Unknown  # refused by the expansion, or entities that could hide a name
    try:
        root = fromstring(data)
    except Exception:
        raise _Unknown from None
    targets, specs = [], []
    for element in root.iter():
        if _local(element) != "include":  # xacro:include, or a bare include of older xacro
            continue
        spec = element.get("filename")
        if spec is None or _GLOB.search(spec):
            raise _Unknown
        if any(_local(ancestor) == "macro" for ancestor in element.iterancestors()):
            specs.append(spec)
        else:
            targets.append(_written_out(spec, file, robot, resolver))
    return targets, specs


def _local(element: etree._Element) -> str:
    return element.tag.rpartition("}")[2] if isinstance(element.tag, str) else ""


def _written_out(spec: str, file: str, robot: str, resolver: PackageResolver) -> str:
    """The path ``spec`` names, as xacro opens it while reading ``file`` (``_Unknown`` unless
    it is ``$(find pkg)`` and a path, or a path)."""
    if "$" not in spec:
        return spec if os.path.isabs(spec) else os.path.join(os.path.dirname(file), spec)
    found = _FIND.fullmatch(spec)
    if found is None:
        raise _Unknown
    package, rest = found.groups()
    hint = _HINT.match(rest).group()  # what the expansion's find is told follows it
    folder = resolver.find(package, file, hint)
    if folder is None and file != robot:
        folder = resolver.find(package, robot, hint)
    if folder is None:
        raise _Unknown
    return str(folder.absolute()) + rest
