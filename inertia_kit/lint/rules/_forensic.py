"""The one check of the forensic rules IN060–IN064: report the link's diagnosis if it is theirs."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.bounds import BOUND_RTOL
from inertia_kit.analysis.forensics.links import diagnose_link
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.rules import RuleContext


def diagnosed(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    """
    A finding of ``ctx``'s rule when :func:`diagnose_link` names its code: a warning, an error
    when the declared value is beyond the geometry's hard bound (the IN023 finding it replaces).
    """
    diagnosis = diagnose_link(link)
    inertial = link.link.inertial
    if diagnosis is None or diagnosis.code != ctx.rule.CODE or inertial is None:
        return
    severity, beyond = None, ""
    excess = link.excess
    if excess is not None and excess.ratio > 1.0 + BOUND_RTOL:
        # it replaces IN023's error: a value no mass inside the geometry has stays an error
        severity = Severity.ERROR
        beyond = "; as written no mass inside the geometry can have it (IN023)"
    yield ctx.finding(
        f"link `{link.name}`: {diagnosis.wording.summary}: {diagnosis.wording.detail}{beyond}",
        inertial.inertia_source or inertial.source,
        link=link.name,
        expected=diagnosis.expected(),
        help=diagnosis.wording.help,
        severity=severity,
    )
