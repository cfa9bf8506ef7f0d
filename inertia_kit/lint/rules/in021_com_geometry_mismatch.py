"""IN021 com-geometry-mismatch: the centre of mass is outside the geometry or far from it."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from inertia_kit.analysis.com_offset import judged_com, offset_fraction
from inertia_kit.analysis.forensics.com_slip import diagnose_link_com, inside_readings
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.lint.findings import Finding, FixRule, Repairs, Safety, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt

CODE = "IN021"
NAME = "com-geometry-mismatch"
SEVERITY = Severity.WARNING
SCOPE = "link"
WEIGHED = True  # judged by what it adds to its lumped body (lint.weighing)
FIX = FixRule("com", Safety.UNSAFE, Repairs.DOUBTFUL, "move the centre of mass to its geometry's")
SUMMARY = "the centre of mass lies outside the link's geometry, or far from its centroid"
OPTIONS = (
    Option("max_offset", float, 0.6, "warn beyond this fraction of the way from centroid to edge"),
    Option(
        "margin", float, 0.02, "an error needs the COM this fraction of the size outside the hull"
    ),
    Option(
        "min_mass_share", float, 0.01, "skip links lighter than this share of their fixed group"
    ),
)


def _xyz(point: np.ndarray) -> str:
    return "(" + ", ".join(fmt(v, 4) for v in point) + ")"


def _alike(link: LinkAnalysis) -> str:
    """The slips that would each explain the centre of mass alike (IN067 names one that alone
    does), for the help: ``""`` when there are none."""
    diagnosis = diagnose_link_com(link)
    if diagnosis is None or diagnosis.reading is not None or not diagnosis.rivals:
        return ""
    words = " or with ".join(r.words for r in diagnosis.rivals)
    return f"; with {words} it would be inside alike, so which slip it was is not known"


def _back_inside(link: LinkAnalysis) -> str:
    """The slips that would put an outside centre of mass back inside its geometry, but not
    near its centroid (IN067 names a slip only then), for the detail: ``""`` when none."""
    found = inside_readings(link)[:2]
    if not found:
        return ""
    said = " or ".join(f"with {r.words} ({fmt(100 * r.fraction, 2)}% to the edge)" for r in found)
    return (
        f"; {said} it would lie inside, though too far from the centroid to say it was that "
        "slip (real parts' centres of mass lie within 54% of the way)"
    )


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    com = judged_com(link, float(ctx.option("min_mass_share")))
    inertial = link.link.inertial
    if com is None or inertial is None:
        return
    source = inertial.origin.source or inertial.source
    envelope = link.envelope
    if envelope is not None:
        low, high = envelope.bounds
        size = float((high - low).max())
        outside = envelope.distance_outside(com)
        if outside > float(ctx.option("margin")) * size:
            solids = [g for g in (link.collision, link.visual) if g.solids]
            shapes = " and ".join(g.describe() for g in solids)
            named = solids[0].name() if len(solids) == 1 else "geometry"
            centroid = link.bases[0].unit.com if link.bases else None  # type: ignore[union-attr]
            yield ctx.finding(
                f"link `{link.name}`: centre of mass at least {fmt(outside, 3)} m outside its "
                f"{named}",
                source,
                link=link.name,
                detail=f"the centre of mass {_xyz(com)} m lies at least {fmt(outside, 3)} m "
                f"outside its {shapes}: no mass inside the geometry has it{_back_inside(link)}",
                expected=None if centroid is None else {"xyz": [float(v) for v in centroid]},
                help="the centre of mass is in the link frame (check the sign, the axes and the "
                "unit of <inertial><origin xyz>), or the geometry is misplaced" + _alike(link),
                severity=Severity.ERROR,
            )
            return
    bases = [g for g in link.bases if g.hull is not None]
    if not bases:
        return
    fractions = [offset_fraction(g, com) for g in bases]
    limit = float(ctx.option("max_offset"))
    # a centre of mass near the centroid of either the collision or the visual geometry is fine
    if min(fractions) <= limit:
        return
    geometry = bases[0]
    assert geometry.unit is not None
    centroid = geometry.unit.com
    distance = float(np.linalg.norm(com - centroid))
    yield ctx.finding(
        f"link `{link.name}`: centre of mass {fmt(distance, 3)} m from its "
        f"{geometry.name(kind=False, possessive=True)} centroid "
        f"({fmt(100 * fractions[0], 3)}% to the edge)",
        source,
        link=link.name,
        detail=f"the centre of mass {_xyz(com)} m is {fmt(distance, 3)} m from the centroid "
        f"{_xyz(centroid)} m of its {geometry.describe()}, {fmt(100 * fractions[0], 3)}% of "
        "the way to its edge",
        expected={"xyz": [float(v) for v in centroid], "offset_fraction": fractions[0]},
        help="check <inertial><origin xyz> (link frame, metres); a heavy motor or counterweight "
        "at one end explains an offset, a value about another frame does not" + _alike(link),
    )
