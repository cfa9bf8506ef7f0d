"""IN067 com-slip: the centre of mass is off its geometry by a sign, axis or unit slip."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from inertia_kit.analysis.com_offset import judged_com
from inertia_kit.analysis.forensics.com_slip import ComReading, diagnose_link_com
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.lint.findings import Finding, FixRule, Repairs, Safety, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt, vector_text

CODE = "IN067"
NAME = "com-slip"
SEVERITY = Severity.WARNING
SCOPE = "link"
WEIGHED = True  # judged by what it adds to its lumped body (lint.weighing)
FIX = FixRule("com-slip", Safety.UNSAFE, Repairs.LIKELY, "undo the slip of the centre of mass")
SUMMARY = (
    "the centre of mass lies outside its geometry, or far from it, and one sign flipped, two "
    "coordinates exchanged or millimetres read as metres put it back"
)
# the explanation replaces the symptom it explains on the same link
SUPERSEDES = ("IN021",)
OPTIONS = (
    Option("min_offset", float, 0.6, "explain a COM beyond this fraction of the way to the edge"),
    Option(
        "margin", float, 0.02, "an error needs the COM this fraction of the size outside the hull"
    ),
    Option(
        "min_mass_share", float, 0.01, "skip links lighter than this share of their fixed group"
    ),
)


def _length(metres: float) -> str:
    """``4 mm`` below a decimetre, else ``0.25 m``."""
    return f"{fmt(metres * 1000, 2)} mm" if metres < 0.1 else f"{fmt(metres, 3)} m"


#: the slip undone in the message, for each kind of reading (its ``words`` say it in full)
_UNDONE = {"mirrored": "with every sign negated", "unit": "read as millimetres"}


def _message(name: str, where: str, reading: ComReading, distance: float) -> str:
    """``link `arm`: COM 73% to the edge; with y negated, 10 mm from the centroid``: without
    the distance, and a frame's name, when a long name makes it too long."""
    undone = _UNDONE.get(reading.kind, f"with {reading.words}")
    brief = undone
    if reading.kind == "frame":
        undone = reading.words.replace("the point read in ", "read in ")
        brief = "read in another frame"
    from inertia_kit.analysis.forensics.candidate import one_line  # a finding's only

    head = f"link `{name}`: COM {where}; "
    return one_line(head, f"{undone}, {_length(distance)} from the centroid", brief)


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    com = judged_com(link, float(ctx.option("min_mass_share")))
    inertial = link.link.inertial
    if com is None or inertial is None:
        return
    diagnosis = diagnose_link_com(link)
    if diagnosis is None or diagnosis.reading is None:
        return  # nothing explains it, or two slips alike: IN021 reports the symptom
    if not diagnosis.declared_fraction > float(ctx.option("min_offset")):
        return
    reading = diagnosis.reading
    envelope = link.envelope
    shapes = " and ".join(g.describe() for g in (link.collision, link.visual) if g.solids)
    percent = fmt(100 * diagnosis.declared_fraction, 2)
    where = f"lies {percent}% of the way from the centroid to the edge of its {shapes}"
    # the message: how far out the point is, the slip and where undoing it puts the point
    short = f"{percent}% to the edge"
    severity = None
    if envelope is not None:
        low, high = envelope.bounds
        outside = envelope.distance_outside(com)
        if outside > float(ctx.option("margin")) * float((high - low).max()):
            where = f"lies at least {_length(outside)} outside its {shapes}"
            short = f"{_length(outside)} outside its geometry"
            severity = Severity.ERROR
    corrected = [float(v) for v in reading.point]
    yield ctx.finding(
        _message(link.name, short, reading, diagnosis.centroid_distance),
        inertial.origin.source or inertial.source,
        link=link.name,
        detail=f"the centre of mass {vector_text(com)} m {where}; with {reading.words} it is "
        f"inside, {_length(diagnosis.centroid_distance)} from the geometry's centroid",
        expected={
            "xyz": corrected,
            "hypothesis": reading.kind,
            "reading": reading.words,
            "offset_fraction": diagnosis.declared_fraction,
            "corrected_fraction": reading.fraction,
            "centroid_distance": diagnosis.centroid_distance,
        },
        help=f'write <origin xyz="{" ".join(fmt(v, 6) for v in np.round(corrected, 9))}"> '
        "(likely, not proven: no other reading of the numbers brings the centre of mass as "
        "close to the geometry's centroid; check against the CAD report before applying the "
        "fix, which is therefore unsafe)",
        severity=severity,
    )
