"""IN023 impossible-radius-of-gyration: a moment no mass inside the link's geometry can have."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from inertia_kit.analysis.bounds import BOUND_RTOL
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
SUMMARY = "a moment exceeds the most any distribution of the mass inside the link's geometry has"
OPTIONS = (
    Option("rtol", float, BOUND_RTOL, "relative excess over the bound allowed for rounding"),
)


def _envelope_text(link: LinkAnalysis) -> str:
    parts = [g.describe() for g in (link.collision, link.visual) if g.solids]
    return " and ".join(parts)


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    declared = link.declared
    if declared is None or not declared.mass > 0:
        return
    excess = link.excess
    if excess is None or not excess.ratio > 1.0 + float(ctx.option("rtol")):
        return
    axis = excess.axis
    name = axis_name(axis)
    if name is not None:
        what = f"i{name}{name}"
    else:
        if axis[np.argmax(np.abs(axis))] < 0:
            axis = -axis
        what = "the moment about the axis (" + ", ".join(fmt(v, 3) for v in axis) + ")"
    gyration = float(np.sqrt(excess.moment / declared.mass))
    uniform = ""
    expected = link.expected
    result = {
        "max": excess.bound,
        "r_max": excess.r_max,
        "axis": [float(v) for v in axis],
    }
    if expected is not None:
        estimate = float(axis @ expected.inertia @ axis)
        result["uniform"] = estimate
        uniform = f"; uniform density gives {fmt(estimate, 4)} kg·m²"
    inertial = link.link.inertial
    assert inertial is not None
    firmness = link.firmness
    doubt = None if firmness is None else firmness.why_not()
    if firmness is not None:
        result["firm"] = firmness.firm
        result["max_with_rounding"] = firmness.margin.bound
    yield ctx.finding(
        f"link `{link.name}`: {what} = {fmt(excess.moment, 4)} kg·m² (radius of gyration "
        f"{fmt(gyration, 3)} m) is more than the {fmt(excess.bound, 4)} kg·m² any "
        f"{fmt(declared.mass)} kg inside its {_envelope_text(link)} can have about that axis "
        f"through the declared centre of mass (the geometry reaches {fmt(excess.r_max, 3)} m "
        f"from it){uniform}" + ("" if doubt is None else f"; a warning, not an error: {doubt}"),
        inertial.inertia_source or inertial.source,
        link=link.name,
        expected=result,
        help="the tensor is impossible for this geometry: recompute it about the centre of mass "
        "(a value about the joint, in g·mm² or a placeholder like 1.0 lands here), or fix the "
        "geometry if the part is larger than its shapes"
        if doubt is None
        else "check the tensor against the part (recompute it about the centre of mass), or "
        "make the collision geometry as large as the part if the tensor is right",
        severity=None if doubt is None else Severity.WARNING,
        # a warning may be a real part: only `inertia-fill --fix all` replaces it
        repairs=None if doubt is None else Repairs.DOUBTFUL,
    )
