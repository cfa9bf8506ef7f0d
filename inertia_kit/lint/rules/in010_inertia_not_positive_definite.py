"""IN010 inertia-not-positive-definite: a principal moment of the declared tensor is ≤ 0."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from inertia_kit.analysis.expected import basis_text, geometry_tensor
from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.analysis.tensors import moments_text, positive_definite, zero_tolerance
from inertia_kit.engines.lumping import lumped, positive_mass
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt

CODE = "IN010"
NAME = "inertia-not-positive-definite"
SEVERITY = Severity.ERROR
SCOPE = "robot"
SUMMARY = "a principal moment of the declared inertia tensor is zero or negative"


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    for link in robot.links:
        declared = positive_mass(link)
        if declared is None:
            continue
        principal = declared.principal_moments
        tol = zero_tolerance(principal)
        if principal[0] > tol:
            continue
        inertial = link.link.inertial
        assert inertial is not None
        negative = principal[0] < -tol
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
            what = f"the tensor is zero: principal moments {moments_text(principal)}"
        elif negative:
            what = (
                f"principal moments {moments_text(principal)}: "
                f"{fmt(principal[0], 4)} kg·m² is negative"
            )
        else:
            what = f"principal moments {moments_text(principal)}: the smallest is 0"
        written = geometry_tensor(link, declared.mass)
        basis = "" if written is None else f"; {basis_text(link, declared.mass)} {written.text()}"
        engines = (
            "MuJoCo refuses the model, Gazebo rejects the tensor, Drake replaces it by a sphere "
            "of water, PyBullet zeroes it"
            if negative
            else "MuJoCo refuses the model; Drake and PyBullet cannot turn a body with no "
            "rotational inertia about that axis"
        )
        yield ctx.finding(
            f"link `{link.name}`: {what}, so the tensor is not positive definite ({engines})"
            f"{basis}",
            inertial.inertia_source or inertial.source,
            link=link.name,
            expected=None if written is None else written.fields,
            help="write the tensor about the centre of mass with every principal moment > 0 "
            "(from CAD, or `inertia-fill --fix invalid` from the geometry); a massless frame "
            "belongs on a link with no <inertial> at all",
        )
