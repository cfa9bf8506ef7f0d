"""
Suppression comments in URDF and xacro files.

``<!-- inertia-lint: ignore[IN012, inertia-too-small] -->`` directly before an element covers
that element and everything inside it: every line from its start tag to its end tag. Codes,
code prefixes and rule names are accepted; text after the ``]`` is a free reason.
``<!-- inertia-lint: disable-file -->`` anywhere covers the whole file.

A finding is covered when its location is: the file and line it is reported at, or, for an
element a xacro macro produced, the element's line in the macro body (so a comment in a macro
covers every instance, and a comment before a macro call covers that call). A finding without
a line (about the robot as a whole) is covered by a comment before the root ``<robot>`` of the
file it is reported in. Each file's
comments are read once (per content: the cache is keyed on size and modification time).
"""

from __future__ import annotations

import functools
import os
import re
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from inertia_kit.errors import InputError
from inertia_kit.lint import catalog
from inertia_kit.lint.findings import Finding

if TYPE_CHECKING:
    from inertia_kit.lint import markup

# the directive's body is what follows, stripped: a lazy group before ``\s*\Z`` would try every
# end in a run of blanks, quadratic in a hostile comment of them
_DIRECTIVE = re.compile(r"\s*inertia-lint\s*:")
_IGNORE = re.compile(r"ignore\s*\[([^\]]*)\](.*)\Z", re.DOTALL)
_MARKERS = tuple("inertia-lint".encode(c) for c in ("utf-8", "utf-16-le", "utf-16-be"))


@dataclass(frozen=True)
class Ignore:
    """An ``ignore[...]`` comment: its selectors and the lines of the element it covers."""

    selectors: tuple[str, ...]
    first: int
    last: int
    line: int  # of the comment
    root: bool = False  # it stands before the root element: it also covers findings without a line

    def holds(self, line: int | None) -> bool:
        """Whether the element it covers holds ``line`` (``None``: the robot as a whole)."""
        return self.root if line is None else self.first <= line <= self.last

    def covers(self, finding: Finding, line: int | None) -> bool:
        return self.holds(line) and catalog.selects(self.selectors, finding.code, finding.name)


@dataclass(frozen=True)
class Directives:
    """The suppression comments of one file, and the ones that say nothing we understand."""

    path: str
    disabled: bool = False
    ignores: tuple[Ignore, ...] = ()
    problems: tuple[tuple[int | None, str], ...] = ()  # (line, message)

    def covers(self, finding: Finding, line: int | None) -> bool:
        if self.disabled:
            return True
        return any(ignore.covers(finding, line) for ignore in self.holding(line))

    def holding(self, line: int | None) -> list[Ignore]:
        """
        The ignores whose element holds ``line`` (``None``: those before the root), in file
        order: looked up by line, not by trying each (``--add-noqa`` writes a comment for each
        of thousands of links, and each finding was checked against every one of them).
        """
        if line is None:
            return [ignore for ignore in self.ignores if ignore.root]
        found = {
            k for level, nodes in enumerate(self._segments) for k in nodes.get(line >> level, ())
        }
        return [self.ignores[k] for k in sorted(found)]

    @functools.cached_property
    def _segments(self) -> list[dict[int, list[int]]]:
        """Each ignore's lines as the few aligned runs of 2**level lines that tile them
        (a segment tree): ``levels[level][line >> level]`` lists the ignores holding the run."""
        levels: list[dict[int, list[int]]] = []
        for index, ignore in enumerate(self.ignores):
            low, high, level = max(ignore.first, 0), ignore.last + 1, 0
            while low < high:
                while len(levels) <= level:
                    levels.append({})
                if low & 1:
                    levels[level].setdefault(low, []).append(index)
                    low += 1
                if high & 1:
                    high -= 1
                    levels[level].setdefault(high, []).append(index)
                low, high, level = low >> 1, high >> 1, level + 1
        return levels


def directives(path: str | Path) -> Directives:
    """
    The suppression comments of the file at ``path`` (none when it cannot be read): as the
    overlay in force holds it (``--fix``'s passes: :mod:`~inertia_kit.description.overlay`),
    else as the disk does, read again when its size or time of change differ.
    """
    from inertia_kit.description.overlay import overlay_bytes

    held = overlay_bytes(path)
    if held is not None:
        return _held_directives(str(path), held)
    try:
        stat = os.stat(path)
    except (OSError, ValueError):
        return Directives(str(path))
    return _directives(str(path), stat.st_mtime_ns, stat.st_size)


def suppressed(finding: Finding) -> bool:
    """Whether a comment in the files the finding points at covers it."""
    if finding.path and directives(finding.path).covers(finding, finding.line):
        return True
    return bool(finding.macro_path) and directives(finding.macro_path).covers(  # type: ignore[arg-type]
        finding, finding.macro_line
    )


def covering(finding: Finding) -> list[tuple[str, Ignore]]:
    """
    Every ``ignore[...]`` comment (with its file) that covers ``finding``, whether or not a
    ``disable-file`` does too: what :mod:`inertia_kit.lint.unused` counts as used.
    """
    places = [(finding.path, finding.line)]
    if finding.macro_path:
        places.append((finding.macro_path, finding.macro_line))
    return [
        (path, ignore)
        for path, line in places
        if path
        for ignore in directives(path).holding(line)
        if ignore.covers(finding, line)
    ]


@functools.lru_cache(maxsize=512)
def _directives(path: str, mtime_ns: int, size: int) -> Directives:
    from inertia_kit.description.safexml import read_bounded

    try:
        data = read_bounded(path)
    except InputError:
        return Directives(path)  # the loader reports unreadable files
    return _read(path, data)


@functools.lru_cache(maxsize=16)
def _held_directives(path: str, data: bytes) -> Directives:
    """By content: the texts of one run of ``--fix`` (a ``bytes`` hashes once)."""
    return _read(path, data)


def _read(path: str, data: bytes) -> Directives:
    from inertia_kit.description.edits import decode_source
    from inertia_kit.description.xmlparse import parse_xml

    try:
        if not any(marker in data for marker in _MARKERS):  # no directive: no need to parse
            return Directives(path)
        parse_xml(data, path)  # well-formed: the markup below is read right
    except InputError:
        return Directives(path)  # the loader reports unreadable files
    try:
        text = decode_source(data, path).text
    except InputError:  # an encoding we cannot edit in: read as libxml2 does then, as UTF-8
        text = data.decode("utf-8", "replace")
    from inertia_kit.lint import markup  # its scanner (a large regex) only for a directive

    return _scan(path, markup.layout(text))


def _scan(path: str, found: markup.Layout) -> Directives:
    """
    The directives among ``found``'s comments. Lines are read from the text as XML counts them
    (:mod:`.markup`), where ``--add-noqa`` places its comments: never from lxml, whose lines
    differ after a lone carriage return.
    """
    known = catalog.names()
    disabled = False
    ignores: list[Ignore] = []
    problems: list[tuple[int | None, str]] = []
    followed = {id(c): e for e in found.elements for c in e.before}  # comment -> its element
    for comment in found.comments:
        match = _DIRECTIVE.match(comment.body)
        if match is None:
            continue
        body = comment.body[match.end() :].strip()
        line = comment.line
        if body == "disable-file" or body.startswith(("disable-file ", "disable-file:")):
            disabled = True
            continue
        ignore = _IGNORE.match(body)
        if ignore is None:
            problems.append(
                (
                    line,
                    f"unknown directive `{body}`: expected `ignore[CODE, ...]` or `disable-file`",
                )
            )
            continue
        selectors = []
        for text in ignore.group(1).split(","):
            if not text.strip():
                continue
            selector = catalog.normalize_selector(text, known)
            if selector is None:
                problems.append((line, catalog.selector_error(text.strip(), known)))
            else:
                selectors.append(selector)
        if not ignore.group(1).strip():
            problems.append((line, "`ignore[]` names no rule: give codes or names"))
            continue
        target = followed.get(id(comment))
        if target is None:
            problems.append((line, "`ignore[...]` is not followed by an element it could cover"))
        elif selectors:
            root = target.parent is None
            ignores.append(Ignore(tuple(selectors), target.first, target.last, line, root))
    return Directives(path, disabled, tuple(ignores), tuple(problems))
