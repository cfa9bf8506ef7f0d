"""IN063 inertia-unit-slip: the declared tensor or mass is in another unit."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.forensics.links import explain
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.lint.findings import Finding, FixRule, Repairs, Safety, Severity
from inertia_kit.lint.rules import RuleContext

CODE = "IN063"
NAME = "inertia-unit-slip"
SEVERITY = Severity.WARNING
SCOPE = "link"
WEIGHED = True  # judged by what it adds to its lumped body (lint.weighing)
FIX = FixRule("slip", Safety.SAFE, Repairs.SLIP, "undo the slip: the values in SI units")
SUMMARY = (
    "the declared tensor is the geometry's in another unit (g·m², kg·mm², kg·cm², lb·in², …) or "
    "the mass is in grams"
)
# the explanation replaces the symptoms it explains on the same link: far from the geometry
# (IN020), beyond its hard bound (IN023), too small to integrate (IN012), a density 1000 times
# too high (IN022, a mass in grams)
SUPERSEDES = ("IN020", "IN023", "IN012", "IN022")


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    why = explain(link, CODE)
    if why is not None:
        yield ctx.explanation_finding(why)
