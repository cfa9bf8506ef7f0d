"""IN069 principal-axes-mismatch: the declared principal axes are turned from the geometry's."""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np

from inertia_kit.analysis.forensics.links import diagnose_link
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.analysis.principal_axes import AxisComparison, axes_mismatch
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt, vector_text

CODE = "IN069"
NAME = "principal-axes-mismatch"
SEVERITY = Severity.WARNING
SCOPE = "link"
WEIGHED = True  # judged by what it adds to its lumped body (lint.weighing)
SUMMARY = (
    "a principal axis of the declared tensor is turned from the geometry's by more than a real "
    "part's axes stray at that spread of moments: products with the wrong sign, other axes"
)

_RANKS = ("least", "middle", "greatest")


def _pointing(axis: np.ndarray) -> np.ndarray:
    """The axis with its largest component positive (an axis has no sign)."""
    return -axis if axis[np.argmax(np.abs(axis))] < 0 else axis


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    declared = link.declared
    inertial = link.link.inertial
    if declared is None or inertial is None or not declared.mass > 0:
        return
    found: list[tuple[str, str, AxisComparison]] = []
    for basis in link.bases:
        expected = basis.at_mass(declared.mass)
        if expected is None:
            return
        mismatch = axes_mismatch(declared.inertia, expected.inertia)
        if mismatch is None:
            return  # the axes agree with the collision or the visual geometry: fine
        found.append((basis.kind, basis.describe(), mismatch))
    # a slip the forensics name (IN060-IN064) explains the turned axes: one finding per slip
    if not found or diagnose_link(link) is not None:
        return
    kind, geometry, axis = found[0]
    rank = _RANKS[axis.rank]
    yield ctx.finding(
        f"link `{link.name}`: axis of {rank} inertia {fmt(axis.angle, 2)}° from the geometry's "
        f"(real parts ≤ {fmt(axis.limit, 2)}°)",
        inertial.inertia_source or inertial.source,
        link=link.name,
        detail=f"the declared axis of {rank} inertia {vector_text(_pointing(axis.declared), 3)} "
        f"is {fmt(axis.angle, 2)}° from its {geometry}'s "
        f"{vector_text(_pointing(axis.geometry), 3)}; with its moments apart by a factor of "
        f"{fmt(math.exp(axis.gap), 2)} a real part's axis strays at most {fmt(axis.limit, 2)}°",
        expected={
            "axis": [float(v) for v in _pointing(axis.geometry)],
            "declared_axis": [float(v) for v in _pointing(axis.declared)],
            "rank": axis.rank,
            "angle": axis.angle,
            "limit": axis.limit,
            "gap": axis.gap,
            "basis": kind,
        },
        help="check the signs of ixy, ixz and iyz (URDF's convention is ixy = -∫xy dm) and the "
        "axes the tensor was written in (<inertial><origin rpy>); a CAD report's tensor about "
        "the part's own frame must be turned into the link frame",
    )
