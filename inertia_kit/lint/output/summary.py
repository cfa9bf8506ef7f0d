"""What a run adds up to: how often each rule fired (``--statistics``), and the summary line."""

from __future__ import annotations

from collections.abc import Iterable, Sequence

from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.merge import Tally
from inertia_kit.lint.output.common import dumps


def statistics(findings: Iterable[Finding] | Tally, as_json: bool = False) -> str:
    """``count  CODE  name`` per rule, most frequent first (or a JSON array); ``findings``, or
    their :class:`~inertia_kit.lint.merge.Tally`."""
    counts = (findings if isinstance(findings, Tally) else Tally.of(findings)).by_rule
    rows = sorted(counts.items(), key=lambda item: (-item[1], item[0][0]))
    if as_json:
        return dumps([{"code": code, "name": name, "count": n} for (code, name), n in rows]) + "\n"
    width = max((len(str(n)) for n in counts.values()), default=1)
    return "".join(f"{n:>{width}}  {code}  {name}\n" for (code, name), n in rows)


def _count(n: int, word: str, plural: str | None = None) -> str:
    return f"{n} {word if n == 1 else plural or word + 's'}"


def summary(
    findings: Sequence[Finding] | Tally,
    checked: int,
    unreadable: int = 0,
    internal: int = 0,
    *,
    flagged: int | None = None,
    fixed: int = 0,
    fixable: int = 0,
    hidden: int = 0,
) -> str:
    """
    One shape, whose ``N files`` always counts the files linted (``checked``):
    ``Found 3 errors, 1 warning in 2 of 6 files.`` or ``No findings in 6 files.``, where 2
    (``flagged``; default: the files the findings are in) is how many of them gave findings
    (``in 6 files`` when all did),
    then the files that could not be read or met an internal error (a bug). With fixes:
    ``Fixed 2 findings; 1 error remains in 1 of 6 files.`` or ``Fixed 2 findings; no findings
    remain in 6 files.``, and a line counting the fixes ``--fix`` (``fixable``) or
    ``--unsafe-fixes`` (``hidden``) would apply. ``findings``: the findings, or their
    :class:`~inertia_kit.lint.merge.Tally` (then ``flagged`` is needed).
    """
    if flagged is None:
        assert not isinstance(findings, Tally), "a tally does not know the files: give flagged"
        flagged = len({f.path for f in findings})
    by_severity = (findings if isinstance(findings, Tally) else Tally.of(findings)).by_severity
    total = sum(by_severity.values())
    # a finding always comes from a linted file: never "in 2 of 1 files"
    checked = max(checked, flagged)
    if total:
        words = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "info"}
        parts = ", ".join(
            _count(by_severity[level], word, "info" if level is Severity.INFO else None)
            for level, word in words.items()
            if by_severity[level]
        )
        # every file linted gave findings: "in 2 files" (still the files linted)
        some = "" if flagged == checked else f"{flagged} of "
        where = f"in {some}{_count(checked, 'file')}"
        text = f"Found {parts} {where}"
        if fixed:
            verb = "remains" if total == 1 else "remain"
            text = f"Fixed {_count(fixed, 'finding')}; {parts} {verb} {where}"
    else:
        text = f"No findings in {_count(checked, 'file')}"
        if fixed:
            text = (
                f"Fixed {_count(fixed, 'finding')}; no findings remain in {_count(checked, 'file')}"
            )
    if unreadable:
        text += f"; {_count(unreadable, 'file')} could not be read"
    if internal:
        text += f"; an internal error in {_count(internal, 'file')}"
    text += "."
    offers = []
    if fixable:
        offers.append(f"[*] {fixable} fixable with the --fix option")
    if hidden:
        offers.append(
            f"{_count(hidden, 'hidden fix', 'hidden fixes')} can be enabled with the "
            "--unsafe-fixes option"
        )
    if offers:
        text += "\n" + (f"{offers[0]} ({offers[1]})" if len(offers) == 2 else offers[0]) + "."
    return text
