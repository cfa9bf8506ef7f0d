"""IN022 implausible-density: the declared mass over the geometry's volume is no material."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.geometry import Geometry
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import as_printed, fmt

CODE = "IN022"
NAME = "implausible-density"
SEVERITY = Severity.WARNING
SCOPE = "link"
WEIGHED = True  # judged by what it adds to its lumped body (lint.weighing)
SUMMARY = "declared mass / geometry volume is outside a plausible range of densities"
OPTIONS = (
    Option("min_density", float, 50.0, "the lowest plausible density, kg/m³"),
    Option("max_density", float, 25000.0, "the highest plausible density, kg/m³"),
    Option(
        "min_mass_share", float, 0.01, "skip links lighter than this share of their fixed group"
    ),
)


def _open(geometry: Geometry) -> bool:
    """A mesh was an open surface: its volume is its convex hull's, an overestimate."""
    return any(s.mesh is not None and not s.mesh.closed for s in geometry.solids)


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    inertial = link.link.inertial
    mass = None if inertial is None else inertial.mass
    if not isinstance(mass, float) or not mass > 0:
        return
    # a negligible part of a welded body (a 1 mg dummy on a fixed joint) weighs nothing there
    if link.mass_share < float(ctx.option("min_mass_share")):
        return
    low, high = float(ctx.option("min_density")), float(ctx.option("max_density"))
    verdicts = []
    for geometry in link.bases:
        density = mass / geometry.volume
        # compared as the message prints them (4 and 5 significant digits): a density that
        # prints as the bound is at the bound, whatever its last float bits say
        shown = as_printed(density, 4)
        if shown > as_printed(high):
            verdicts.append(("high", geometry, density))
        elif shown < as_printed(low) and not _open(geometry):
            verdicts.append(("low", geometry, density))
        else:
            # plausible, or low on an overestimated volume: either basis clears the link
            return
    if not verdicts:
        return
    side, geometry, density = verdicts[0]
    limit = f"above {fmt(high)}" if side == "high" else f"below {fmt(low)}"
    bound = (
        f"above the plausible {fmt(high)} kg/m³ (tungsten is 19 300)"
        if side == "high"
        else f"below the plausible {fmt(low)} kg/m³ (foam is 30, wood 500)"
    )
    assert inertial is not None
    yield ctx.finding(
        f"link `{link.name}`: {fmt(mass)} kg in its {geometry.name()} is {fmt(density, 4)} "
        f"kg/m³, {limit} kg/m³",
        inertial.mass_source or inertial.source,
        link=link.name,
        detail=f"{fmt(mass)} kg in its {geometry.describe()} of {fmt(geometry.volume, 4)} m³ is "
        f"{fmt(density, 4)} kg/m³, {bound}",
        expected={
            "density": density,
            "volume": geometry.volume,
            "mass_at_1000_kg_m3": 1000.0 * geometry.volume,
            "basis": geometry.kind,
        },
        help="check the mass (kg, not g) and the geometry's size and mesh scale; a placeholder "
        "mass on a link that moves misleads every simulator",
    )
