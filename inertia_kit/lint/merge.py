"""
The results of linting several files as one: each finding and each message once.

A xacro file included by several linted files is analysed with each of them, so its findings,
and the notes about its suppression comments, come back once per including file; they are
told once.

A run that streams its report (:class:`~inertia_kit.lint.paths.Linting` with ``release``) has
already told most findings when the files are merged, and kept only their :class:`Tally`.
"""

from __future__ import annotations

import dataclasses
from collections import Counter
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from inertia_kit.errors import InputError, InternalError
    from inertia_kit.lint.findings import Finding, Severity
    from inertia_kit.lint.runner import FileResult


@dataclass
class Tally:
    """
    What the summary line and ``--statistics`` need of a run's findings, without them: how many
    by severity and by rule (code, name); how many have a fix ``--fix`` applies, without and
    with ``--unsafe-fixes`` (which a later file's configuration may still turn on); how many
    have one that ``--unsafe-fixes`` would enable (``hidden``, by each file's own setting).
    """

    by_severity: Counter[Severity] = field(default_factory=Counter)
    by_rule: Counter[tuple[str, str]] = field(default_factory=Counter)
    fixable: int = 0
    fixable_unsafe: int = 0
    hidden: int = 0

    @classmethod
    def of(cls, findings: Iterable[Finding], unsafe_fixes: bool = False) -> Tally:
        tally = cls()
        tally.add(findings, unsafe_fixes)
        return tally

    def add(self, findings: Iterable[Finding], unsafe_fixes: bool = False) -> None:
        """Count ``findings`` of a file whose fixes include unsafe ones when ``unsafe_fixes``."""
        from inertia_kit.lint.applying import applicable, hidden

        for finding in findings:
            self.by_severity[finding.severity] += 1
            self.by_rule[(finding.code, finding.name)] += 1
            self.fixable += applicable(finding, False)
            self.fixable_unsafe += applicable(finding, True)
            self.hidden += hidden(finding, unsafe_fixes)

    def __add__(self, other: Tally) -> Tally:
        return Tally(
            self.by_severity + other.by_severity,
            self.by_rule + other.by_rule,
            self.fixable + other.fixable,
            self.fixable_unsafe + other.fixable_unsafe,
            self.hidden + other.hidden,
        )

    @property
    def total(self) -> int:
        return sum(self.by_severity.values())


@dataclass(frozen=True)
class Merged:
    """
    ``findings`` in the order the files gave them, each once; ``errors`` the files that could
    not be read; ``messages`` what to tell besides the findings, as ``(level, text)`` each once
    (``error`` unreadable, ``note`` a skipped fragment, ``warning`` a suppression comment not
    understood); ``failing`` whether a file has a finding at or above its ``fail-on``;
    ``checked`` how many files were linted (a fragment linted through its robots counts when
    they found something in it), ``linted`` which, and ``flagged`` how many of them gave
    findings (in themselves or in what they include); ``tally`` counts every finding of the
    run: those in ``findings`` and those told before the merge.
    """

    findings: list[Finding]
    errors: list[InputError | InternalError]
    messages: list[tuple[str, str]]
    failing: bool
    checked: int
    fixed: int = 0  # findings whose fix was applied (``--fix``)
    diff: str = ""  # ``--diff``: the fixes' unified diff, each file once
    linted: tuple[str, ...] = ()
    flagged: int = 0
    tally: Tally = field(default_factory=Tally)


def merge(results: Sequence[FileResult], told: Tally | None = None) -> Merged:
    """The per-file ``results`` of one run as one; ``told``: the findings already told, and
    dropped from the results (:attr:`FileResult.told`)."""
    messages: dict[tuple[str, str], None] = {}
    findings: dict[tuple, Finding] = {}
    unsafe: dict[tuple, bool] = {}  # whether the result a finding came from first has unsafe fixes
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
            where = _where(finding)
            first = findings.setdefault(where, finding)
            unsafe.setdefault(where, result.unsafe_fixes)
            if first is not finding and first.via != finding.via:
                # several robots found it: all named; its own file, linted as itself: none
                both = first.via and finding.via
                via = tuple(dict.fromkeys(first.via + finding.via)) if both else ()
                findings[where] = dataclasses.replace(first, via=via)
    tally = Tally()
    for where, finding in findings.items():
        tally.add([finding], unsafe[where])
    if told is not None:
        tally = told + tally
    linted = [r for r in results if r.error is None and not r.disabled]
    linted = [r for r in linted if not r.fragment or r.findings or r.told]
    return Merged(
        list(findings.values()),
        [result.error for result in results if result.error is not None],
        list(messages),
        any(result.failing or result.told_failing for result in results),
        len(linted),
        sum(result.fixed for result in results),
        "".join(dict.fromkeys(result.diff for result in results if result.diff)),
        tuple(result.path for result in linted),
        sum(1 for result in linted if result.findings or result.told),
        tally,
    )


def _where(finding: Finding) -> tuple:
    """What tells a finding once."""
    return (finding.path, finding.line, finding.column, finding.code, finding.message)
