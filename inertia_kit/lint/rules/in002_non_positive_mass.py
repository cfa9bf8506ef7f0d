"""IN002 non-positive-mass: a ``<mass value>`` that is zero or negative."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.lint.findings import Finding, FixRule, Repairs, Safety, Severity
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt

CODE = "IN002"
NAME = "non-positive-mass"
SEVERITY = Severity.ERROR
SCOPE = "link"
WEIGHED = True  # judged by what it adds to its lumped body (lint.weighing)
FIX = FixRule(
    "geometry", Safety.UNSAFE, Repairs.IMPOSSIBLE, "replace the <inertial> with its geometry's"
)
SUMMARY = "`<mass value>` is zero or negative"


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    inertial = link.link.inertial
    if inertial is None or not isinstance(inertial.mass, float) or inertial.mass > 0:
        return
    geometry = link.geometry
    expected = None
    basis = ""
    if geometry.unit is not None:
        expected = {"mass_at_1000_kg_m3": 1000.0 * geometry.volume, "volume": geometry.volume}
        basis = (
            f"its {geometry.describe()} holds {fmt(geometry.volume)} m³, "
            f"{fmt(1000.0 * geometry.volume)} kg at 1000 kg/m³"
        )
    yield ctx.finding(
        f"link `{link.name}`: mass = {fmt(inertial.mass)} kg is not positive",
        inertial.mass_source or inertial.source,
        link=link.name,
        expected=expected,
        detail=basis or None,
        help="give the link's real mass in kg (weigh it, or run `inertia-fill --fix invalid`); "
        "a massless frame belongs on a link with no <inertial> at all",
        # a moving link without a usable mass needs one (`inertia-fill` fills it by default)
        repairs=Repairs.MISSING if link.moves else None,
    )
