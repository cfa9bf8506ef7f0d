"""
``inertia-lint --fix``: apply the fixes findings carry, as ruff does.

One pass takes the applicable fixes (safe ones; unsafe ones too with ``--unsafe-fixes``) in the
order of their findings, skips a fix whose edits overlap an edit already taken (identical edits,
such as one macro body shared by two links, are taken once), writes every changed file
atomically (:func:`~inertia_kit.description.edits.write_all_atomic`: byte-identical outside the
edited spans, symbolic links followed), and lints again. Passes repeat until no fix applies or
nothing changes, at most :data:`MAX_PASSES` times; a file that did not settle gets a note.
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
    if fix is None or not fix.edits:
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
    Lint, apply, lint again until nothing applies (``write``); or, without ``write``, one pass
    whose diff is returned. ``InputError`` from a write is kept in the result (as a file that
    could not be read), so is ``check(paths)``'s, which may refuse the files about to be
    written.

    Each pass edits the text its lint read and writes only if the files still hold it; a pass
    after the first also stops when a file it wrote is no longer what it wrote (another writer
    came between two passes: ``ChangedWhileEditing``).
    """
    from inertia_kit.description.edits import CHANGED, ChangedWhileEditing, write_all_atomic
    from inertia_kit.description.reads import digest, key

    fixed = 0
    ours: dict[str, str] = {}  # real path -> digest of what the last pass wrote there
    for number in range(1, MAX_PASSES + 1):
        result = lint()
        if result.error is not None or result.disabled or result.fragment:
            return Outcome(result, fixed, number - 1)
        foreign = [name for name, mine in ours.items() if result.reads.get(name, mine) != mine]
        if foreign:
            result.error = ChangedWhileEditing(CHANGED, foreign[0])
            return Outcome(result, fixed, number - 1)
        try:
            step = one_pass(result.findings, unsafe, result.reads)
            if not step.changes:
                return Outcome(result, fixed, number - 1)
            if not write:
                return Outcome(result, 0, 1, diff=step.diff())
            writes = [(s.path, s.encode(text), s.original) for s, text in step.changes]
            if check is not None:
                check([path for path, _, _ in writes])
            write_all_atomic(writes)
        except InputError as error:
            result.error = error
            return Outcome(result, fixed, number)
        ours.update((key(path), digest(data)) for path, data, _ in writes)
        fixed += len(step.fixed)
    result = lint()
    try:
        settled = one_pass(result.findings, unsafe, result.reads).changes == ()
    except InputError as error:
        result.error = error
        return Outcome(result, fixed, MAX_PASSES)
    if not settled:
        result.notes.append(
            f"{result.path}: the fixes did not settle after {MAX_PASSES} passes; "
            "run inertia-lint --fix again and report the file if it still changes"
        )
    return Outcome(result, fixed, MAX_PASSES, settled)
