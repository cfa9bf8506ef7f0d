"""IN011 inertia-triangle-inequality: the principal moments break A + B ≥ C."""

from __future__ import annotations

import math
from collections.abc import Iterator
from decimal import Decimal

import numpy as np

from inertia_kit.analysis.expected import basis_text, geometry_tensor
from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.analysis.tensors import ZERO_ATOL, moments_text, positive_definite, zero_tolerance
from inertia_kit.description import model
from inertia_kit.engines.lumping import lumped, positive_mass
from inertia_kit.lint.findings import Finding, FixRule, Repairs, Safety, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt

CODE = "IN011"
NAME = "inertia-triangle-inequality"
SEVERITY = Severity.ERROR
SCOPE = "robot"
WEIGHED = True  # judged by what it adds to its lumped body (lint.weighing)
FIX = FixRule(
    "geometry", Safety.UNSAFE, Repairs.IMPOSSIBLE, "replace the tensor with its geometry's"
)
SUMMARY = "the principal moments break the triangle inequality A + B ≥ C"
OPTIONS = (
    # 0.01: the worst violation that rounding a body on the bound (a disk, a plate) to 3
    # significant digits produces is 0.86 % of C; 4 digits: 0.086 %
    Option("rtol", float, 0.01, "the largest violation, as a fraction of C, excused as rounding"),
    Option("digits_aware", bool, True, "excuse no more than the written digits explain"),
)

# below this fraction of C a violation is floating-point noise, whatever the digits
NOISE_RTOL = 1e-9


def half_unit(value: float) -> float:
    """
    Half a unit in the last written digit of ``value``: the most rounding can have moved it.

    The model keeps floats, not the text; the shortest text that reads back as the float has the
    digits the file had (trailing zeros aside, which only makes this larger).
    """
    if value == 0 or not math.isfinite(value):
        return 0.0
    exponent = Decimal(repr(abs(value))).normalize().as_tuple().exponent
    return 0.5 * 10.0 ** int(exponent)


def rounding_bound(inertial: model.Inertial) -> float:
    """
    The largest amount, kg·m², by which rounding the six written values can push C - A - B up:
    each eigenvalue moves by at most the spectral norm of the rounding error (Weyl), which the
    Frobenius norm of the half-units bounds; A + B - C moves by at most three times that.
    """
    u = {name: half_unit(v) for name, v in inertial.tensor_values().items()}  # type: ignore[arg-type]
    frobenius = math.sqrt(
        u["ixx"] ** 2
        + u["iyy"] ** 2
        + u["izz"] ** 2
        + 2 * (u["ixy"] ** 2 + u["ixz"] ** 2 + u["iyz"] ** 2)
    )
    return 3.0 * frobenius


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    rtol = float(ctx.option("rtol"))
    digits_aware = bool(ctx.option("digits_aware"))
    for link in robot.links:
        declared = positive_mass(link)
        # no rigid body of any mass has such a tensor: judged from the six values alone when
        # the mass or the <origin> is missing or not a number (IN003, IN004) or the mass ≤ 0
        moments = link.moments if declared is None else declared.principal_moments
        if moments is None:
            continue
        a, b, c = (float(v) for v in moments)
        tol0 = zero_tolerance(np.array([a, b, c]))
        if a < -tol0:
            continue  # a negative moment: IN010's
        if a <= tol0 and (
            declared is None
            or not (
                robot.welded_to_world(link.name)
                or (
                    len(robot.group_of(link.name)) > 1
                    and positive_definite(lumped(robot, link.name))
                )
            )
        ):
            continue  # a zero moment IN010 reports (or not, without a positive mass)
        inertial = link.link.inertial
        assert inertial is not None
        shortfall = c - (a + b)
        allowed = rtol * c
        if digits_aware:
            allowed = min(allowed, rounding_bound(inertial))
        allowed = max(allowed, NOISE_RTOL * c, 3 * ZERO_ATOL)
        if shortfall <= allowed:
            continue
        written = None if declared is None else geometry_tensor(link, declared.mass)
        basis = "" if written is None else f"; {basis_text(link, declared.mass)} {written.text()}"
        principal = np.array([a, b, c])
        shown = [0.0 if abs(v) <= tol0 else v for v in (a, b)]
        consequence = (
            "no rigid body has such a tensor: MuJoCo refuses it, Gazebo rejects it, Drake "
            "replaces it by a sphere of water, PyBullet zeroes it"
        )
        severity = None
        inference = robot.robot.inference
        if inference is not None and inference.balance:
            # the model loads: MuJoCo's balanceinertia makes the moments their mean (IN070)
            severity = Severity.WARNING
            consequence = (
                "no rigid body has such a tensor; the compiler's balanceinertia loads it as "
                f"three moments of {fmt(float(principal.sum()) / 3, 4)} kg·m², their mean"
            )
        yield ctx.finding(
            f"link `{link.name}`: the principal moments break A + B ≥ C, "
            f"{fmt(100 * shortfall / c, 3)} % short",
            inertial.inertia_source or inertial.source,
            link=link.name,
            expected=None if written is None else written.fields,
            detail=f"principal moments {moments_text(principal)}: {fmt(shown[0], 4)} + "
            f"{fmt(shown[1], 4)} = {fmt(shown[0] + shown[1], 4)} < {fmt(c, 4)}; "
            f"{consequence}{basis}",
            severity=severity,
            help="the tensor is impossible: check that it is about the centre of mass (not the "
            "link origin), that the products of inertia have the URDF sign (ixy = -∫xy dm), and "
            "that the values were not typed by hand; `inertia-fill --fix invalid` recomputes it "
            "from the geometry",
        )
