"""
Which suppression comments suppressed something (as ruff's RUF100 needs): the suppression pass.

A rule of scope ``"suppressions"`` (IN090) cannot run with the others: it judges the comments
by the findings of every other rule. So the runner, once the rules of a robot have run, counts
for every ``ignore[...]`` comment of the robot's files which of its selectors covered a finding
(:func:`track`), and then runs the suppression rules on that count (:func:`report`). A selector
is *judged* only when every rule it picks ran on that robot: a code of a rule not selected, or
of an engine rule whose engine is not chosen, could be suppressing something we did not look
for. A comment in a file several robots include is judged over all of them
(:func:`combine`): unused when some robot judged it and none used it.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Mapping, Sequence
from types import ModuleType
from typing import TYPE_CHECKING

from inertia_kit.lint import catalog
from inertia_kit.lint.comment_use import CommentUse, Uses
from inertia_kit.lint.findings import Finding
from inertia_kit.lint.rules import RuleContext
from inertia_kit.lint.suppress import covering, directives, suppressed

if TYPE_CHECKING:
    from pathlib import Path

    from inertia_kit.lint.runner import FileResult, Selection

SCOPE = "suppressions"


def suppression_rules(rules: Iterable[ModuleType]) -> list[ModuleType]:
    return [rule for rule in rules if rule.SCOPE == SCOPE]


def track(
    files: Iterable[str],
    findings: Sequence[Finding],
    ran: Sequence[ModuleType],
    reads: Mapping[str, str | None] | None = None,
) -> Uses:
    """
    The use of every ``ignore[...]`` comment in ``files`` (a robot's files) by ``findings``
    (everything the rules ``ran`` found on that robot, before any suppression). Files with
    ``disable-file`` are not judged: nothing in them is reported. ``reads``: what the robot's
    load read (:mod:`inertia_kit.description.reads`), each comment's file's digest.
    """
    from inertia_kit.description.reads import key

    reads = {} if reads is None else reads
    codes = {rule.CODE for rule in ran if rule.SCOPE != SCOPE}
    uses: Uses = {}
    for path in dict.fromkeys(files):
        found = directives(path)
        if found.disabled:
            continue
        for ignore in found.ignores:
            judged = {s for s in ignore.selectors if _judged(s, codes)}
            lines = (ignore.first, ignore.last)
            uses[(path, ignore.line)] = CommentUse(
                path, ignore.line, ignore.selectors, lines, judged, digest=reads.get(key(path))
            )
    for finding in findings:
        for path, ignore in covering(finding):
            use = uses.get((path, ignore.line))
            if use is not None:
                use.used.update(
                    s for s in ignore.selectors if catalog.selects([s], finding.code, finding.name)
                )
    return uses


def _judged(selector: str, ran: set[str]) -> bool:
    """Whether every rule ``selector`` picks ran (so that none of them found anything)."""
    picked = [r.CODE for r in catalog.RULES if catalog.selects([selector], r.CODE, r.NAME)]
    return bool(picked) and all(code in ran for code in picked)


def combine(each: Iterable[Uses]) -> Uses:
    """The uses of several robots' runs as one: judged by any, used by any."""
    combined: Uses = {}
    for uses in each:
        for key, use in uses.items():
            if key not in combined:
                combined[key] = CommentUse(
                    use.path, use.line, use.selectors, use.lines, robots=0, digest=use.digest
                )
            total = combined[key]
            if total.digest != use.digest:  # robots read different texts: no removal planned
                total.digest = None
            total.judged |= use.judged
            total.used |= use.used
            total.robots += use.robots
    return combined


def report(
    uses: Mapping[tuple[str, int], CommentUse], selection: Selection, linted: str | Path
) -> list[Finding]:
    """
    The findings of the enabled suppression rules (IN090) on ``uses``, less those a per-file
    ignore or a comment (``disable-file``) drops, as for any rule.
    """
    found: list[Finding] = []
    for rule in suppression_rules(selection.enabled(catalog.RULES)):
        options = catalog.option_values(rule, selection.options.get(rule.CODE, {}))
        ctx = RuleContext(rule, options, selection.severities.get(rule.CODE))
        found.extend(rule.check(list(uses.values()), ctx))
    return sorted(f for f in found if not selection.ignored(f, linted) and not suppressed(f))


def judge_shared(results: Sequence[FileResult]) -> None:
    """
    A comment in a file several linted robots include is judged over all of them: each
    result's suppression-rule findings are made again from the combined use.
    """
    judged = [result for result in results if result.uses]
    if len(judged) < 2:
        return
    combined = combine(result.uses for result in judged)
    scoped = {rule.CODE for rule in suppression_rules(catalog.RULES)}
    robots = Counter(key for result in judged for key in result.uses)
    for result in judged:
        if all(robots[key] == 1 for key in result.uses):
            # no other robot has its comments: judged as they were (a streamed report may
            # have told those findings already: lint.paths.settled)
            continue
        assert result.selection is not None
        mine = {key: combined[key] for key in result.uses}
        again = report(mine, result.selection, result.path)
        result.findings = [f for f in result.findings if f.code not in scoped] + again
