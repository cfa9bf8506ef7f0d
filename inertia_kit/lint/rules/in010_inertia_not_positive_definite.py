"""IN010 inertia-not-positive-definite: a principal moment of the declared tensor is ≤ 0."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from inertia_kit.analysis.declared import declared_mass, negative_diagonal
from inertia_kit.analysis.expected import basis_text, geometry_tensor
from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
from inertia_kit.analysis.tensors import moments_text, positive_definite, zero_tolerance
from inertia_kit.engines.lumping import lumped, positive_mass
from inertia_kit.lint.findings import Finding, FixRule, Repairs, Safety, Severity
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt

CODE = "IN010"
NAME = "inertia-not-positive-definite"
SEVERITY = Severity.ERROR
SCOPE = "robot"
WEIGHED = True  # judged by what it adds to its lumped body (lint.weighing)
FIX = FixRule(
    "geometry", Safety.UNSAFE, Repairs.IMPOSSIBLE, "replace the tensor with its geometry's"
)
SUMMARY = "a principal moment of the declared inertia tensor is zero or negative"
HELP = (
    "write the tensor about the centre of mass with every principal moment > 0 (from CAD, or "
    "`inertia-fill --fix invalid` from the geometry); a massless frame belongs on a link with "
    "no <inertial> at all"
)


def _judged(link: LinkAnalysis) -> tuple[np.ndarray, float | None] | None:
    """
    The principal moments to judge and the declared mass (``None`` when it is missing, not a
    number or ≤ 0): the whole ``<inertial>`` when it is complete, else the six values alone,
    which need neither the mass nor the ``<origin>``.
    """
    declared = positive_mass(link)
    if declared is not None:
        return declared.principal_moments, declared.mass
    if link.moments is None:
        return None
    return link.moments, declared_mass(link.link)


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    for link in robot.links:
        judged = _judged(link)
        if judged is None:
            yield from _negative_diagonal(link, ctx)
            continue
        principal, mass = judged
        tol = zero_tolerance(principal)
        if principal[0] > tol:
            continue
        inertial = link.link.inertial
        assert inertial is not None
        negative = principal[0] < -tol
        if not negative and mass is None:
            # a zero moment is wrong only for a positive mass: with the mass 0 (IN002), missing
            # (IN003) or not a number (IN004), it may be a massless frame; a negative one is
            # wrong whatever the mass
            continue
        if not negative and (
            robot.welded_to_world(link.name)
            or (len(robot.group_of(link.name)) > 1 and positive_definite(lumped(robot, link.name)))
        ):
            # a point mass (or rod, or plate) welded to a body: every engine lumps it into
            # that body, whose tensor is positive definite
            continue
        values = inertial.tensor_values()
        if all(v == 0 for v in values.values()):
            what = "all six `<inertia>` values are 0"
        elif float(np.abs(principal).max()) <= tol:
            what = "the tensor is zero"
        elif negative:
            what = f"principal moment {fmt(principal[0], 4)} kg·m² is negative"
        else:
            what = "the smallest principal moment is 0"
        # the geometry's values, in the axes the file writes them in: needs the mass and rpy
        written = None if link.declared is None else geometry_tensor(link, link.declared.mass)
        basis = "" if written is None else f"; {basis_text(link, mass)} {written.text()}"
        yield ctx.finding(
            f"link `{link.name}`: {what}: not positive definite",
            inertial.inertia_source or inertial.source,
            link=link.name,
            expected=None if written is None else written.fields,
            help=HELP,
            detail=f"principal moments {moments_text(principal)}: {_engines(negative)}{basis}",
        )


def _engines(negative: bool) -> str:
    if negative:
        return (
            "MuJoCo refuses the model, Gazebo rejects the tensor, Drake replaces it by a sphere "
            "of water, PyBullet zeroes it"
        )
    return (
        "MuJoCo refuses the model; Drake and PyBullet cannot turn a body with no rotational "
        "inertia about that axis"
    )


def _negative_diagonal(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    """
    A tensor with a value missing or not a number (IN003, IN004) cannot be judged whole, but a
    negative diagonal value already makes it impossible: the smallest principal moment is at
    most the smallest diagonal value.
    """
    negative = negative_diagonal(link.link)
    inertial = link.link.inertial
    if not negative or inertial is None:
        return
    name, value = min(negative, key=lambda item: item[1])
    yield ctx.finding(
        f"link `{link.name}`: {name} = {fmt(value, 4)} kg·m² is negative: not positive definite",
        inertial.inertia_source or inertial.source,
        link=link.name,
        help=HELP,
        detail=f"a principal moment is at most {fmt(value, 4)} kg·m², whatever the other values "
        f"are: {_engines(True)}",
    )
