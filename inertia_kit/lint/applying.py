"""
``inertia-lint --fix``: apply the fixes findings carry, as ruff does.

One pass takes the applicable fixes (safe ones; unsafe ones too with ``--unsafe-fixes``) in the
order of their findings, skips a fix whose edits overlap an edit already taken (identical edits,
such as one macro body shared by two links, are taken once), and applies them to the text of
each file. Passes repeat until no fix applies or nothing changes, at most :data:`MAX_PASSES`
times (a file that did not settle gets a note), in memory: each pass after the first lints the
text the one before produced (:mod:`~inertia_kit.description.overlay`, which the loader, xacro's
includes and the suppression comments read through), and every changed file is written once, at
the end, all together (:func:`~inertia_kit.description.edits.write_all_atomic`: byte-identical
outside the edited spans, symbolic links followed). A run killed between two passes leaves every
file as it was; the write expects the bytes the first lint read, so another writer's save at any
moment of the run is kept and nothing is written.
``--diff`` makes one pass and prints the unified diff instead of writing.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from inertia_kit.errors import InputError
from inertia_kit.lint.findings import Finding, Safety

if TYPE_CHECKING:
    from inertia_kit.description.edits import Edit, SourceText
    from inertia_kit.lint.runner import FileResult

MAX_PASSES = 10


def applicable(finding: Finding, unsafe: bool) -> bool:
    """Whether ``--fix`` applies the finding's fix (unsafe ones only with ``--unsafe-fixes``)."""
    fix = finding.fix
    if fix is None or (fix.placed and not fix.edits):
        return False
    return fix.safety is Safety.SAFE or (unsafe and fix.safety is Safety.UNSAFE)


def hidden(finding: Finding, unsafe: bool) -> bool:
    """An unsafe fix that ``--unsafe-fixes`` would enable (ruff's "hidden fixes")."""
    wants = finding.wants
    if unsafe or finding.unfixable is not None or applicable(finding, unsafe):
        return False
    fix_safety = finding.fix.safety if finding.fix is not None else None
    return Safety.UNSAFE in (fix_safety, None if wants is None else wants.safety)


@dataclass(frozen=True)
class Pass:
    """One pass: the findings whose fix was taken, and ``(file as read, new text)``."""

    fixed: tuple[Finding, ...]
    changes: tuple[tuple[SourceText, str], ...]

    def diff(self) -> str:
        from inertia_kit.description.edits import unified_diff

        return unified_diff((source.path, source.text, text) for source, text in self.changes)


def one_pass(
    findings: Sequence[Finding], unsafe: bool, reads: Mapping[str, str | None] | None = None
) -> Pass:
    """
    The applicable, non-overlapping fixes of ``findings`` applied to their files' text, each
    file read as the lint's load read it (``reads``: :mod:`inertia_kit.description.reads`;
    ``ChangedWhileEditing`` when it holds other bytes now).
    """
    from inertia_kit.description.edits import apply_edits
    from inertia_kit.description.reads import as_loaded

    taken: dict[str, _Taken] = {}  # resolved path -> edits
    fixed = []
    for finding in findings:
        if not applicable(finding, unsafe):
            continue
        assert finding.fix is not None
        files = [
            (edit, taken.setdefault(_resolved(edit.path), _Taken())) for edit in finding.fix.edits
        ]
        new = [(edit, where) for edit, where in files if edit not in where.edits]
        if any(where.overlaps(edit) for edit, where in new):
            continue  # the next pass, after a new lint, may take it
        for edit, where in new:
            where.add(edit)
        fixed.append(finding)
    changes = []
    for where in taken.values():
        if not where.edits:
            continue
        edits = list(where.edits)
        source = as_loaded(edits[0].path, reads or {})
        text, _ = apply_edits(source.text, edits)
        if source.encode(text) != source.original:
            changes.append((source, text))
    return Pass(tuple(fixed), tuple(changes))


def _resolved(path: str) -> str:
    return str(Path(path).resolve())


def _overlaps(a: Edit, b: Edit) -> bool:
    """Two edits touching the same text (two insertions at one point count)."""
    return a.start == b.start or (a.start < b.end and b.start < a.end)


class _Taken:
    """
    The edits taken in one file, and where they stand: each is filed under the stretches of
    :data:`_STRETCH` characters it touches, so an edit is checked against its neighbours only
    (against every edit taken, a fix of each of 5000 links was quadratic: 29 s of 40).
    """

    def __init__(self) -> None:
        self.edits: dict[Edit, None] = {}  # in the order taken
        self._near: dict[int, list[Edit]] = {}

    def overlaps(self, edit: Edit) -> bool:
        return any(
            _overlaps(edit, other) for key in _stretches(edit) for other in self._near.get(key, ())
        )

    def add(self, edit: Edit) -> None:
        self.edits[edit] = None
        for key in _stretches(edit):
            self._near.setdefault(key, []).append(edit)


_STRETCH = 4096


def _stretches(edit: Edit) -> range:
    return range(edit.start // _STRETCH, max(edit.end, edit.start + 1) // _STRETCH + 1)


@dataclass
class Outcome:
    """What fixing one file did: the last lint, findings fixed, passes, whether it settled."""

    result: FileResult
    fixed: int = 0
    passes: int = 0
    settled: bool = True
    diff: str = ""


def fix_file(
    lint: Callable[[], FileResult],
    unsafe: bool,
    *,
    write: bool,
    check: Callable[[Sequence[str]], None] | None = None,
) -> Outcome:
    """
    Lint, apply, lint again until nothing applies, in memory, then write every changed file
    at once (``write``); or, without ``write``, one pass whose diff is returned. ``lint`` reads
    the files through :mod:`~inertia_kit.description.overlay`, so each pass after the first
    lints the text the one before produced.

    The write expects each file to hold the bytes the first lint read: another writer that
    saved one of them at any moment of the run is seen and nothing is written
    (``ChangedWhileEditing``), as when a file the passes read but did not edit holds other
    bytes in a later pass. That error, any other ``InputError`` of the write, and
    ``check(paths)``'s (which may refuse the files about to be written) are kept in the result
    of the first lint (as a file that could not be read), nothing fixed. A lint or a pass that
    fails on an edited text ends the passes there: what the passes before it did is written.
    """
    from inertia_kit.description.edits import ChangedWhileEditing
    from inertia_kit.description.overlay import overlaid

    if not write:
        return _diff(lint(), unsafe)
    edited = _Edited()
    first: FileResult | None = None
    fixed = passes = 0
    settled = True
    for number in range(1, MAX_PASSES + 2):
        with overlaid(edited.texts):
            result = lint()
            first = result if first is None else first
            try:
                if isinstance(result.error, ChangedWhileEditing):
                    raise result.error
                if result.error is not None or result.disabled or result.fragment:
                    break
                edited.check_reads(result.reads, first.reads)
                step = one_pass(result.findings, unsafe, result.reads)
            except ChangedWhileEditing as error:  # another writer: nothing is written
                first.error = error
                return Outcome(first)
            except InputError as error:
                result.error = error
                break
        if not step.changes:
            break
        if number > MAX_PASSES:
            settled = False
            result.notes.append(
                f"{result.path}: the fixes did not settle after {MAX_PASSES} passes; "
                "run inertia-lint --fix again and report the file if it still changes"
            )
            break
        edited.take(step.changes)
        fixed, passes = fixed + len(step.fixed), number
    writes = edited.writes()
    if writes:
        from inertia_kit.description.edits import write_all_atomic

        try:
            if check is not None:
                check([path for path, _, _ in writes])
            # the files the first lint read and no pass edited must still hold those bytes
            write_all_atomic(writes, unchanged=first.reads)
        except InputError as error:
            assert first is not None
            first.error = error
            return Outcome(first)
    return Outcome(result, fixed, passes, settled)


def _diff(result: FileResult, unsafe: bool) -> Outcome:
    """The one pass of ``--diff``: its diff, nothing written."""
    if result.error is not None or result.disabled or result.fragment:
        return Outcome(result)
    try:
        step = one_pass(result.findings, unsafe, result.reads)
    except InputError as error:
        result.error = error
        return Outcome(result, 0, 1)
    if not step.changes:
        return Outcome(result)
    return Outcome(result, 0, 1, diff=step.diff())


class _Edited:
    """
    The files the passes changed, by real path: as first read (the bytes the write expects
    the file to hold still) and as the last pass left them (what the next pass lints).
    """

    def __init__(self) -> None:
        self.read: dict[str, SourceText] = {}
        self.texts: dict[str, bytes] = {}

    def take(self, changes: Sequence[tuple[SourceText, str]]) -> None:
        from inertia_kit.description.reads import key

        for source, text in changes:
            name = key(source.path)
            self.read.setdefault(name, source)
            self.texts[name] = source.encode(text)

    def check_reads(self, reads: Mapping[str, str | None], first: Mapping[str, str | None]):
        """``ChangedWhileEditing`` when a file the first lint read and no pass edited holds
        other bytes now (the edits of this pass would be computed on another robot)."""
        from inertia_kit.description.edits import CHANGED, ChangedWhileEditing

        for name, found in reads.items():
            if name not in self.texts and first.get(name, found) != found:
                raise ChangedWhileEditing(CHANGED, name)

    def writes(self) -> list[tuple[str, bytes, bytes]]:
        """``(path, new bytes, bytes expected there)`` of every file that changed."""
        return [
            (self.read[name].path, data, self.read[name].original)
            for name, data in self.texts.items()
            if data != self.read[name].original
        ]
