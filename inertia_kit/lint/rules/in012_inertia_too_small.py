"""IN012 inertia-too-small: a principal moment below the floor simulators integrate stably."""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np

from inertia_kit.analysis.declared import declared_mass, written_tensor
from inertia_kit.analysis.expected import basis_text
from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
from inertia_kit.analysis.tensors import zero_tolerance
from inertia_kit.engines.lumping import lumped, positive_mass
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt, vector_text
from inertia_kit.physics.mass import MassProperties

CODE = "IN012"
NAME = "inertia-too-small"
SEVERITY = Severity.WARNING
SCOPE = "robot"
WEIGHED = True  # judged by what it adds to its lumped body (lint.weighing)
SUMMARY = (
    "a principal moment is below an absolute floor, or its radius of gyration below a length "
    "floor: too small to integrate stably"
)
# measured on the robots shipped by pybullet_data, rtb-data, example-robot-data, dexmate-urdf
# and fourier-robot-descriptions (rules/IN012-inertia-too-small.md): the smallest moment of a
# correct moving part is 3.7e-8 kg·m² (a 2.6 g finger link, radius of gyration 3.8 mm)
OPTIONS = (
    Option("min_moment", float, 1e-9, "the smallest principal moment, kg·m²"),
    Option("min_radius", float, 0.001, "the smallest radius of gyration, m"),
)


def _too_small(body: MassProperties, min_moment: float, min_radius: float) -> bool:
    smallest = float(body.principal_moments[0])
    return smallest < min_moment or smallest < body.mass * min_radius**2


def _without_origin(link: LinkAnalysis) -> MassProperties | None:
    """
    The mass and the written tensor when only the ``<inertial><origin>`` is not a number
    (IN004's): neither floor depends on it (the axes change no principal moment).
    """
    mass = declared_mass(link.link)
    tensor = written_tensor(link.link)
    if mass is None or tensor is None or link.moments is None:
        return None
    return MassProperties(mass, np.zeros(3), tensor)


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    min_moment = float(ctx.option("min_moment"))
    min_radius = float(ctx.option("min_radius"))
    for link in robot.links:
        declared = positive_mass(link)
        if declared is None:
            declared = _without_origin(link)
        if declared is None:
            continue  # the floor is relative to a positive mass: without one, IN002-IN004's
        principal = declared.principal_moments
        smallest = float(principal[0])
        if smallest <= zero_tolerance(principal):
            continue  # zero or negative: IN010's
        if not _too_small(declared, min_moment, min_radius):
            continue
        if robot.welded_to_world(link.name):
            continue  # static: never integrated
        if len(robot.group_of(link.name)) > 1:
            body = lumped(robot, link.name)
            if body is not None and not _too_small(body, min_moment, min_radius):
                # welded to a body that carries the inertia: engines integrate the lumped body
                continue
        inertial = link.link.inertial
        assert inertial is not None
        mass = declared.mass
        radius = math.sqrt(smallest / mass)
        floor = max(min_moment, mass * min_radius**2)
        if smallest < min_moment and smallest >= mass * min_radius**2:
            basis = f"the floor of {fmt(min_moment)} kg·m²"
        else:
            basis = (
                f"{fmt(mass * min_radius**2, 3)} kg·m², a {fmt(min_radius * 1000, 3)} mm radius "
                f"of gyration for {fmt(mass)} kg"
            )
        payload: dict[str, object] = {"min_moment": floor}
        geometry_text = ""
        # principal moments: the same in any axes, so the <origin> is not needed
        expected = link.geometry.at_mass(mass)
        if expected is not None:
            geometry_moments = expected.principal_moments
            payload["geometry_principal_moments"] = [float(v) for v in geometry_moments]
            geometry_text = (
                f"; {basis_text(link, mass)} principal moments "
                f"{vector_text(geometry_moments, 3)} kg·m²"
            )
        yield ctx.finding(
            f"link `{link.name}`: smallest principal moment {fmt(smallest, 3)} kg·m² is below "
            f"{fmt(floor, 3)} kg·m²",
            inertial.inertia_source or inertial.source,
            link=link.name,
            expected=payload,
            detail=f"radius of gyration {fmt(radius * 1000, 3)} mm for {fmt(mass)} kg, below "
            f"{basis}: simulators integrate such a light rotation stiffly and it jitters or blows "
            f"up{geometry_text}",
            help="use the part's real tensor about its centre of mass (from CAD, or "
            "`inertia-fill --fix invalid` from the geometry); lower `min_moment`/`min_radius` "
            "in [tool.inertia-kit.rules.IN012] if this part really is that small",
        )
