"""
The results of linting several files as one: each finding and each message once.

A xacro file included by several linted files is analysed with each of them, so its findings,
and the notes about its suppression comments, come back once per including file; they are
told once.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from inertia_kit.errors import InputError, InternalError
    from inertia_kit.lint.findings import Finding
    from inertia_kit.lint.runner import FileResult


@dataclass(frozen=True)
class Merged:
    """
    ``findings`` in the order the files gave them, each once; ``errors`` the files that could
    not be read; ``messages`` what to tell besides the findings, as ``(level, text)`` each once
    (``error`` unreadable, ``note`` a skipped fragment, ``warning`` a suppression comment not
    understood); ``failing`` whether a file has a finding at or above its ``fail-on``;
    ``checked`` how many files were linted (a fragment linted through its robots counts when
    they found something in it), ``linted`` which, and ``flagged`` how many of them gave
    findings (in themselves or in what they include).
    """

    findings: list[Finding]
    errors: list[InputError | InternalError]
    messages: list[tuple[str, str]]
    failing: bool
    checked: int
    fixed: int = 0  # findings whose fix was applied (``--fix``)
    diff: str = ""  # ``--diff``: the fixes' unified diff, each file once
    hidden: int = 0  # fixes that ``--unsafe-fixes`` would enable
    linted: tuple[str, ...] = ()
    flagged: int = 0


def merge(results: Sequence[FileResult]) -> Merged:
    """The per-file ``results`` of one run as one."""
    from inertia_kit.lint.applying import hidden

    messages: dict[tuple[str, str], None] = {}
    findings: dict[tuple, Finding] = {}
    for result in results:
        if result.error:
            messages[("error", str(result.error))] = None
        if result.fragment and not result.remarks:
            note = f"{result.path}: a xacro fragment (macros and properties only, to be included)"
            messages[("note", f"{note}: skipped")] = None
        for text in result.remarks:
            messages[("note", text)] = None
        for text in result.notes:
            messages[("warning", text)] = None
        for finding in result.findings:
            where = (finding.path, finding.line, finding.column, finding.code, finding.message)
            first = findings.setdefault(where, finding)
            if first is not finding and first.via != finding.via:
                # several robots found it: all named; its own file, linted as itself: none
                both = first.via and finding.via
                via = tuple(dict.fromkeys(first.via + finding.via)) if both else ()
                findings[where] = dataclasses.replace(first, via=via)
    linted = [r for r in results if r.error is None and not r.disabled]
    linted = [r for r in linted if not r.fragment or r.findings]
    return Merged(
        list(findings.values()),
        [result.error for result in results if result.error is not None],
        list(messages),
        any(result.failing for result in results),
        len(linted),
        sum(result.fixed for result in results),
        "".join(dict.fromkeys(result.diff for result in results if result.diff)),
        sum(
            1
            for result in results
            for finding in result.findings
            if hidden(finding, result.unsafe_fixes)
        ),
        tuple(result.path for result in linted),
        sum(1 for result in linted if result.findings),
    )
