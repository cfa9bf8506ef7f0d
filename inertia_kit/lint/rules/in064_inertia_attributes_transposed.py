"""IN064 inertia-attributes-transposed: the six inertia values are in the wrong attributes."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.forensics.links import explain
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.lint.findings import Finding, FixRule, Repairs, Safety, Severity
from inertia_kit.lint.rules import RuleContext

CODE = "IN064"
NAME = "inertia-attributes-transposed"
SEVERITY = Severity.WARNING
SCOPE = "link"
WEIGHED = True  # judged by what it adds to its lumped body (lint.weighing)
FIX = FixRule("slip", Safety.SAFE, Repairs.SLIP, "undo the slip: the values in their places")
SUMMARY = "the six inertia values are the geometry's transcribed into the wrong attributes"
# the explanation replaces the symptoms it explains on the same link: far from the geometry
# (IN020), beyond its hard bound (IN023)
SUPERSEDES = ("IN020", "IN023")


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    why = explain(link, CODE)
    if why is not None:
        yield ctx.explanation_finding(why)
