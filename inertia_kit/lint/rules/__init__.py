"""
The rule modules, and the context a rule checks with. The registry is
:mod:`inertia_kit.lint.catalog`.

A rule is a module ``inN_<name>.py`` with a one-line docstring and::

    CODE = "IN020"                      # stable, never reused
    NAME = "inertia-geometry-mismatch"  # kebab-case, names the flagged pattern
    SEVERITY = Severity.WARNING         # default; configuration may change it
    SCOPE = "link"                      # "link": check(link: LinkAnalysis, ctx) per link;
                                        # "robot": check(robot: RobotAnalysis, ctx) once
    SUMMARY = "..."                     # one line for --statistics and the index
    OPTIONS = {"factor": float}         # option types ...
    DEFAULTS = {"factor": 2.0}          # ... and defaults
    def check(target, ctx: RuleContext) -> Iterator[Finding]: ...

Every rule has a document ``rules/<CODE>-<NAME>.md`` whose examples run as tests.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import ModuleType
from typing import Any

from inertia_kit.description.model import Source
from inertia_kit.lint.findings import Finding, Fix, Severity


@dataclass
class RuleContext:
    """What a rule's ``check`` gets besides its target: its options and a finding factory."""

    rule: ModuleType
    options: Mapping[str, Any] = field(default_factory=dict)
    severity: Severity | None = None  # configured override of the rule's default

    def option(self, name: str) -> Any:
        return self.options.get(name, self.rule.DEFAULTS[name])

    def finding(
        self,
        message: str,
        source: Source | None,
        *,
        link: str | None = None,
        joint: str | None = None,
        expected: dict[str, Any] | None = None,
        help: str | None = None,
        fix: Fix | None = None,
        severity: Severity | None = None,
    ) -> Finding:
        """
        A finding of this rule at ``source``. For an element a xacro macro produced, the
        location is the innermost macro call (what distinguishes this instance), and the
        element's place in the macro body is kept as ``macro_path``/``macro_line``.

        ``severity`` lets a rule escalate (e.g. warning → error for an impossible value); a
        configured severity always wins.
        """
        # Severity.INFO is 0: pick the first that is set, not the first that is truthy
        level = next(s for s in (self.severity, severity, self.rule.SEVERITY) if s is not None)
        path, line, column, macro_path, macro_line = "", None, None, None, None
        if source is not None:
            if source.calls:
                call = source.calls[-1]
                path, line, column = call.path, call.line, call.column
                macro_path, macro_line = source.path, source.line
            else:
                path, line, column = source.path, source.line, source.column
        return Finding(
            path,
            line,
            column,
            self.rule.CODE,
            self.rule.NAME,
            level,
            message,
            link=link,
            joint=joint,
            expected=expected,
            help=help,
            fix=fix,
            macro_path=macro_path,
            macro_line=macro_line,
        )
