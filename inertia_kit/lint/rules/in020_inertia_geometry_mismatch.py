"""IN020 inertia-geometry-mismatch: the declared tensor is far from the geometry's."""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

import numpy as np

from inertia_kit.analysis.bounds import BOUND_RTOL
from inertia_kit.analysis.forensics.links import diagnose_basis
from inertia_kit.analysis.geometry import Geometry
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.analysis.tensors import TensorComparison, axis_name, compare_tensors
from inertia_kit.lint.findings import Finding, FixRule, Repairs, Safety, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.mass import MassProperties

if TYPE_CHECKING:
    from inertia_kit.analysis.forensics.diagnosis import Diagnosis

CODE = "IN020"
NAME = "inertia-geometry-mismatch"
SEVERITY = Severity.WARNING
SCOPE = "link"
WEIGHED = True  # judged by what it adds to its lumped body (lint.weighing)
FIX = FixRule(
    "geometry", Safety.UNSAFE, Repairs.IMPOSSIBLE, "replace the tensor with its geometry's"
)
SUMMARY = (
    "the declared tensor differs from the geometry's (declared mass, uniform density) by more "
    "than a factor about some axis"
)
OPTIONS = (
    Option(
        "factor", float, 2.5, "flag a moment more than this many times the geometry's", minimum=1.0
    ),
    Option(
        "factor_below",
        float,
        5.0,
        "flag a moment less than 1/factor_below of the geometry's",
        minimum=1.0,
    ),
    Option(
        "error_below",
        float,
        100.0,
        "an error for a moment less than 1/error_below of its collision geometry's",
        minimum=1.0,
    ),
)

# A slip that forensics recognises (analysis.forensics: about another point, other axes, a
# unit, flipped signs, transposed values) is reported from a smaller deviation than the factors:
# more than MISMATCH about some axis. With its IN06x rule enabled, that rule's finding replaces
# this one (SUPERSEDES); otherwise the slip is named here.
MISMATCH = 1.5

# the slip each forensic rule names, in a few words for the message (its wording is the detail)
_SLIPS = {
    "IN060": "about another point",
    "IN061": "signs flipped",
    "IN062": "in other axes",
    "IN063": "in other units",
    "IN064": "values transposed",
}


def _about(axis: np.ndarray) -> str:
    """``ixx`` for a link axis, else the moment about the axis."""
    name = axis_name(axis)
    if name is not None:
        return f"i{name}{name}"
    if axis[np.argmax(np.abs(axis))] < 0:
        axis = -axis
    return "the moment about the axis (" + ", ".join(fmt(v, 3) for v in axis) + ")"


def _short_about(axis: np.ndarray) -> str:
    """``ixx`` for a link axis, else ``a moment`` (the detail gives the axis)."""
    name = axis_name(axis)
    return f"i{name}{name}" if name is not None else "a moment"


def _ratio(ratio: float) -> str:
    """``2.5 times`` or ``1/10 of``."""
    return f"{fmt(ratio, 3)} times" if ratio > 1 else f"1/{fmt(1 / ratio, 3)} of"


def _prefer_link_axis(
    axis: np.ndarray, ratio: float, declared: np.ndarray, expected: np.ndarray
) -> np.ndarray:
    """
    A link axis with the same moment ratio as ``axis``, if there is one: when two ratios are
    equal (a symmetric body) the eigenvector is any axis of their plane, and ``ixx`` reads
    better than an arbitrary direction in it.
    """
    for candidate in np.eye(3):
        value = (candidate @ declared @ candidate) / (candidate @ expected @ candidate)
        if abs(value - ratio) <= 1e-6 * ratio:
            return candidate
    return axis


def _verdict(
    link: LinkAnalysis,
    basis: Geometry,
    declared: MassProperties,
    expected: MassProperties,
    above: float,
    below: float,
) -> tuple[TensorComparison, Diagnosis | None] | None:
    """The comparison with one geometry and the slip it shows, if it is far; else None."""
    comparison = compare_tensors(declared.inertia, expected.inertia)
    if comparison is None or comparison.factor <= min(MISMATCH, above, below):
        return None  # close enough whatever the cause: no need to look for a slip
    # a slip explained within rounding (an IN06x finding), else the likely one
    diagnosis = diagnose_basis(link, basis) or diagnose_basis(link, basis, loose=True)
    ratios = comparison.ratios
    if ratios.max() > above or ratios.min() < 1.0 / below:
        return comparison, diagnosis
    if diagnosis is not None:
        return comparison, diagnosis
    return None


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    declared = link.declared
    if declared is None or not declared.mass > 0:
        return
    above, below = float(ctx.option("factor")), float(ctx.option("factor_below"))
    verdicts: list[tuple[Geometry, MassProperties, TensorComparison, Diagnosis | None]] = []
    for basis in link.bases:
        expected = basis.at_mass(declared.mass)
        if expected is None:
            return
        verdict = _verdict(link, basis, declared, expected, above, below)
        # a tensor that agrees with either the collision or the visual geometry is fine
        if verdict is None:
            return
        verdicts.append((basis, expected, *verdict))
    if not verdicts:
        return
    geometry, expected, comparison, diagnosis = verdicts[0]
    worst = comparison.worst
    ratio = float(comparison.ratios[worst])
    axis = _prefer_link_axis(comparison.axes[worst], ratio, declared.inertia, expected.inertia)
    moment = float(axis @ declared.inertia @ axis)
    estimate = float(axis @ expected.inertia @ axis)
    relation = _ratio(ratio)
    notes = [] if diagnosis is None else [f"likely {diagnosis.wording.summary} ({diagnosis.code})"]
    severity = None
    excess = link.excess
    beyond = excess is not None and excess.ratio > 1.0 + BOUND_RTOL
    firmness = link.firmness if beyond else None
    if firmness is not None:
        # an error only when the bound holds whichever way the written numbers were rounded,
        # on collision geometry (analysis.firmness); else a warning that says why
        if firmness.firm:
            severity = Severity.ERROR
            notes.append(
                f"no {fmt(declared.mass)} kg inside the link's geometry can have it (IN023)"
            )
        else:
            notes.append(
                f"beyond what {fmt(declared.mass)} kg inside the link's geometry can have, "
                f"but {firmness.why_not()} (IN023)"
            )
    error_below = float(ctx.option("error_below"))
    if severity is None and geometry.kind == "collision" and ratio * error_below < 1:
        # no real part comes near: their moments are 0.6 to 1.7 times their solid's, and a
        # moment this small about a heavy part's axis makes the engine spin it at will
        severity = Severity.ERROR
        notes.append(
            f"no real part's moment is below 1/{fmt(error_below)} of its solid's (they are "
            "0.6 to 1.7 times it): a placeholder, a unit or a slip of digits"
        )
    tensor = expected.cleaned().inertia
    inertial = link.link.inertial
    assert inertial is not None
    # the message: the moment, its ratio to the geometry's and the slip, named by its rule; the
    # values, the geometry's dimensions, what the slip is and the bound are in the detail
    slip = ""
    if diagnosis is not None:
        slip = f", likely {_SLIPS.get(diagnosis.code, 'a slip')} ({diagnosis.code})"
    basis = (
        f"{_about(axis)} = {fmt(moment, 4)} kg·m² but its {geometry.describe()} with the "
        f"declared {fmt(declared.mass)} kg gives {fmt(estimate, 4)} kg·m² ({relation} that)"
    )
    yield ctx.finding(
        f"link `{link.name}`: {_short_about(axis)} {relation} its "
        f"{geometry.name(possessive=True)}{slip}",
        inertial.inertia_source or inertial.source,
        link=link.name,
        expected={
            "mass": declared.mass,
            "xyz": [float(v) for v in expected.cleaned().com],
            "ixx": float(tensor[0, 0]),
            "ixy": float(tensor[0, 1]),
            "ixz": float(tensor[0, 2]),
            "iyy": float(tensor[1, 1]),
            "iyz": float(tensor[1, 2]),
            "izz": float(tensor[2, 2]),
            "basis": geometry.kind,
            "ratio": ratio,
            "axis": [float(v) for v in axis],
        },
        help="write the tensor of the link's real mass distribution about its centre of mass, "
        "in the axes of <inertial><origin rpy>; the expected values assume uniform density",
        detail="; ".join([basis, *notes]),
        severity=severity,
        # only an error is certainly impossible; a warning may be a real part (`--fix all`)
        repairs=None if severity is Severity.ERROR else Repairs.DOUBTFUL,
    )
