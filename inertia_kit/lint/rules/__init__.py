"""
The rule contract: what a rule module holds, and the context its ``check`` gets.

A rule is one module ``inertia_kit/lint/rules/in<NNN>_<name>.py`` (its code in lower case, its
name with ``_`` for ``-``), imported by :mod:`inertia_kit.lint.catalog` (whose import list is
the registry), with a document ``rules/<CODE>-<name>.md`` whose examples run as tests. A rule
imports no other rule: logic two rules share lives in the layer it belongs to (analysis,
engines). Its module attributes below are the whole contract: the catalogue reads these and
nothing else, and ``tests/lint/test_rule_contract.py`` checks every rule against this list.

Every rule has:

``__doc__``
    First line ``"<CODE> <name>: what it flags."``.
``CODE: str``
    ``"IN020"``: stable, never reused; the decade is the family (DESIGN.md, rule catalog).
``NAME: str``
    ``"inertia-geometry-mismatch"``: kebab-case, names the flagged pattern.
``SEVERITY: Severity``
    The default severity. A finding may set another (``ctx.finding(..., severity=...)``): an
    impossible value escalated, a doubtful one lowered; a configured ``severity`` always wins.
``SCOPE: str``
    ``"link"``: ``check`` runs once per link, on its ``LinkAnalysis``; ``"robot"``: once, on
    the ``RobotAnalysis``; ``"suppressions"``: once, after every other rule, on the use of
    the robot's suppression comments (a list of :class:`inertia_kit.lint.comment_use.CommentUse`;
    IN090 is the one such rule).
``SUMMARY: str``
    One line: what the rule flags (SARIF's short description of the rule).
``check(target, ctx: RuleContext) -> Iterator[Finding]``
    The findings on ``target`` (see ``SCOPE``), each made by ``ctx.finding(...)``.

A rule may have:

``OPTIONS: tuple[Option, ...]``
    What ``[tool.inertia-kit.rules.<CODE>]`` may set, each a
    :class:`~inertia_kit.lint.options.Option` (name, type, default, help); ``check`` reads
    them with ``ctx.option(name)``. The document lists each under ``## Options``. None when
    absent.
``ENGINE: str``
    Makes it an engine rule (IN07x) speaking for one engine of
    :data:`inertia_kit.engines.vocabulary.ENGINES`: it runs only when that engine is chosen
    (``--engine``, ``engines = [...]``), never by ``select``.
``DESCRIPTION_FORMATS: tuple[str, ...]``
    The description formats it judges (of :data:`inertia_kit.lint.catalog.ALL_FORMATS`), for a
    rule about what only one format says or only its readers do (URDF's ``<limit>``, KDL's
    root): it stays silent on a model of another format. Every format when absent.
``SUPERSEDES: tuple[str, ...]``
    Codes of other rules whose findings on the same link a finding of this rule replaces: an
    explanation (IN063, a unit slip) replaces the symptoms it explains (IN020, far from the
    geometry). Applied only when both rules run.
``FIX: FixRule``
    The rule's fix (:class:`~inertia_kit.lint.findings.FixRule`): how the values are found,
    its safety and what it repairs. Every finding the rule makes for a link offers it (a
    finding may say what it repairs instead, ``ctx.finding(..., repairs=...)``, or that it
    has no fix, ``fixable=False``); the values are found and placed for the whole robot at
    once (:mod:`inertia_kit.lint.fixing`). ``safe``: provably right (a recognised slip
    undone, the declared values kept); ``unsafe``: a judgment (values from the geometry at an
    assumed uniform density). The document says so on a ``Fix:`` line.
``TEXT_FIX: Safety``
    For a rule whose findings carry a ready text fix of their own, not values for a link
    (IN090 removes a comment): that fix's safety, which its findings' ``Fix`` use. The
    document says so on a ``Fix:`` line.
``WEIGHED: bool``
    Its findings judge the link's own mass properties (or the geometry they are judged by),
    which engines integrate as part of the body the link's fixed joints weld it into: when
    the link carries a negligible share of that body, the runner lowers an error to a warning
    and says the share (:mod:`inertia_kit.lint.weighing`). A finding may say otherwise
    (``ctx.finding(..., weighed=False)``).
``SPOILS_GEOMETRY: bool``
    A finding of this rule on a link means its geometry cannot give values: fixes from the
    geometry are withheld for that link, with the finding's message as the reason (IN031, a
    mesh in other units).

Any other public upper-case name is the rule's own constant and its code must read it, so that
a misspelt or retired contract attribute (``SUPERSEDE``, ``DEFAULTS``) fails the contract test
instead of being ignored.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import ModuleType
from typing import Any

from inertia_kit.analysis.forensics.links import Explanation
from inertia_kit.description.model import Source
from inertia_kit.engines.vocabulary import Event
from inertia_kit.lint.findings import Finding, Fix, Repairs, Severity, severity_of


@dataclass
class RuleContext:
    """What a rule's ``check`` gets besides its target: its options and a finding factory."""

    rule: ModuleType
    # every option the rule declares: the configured value, else its default
    options: Mapping[str, Any] = field(default_factory=dict)
    severity: Severity | None = None  # configured override of the rule's default

    def option(self, name: str) -> Any:
        return self.options[name]

    def finding(
        self,
        message: str,
        source: Source | None,
        *,
        link: str | None = None,
        joint: str | None = None,
        expected: dict[str, Any] | None = None,
        help: str | None = None,
        detail: str | None = None,
        fix: Fix | None = None,
        severity: Severity | None = None,
        repairs: Repairs | None = None,
        fixable: bool = True,
        weighed: bool | None = None,
    ) -> Finding:
        """
        A finding of this rule at ``source``. For an element a xacro macro produced, the
        location is the innermost macro call (what distinguishes this instance), and the
        element's place in the macro body is kept as ``macro_path``/``macro_line``.

        ``severity`` lets a rule escalate (e.g. warning → error for an impossible value); a
        configured severity always wins. A finding for a link offers the rule's ``FIX``
        (``repairs`` overrides what it repairs; ``fixable=False``: no fix for this one).
        ``weighed`` overrides the rule's ``WEIGHED`` for this finding.
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
        wants = getattr(self.rule, "FIX", None) if fixable and link is not None else None
        if wants is not None and repairs is not None:
            wants = dataclasses.replace(wants, repairs=repairs)
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
            detail=detail,
            fix=fix,
            macro_path=macro_path,
            macro_line=macro_line,
            wants=wants,
            weighed=bool(getattr(self.rule, "WEIGHED", False) if weighed is None else weighed)
            and link is not None,
        )

    def engine_finding(self, event: Event, help: str) -> Finding:
        """An engine rule's finding for one engine event, at the severity of its verdict."""
        return self.finding(
            event.message,
            event.source,
            link=event.link,
            joint=event.joint,
            expected=event.expected,
            help=help,
            detail=event.detail,
            severity=severity_of(event.verdict),
        )

    def explanation_finding(self, why: Explanation) -> Finding:
        """
        A forensic rule's finding (IN06x) for a link its hypothesis explains: an error when the
        declared value is beyond the geometry's hard bound (it then replaces IN023's error). A
        real part's likely slip is no recognised slip: no ``inertia-fill`` mode takes its fix
        (``--fix invalid`` leaves the link, ``--fix all`` recomputes it from its geometry);
        ``inertia-lint --unsafe-fixes`` undoes the slip.
        """
        return self.finding(
            why.message,
            why.source,
            link=why.link,
            expected=why.expected,
            help=why.help,
            detail=why.detail,
            severity=Severity.ERROR if why.impossible else None,
            repairs=Repairs.LIKELY if why.likely else None,
        )
