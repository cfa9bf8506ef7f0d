"""IN062 inertia-in-other-axes: the declared tensor is written in the axes of another frame."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.forensics.links import explain
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.lint.findings import Finding, FixRule, Repairs, Safety, Severity
from inertia_kit.lint.rules import RuleContext

CODE = "IN062"
NAME = "inertia-in-other-axes"
SEVERITY = Severity.WARNING
SCOPE = "link"
WEIGHED = True  # judged by what it adds to its lumped body (lint.weighing)
FIX = FixRule(
    "slip", Safety.SAFE, Repairs.SLIP, "undo the slip: the tensor turned into the link's axes"
)
SUMMARY = (
    "the declared tensor is the geometry's written in the axes of another frame (a shape's own "
    "axes, swapped axes, principal axes)"
)
# the explanation replaces the symptoms it explains on the same link: far from the geometry
# (IN020), beyond its hard bound (IN023)
SUPERSEDES = ("IN020", "IN023")


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    why = explain(link, CODE)
    if why is not None:
        yield ctx.explanation_finding(why)
