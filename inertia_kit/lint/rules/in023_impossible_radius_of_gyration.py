"""IN023 impossible-radius-of-gyration: a moment no mass inside the link's geometry can have."""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator

import numpy as np

from inertia_kit.analysis.bounds import BOUND_RTOL, MomentExcess
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.analysis.tensors import axis_name
from inertia_kit.lint.findings import Finding, FixRule, Repairs, Safety, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt

CODE = "IN023"
NAME = "impossible-radius-of-gyration"
SEVERITY = Severity.ERROR
SCOPE = "link"
WEIGHED = True  # judged by what it adds to its lumped body (lint.weighing)
FIX = FixRule(
    "geometry", Safety.UNSAFE, Repairs.IMPOSSIBLE, "replace the tensor with its geometry's"
)
SUMMARY = (
    "a moment about an axis, or a second moment along a direction, exceeds the most any "
    "distribution of the mass inside the link's geometry has"
)
OPTIONS = (
    Option("rtol", float, BOUND_RTOL, "relative excess over the bound allowed for rounding"),
)


def _envelope_text(link: LinkAnalysis) -> str:
    parts = [g.describe() for g in (link.collision, link.visual) if g.solids]
    return " and ".join(parts)


def _direction(axis: np.ndarray) -> tuple[np.ndarray, str | None, str]:
    """The axis with its largest component positive, its link-axis name, and in words."""
    name = axis_name(axis)
    if axis[np.argmax(np.abs(axis))] < 0:
        axis = -axis
    words = name if name is not None else "(" + ", ".join(fmt(v, 3) for v in axis) + ")"
    return axis, name, words


_SECOND = {"x": "(iyy + izz - ixx)/2", "y": "(ixx + izz - iyy)/2", "z": "(ixx + iyy - izz)/2"}


def _along_text(link: LinkAnalysis, excess: MomentExcess, name: str | None, words: str) -> str:
    """The second moment along a direction in words: what it is, the bound and its basis."""
    declared = link.declared
    assert declared is not None
    inertial = link.link.inertial
    assert inertial is not None
    rpy = inertial.origin.rpy
    written = name is not None and isinstance(rpy, tuple) and not any(rpy)
    formula = f" = {_SECOND[name]}" if written else ""  # type: ignore[index]
    integral = f"∫{name}² dm" if name is not None else "∫(u·r)² dm"
    low, high = excess.sides
    return (
        f"the second moment along {words}, {integral}{formula} = {fmt(excess.moment, 4)} "
        f"kg·m², is more than the {fmt(excess.bound, 4)} kg·m² any {fmt(declared.mass)} kg "
        f"inside its {_envelope_text(link)} can have with its centre of mass {fmt(low, 3)} m "
        f"and {fmt(high, 3)} m from the geometry's two ends along {words} "
        f"({fmt(declared.mass)} kg × {fmt(low, 3)} m × {fmt(high, 3)} m)"
    )


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    declared = link.declared
    if declared is None or not declared.mass > 0:
        return
    excess = link.excess
    if excess is None or not excess.ratio > 1.0 + float(ctx.option("rtol")):
        return
    firmness = link.firmness
    if firmness is not None:
        # the firm one of the two kinds of bound when the link's own is not (analysis.firmness)
        excess = firmness.excess
    axis, name, words = _direction(excess.axis)
    if excess.kind == "along" and float(axis @ excess.axis) < 0:
        # the sides are towards -u and +u: the direction turned round swaps them
        excess = dataclasses.replace(excess, axis=axis, sides=excess.sides[::-1])
    expected = link.expected
    result: dict[str, object] = {
        "kind": excess.kind,
        "max": excess.bound,
        "r_max": excess.r_max,
        "axis": [float(v) for v in axis],
    }
    if excess.kind == "along":
        result["sides"] = list(excess.sides)
    uniform = ""
    if expected is not None:
        estimate = float(axis @ expected.inertia @ axis)
        if excess.kind == "along":
            estimate = 0.5 * float(np.trace(expected.inertia)) - estimate
        result["uniform"] = estimate
        uniform = f"; uniform density gives {fmt(estimate, 4)} kg·m²"
    inertial = link.link.inertial
    assert inertial is not None
    doubt = None if firmness is None else firmness.why_not()
    if firmness is not None:
        result["firm"] = firmness.firm
        result["max_with_rounding"] = firmness.margin.bound
    # the message: the value and the bound; the geometry, the basis and the doubt: the detail
    if excess.kind == "about":
        short = (
            f"i{name}{name} = {fmt(excess.moment, 4)} kg·m²"
            if name is not None
            else f"an oblique moment of {fmt(excess.moment, 4)} kg·m²"
        )
    else:
        short = (
            f"∫{name}² dm" if name is not None else "an oblique ∫(u·r)² dm"
        ) + f" = {fmt(excess.moment, 4)} kg·m²"
    if excess.kind == "about":
        what = f"i{name}{name}" if name is not None else f"the moment about the axis {words}"
        gyration = float(np.sqrt(excess.moment / declared.mass))
        claim = (
            f"{what} = {fmt(excess.moment, 4)} kg·m² (radius of gyration {fmt(gyration, 3)} m) "
            f"is more than the {fmt(excess.bound, 4)} kg·m² any {fmt(declared.mass)} kg inside "
            f"its {_envelope_text(link)} can have about that axis through the declared centre "
            f"of mass (the geometry reaches {fmt(excess.r_max, 3)} m from it)"
        )
        help = (
            "the tensor is impossible for this geometry: recompute it about the centre of mass "
            "(a value about the joint, in g·mm² or a placeholder like 1.0 lands here), or fix "
            "the geometry if the part is larger than its shapes"
        )
    else:
        claim = _along_text(link, excess, name, words)
        integral = f"∫{name}² dm" if name is not None else "∫(u·r)² dm"
        help = (
            f"the tensor is impossible for this geometry: {integral} = ½ tr(I) - uᵀIu about the "
            "centre of mass, and a mass between two planes a and b from its centre of mass has "
            "at most m·a·b of it (Bhatia–Davis; two point masses on the planes reach it); a "
            "disc's ½ m r² written for all three axes (a wheel, a rotor) lands here: recompute "
            "the tensor about the centre of mass, or fix the geometry if the part is thicker "
            f"along {words} than its shapes"
        )
    yield ctx.finding(
        f"link `{link.name}`: {short} exceeds the {fmt(excess.bound, 4)} kg·m² its geometry allows",
        inertial.inertia_source or inertial.source,
        link=link.name,
        expected=result,
        detail=f"{claim}{uniform}"
        + ("" if doubt is None else f"; a warning, not an error: {doubt}"),
        help=help
        if doubt is None
        else "check the tensor against the part (recompute it about the centre of mass), or "
        "make the collision geometry as large as the part if the tensor is right",
        severity=None if doubt is None else Severity.WARNING,
        # a warning may be a real part: only `inertia-fill --fix all` replaces it
        repairs=None if doubt is None else Repairs.DOUBTFUL,
    )
