"""IN060 inertia-about-other-point: the declared tensor is about another point, not the COM."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.forensics.links import explain
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.lint.findings import Finding, FixRule, Repairs, Safety, Severity
from inertia_kit.lint.rules import RuleContext

CODE = "IN060"
NAME = "inertia-about-other-point"
SEVERITY = Severity.WARNING
SCOPE = "link"
WEIGHED = True  # judged by what it adds to its lumped body (lint.weighing)
FIX = FixRule(
    "slip", Safety.SAFE, Repairs.SLIP, "undo the slip: the tensor about the centre of mass"
)
SUMMARY = (
    "the declared tensor is the geometry's about another point (the link origin, a joint, a mesh "
    "origin) instead of the centre of mass"
)
# the explanation replaces the symptoms it explains on the same link: far from the geometry
# (IN020), beyond its hard bound (IN023)
SUPERSEDES = ("IN020", "IN023")


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    why = explain(link, CODE)
    if why is not None:
        yield ctx.explanation_finding(why)
