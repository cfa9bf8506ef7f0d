"""
What Gazebo does with each link: SDFormat's URDF converter (``parser_urdf.cc``) lumps fixed
joints (see :mod:`~.lumping`), drops a body without mass together with its joint and everything
below it, and gz-math rejects a body's invalid inertia.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.engines.lumping import Body, preserved_joints, simulated_bodies
from inertia_kit.engines.vocabulary import Event, Verdict, event, verdict_detail
from inertia_kit.physics.formatting import fmt, vector_text

ENGINE = "gazebo"
# libsdformat before gazebosim/sdformat#1238 (9.10.1, 14.1.0) compared the mass with 0 through
# gz::math::equal, whose default tolerance is 1e-6: a lighter link was dropped as massless
OLD_SDFORMAT_MASS_TOLERANCE = 1e-6
_URL = "http://sdformat.org/tutorials?tut=sdformat_urdf_extensions"


def gz_mass_matrix_valid(
    mass: float, inertia: NDArray[np.float64], tolerance: float = 10.0
) -> bool:
    """
    gz-math ``MassMatrix3::IsValid()``: mass ≥ 0, the tensor near positive semi-definite (leading
    minors ≥ -ε) and its principal moments ≥ -ε and satisfying the triangle inequality within
    ε = tolerance · DBL_EPSILON · ½|trace| (``MassMatrix3.hh``).
    """
    i = 0.5 * (np.asarray(inertia, dtype=np.float64) + np.asarray(inertia, dtype=np.float64).T)
    if not (math.isfinite(mass) and np.isfinite(i).all()):
        return False
    eps = tolerance * np.finfo(np.float64).eps * 0.5 * abs(float(np.trace(i)))
    near_positive = (
        mass >= 0
        and i[0, 0] + eps >= 0
        and i[0, 0] * i[1, 1] - i[0, 1] ** 2 + eps >= 0
        and float(np.linalg.det(i)) + eps >= 0
    )
    a, b, c = np.linalg.eigvalsh(i)
    return bool(
        near_positive
        and a + eps >= 0
        and a + b + eps >= c
        and b + c + eps >= a
        and c + a + eps >= b
    )


def events(robot: RobotAnalysis) -> Iterator[Event]:
    """
    ``dropped`` for each link the converter drops (first those it drops, then per body):
    ``old-sdformat`` (a body lighter than 1e-6 kg, dropped before libsdformat 9.10.1 / 14.1.0)
    and ``invalid-inertia`` (the body's inertia fails ``MassMatrix3::IsValid``).
    """
    found = simulated_bodies(robot, ENGINE)
    preserved = preserved_joints(robot.robot)
    for dropped in found.dropped:
        joint = " with its joint" if dropped.joint else ""
        joint_named = f" with its joint `{dropped.joint}`" if dropped.joint else ""
        claim = None
        if dropped.link == dropped.cause:
            below = found.dropped_below(dropped.cause)
            below = tuple(b for b in below if found.dropped_link(b).reason == "ancestor")
            tail = tail_named = ""
            if below:
                names = ", ".join(f"`{b}`" for b in below)
                links = f"{len(below)} link{'s' * (len(below) > 1)}"
                tail = f" and the {links} below it"
                tail_named = f" and the {links} below it ({names})"
            message = _not_modeled(robot, dropped.link, dropped.reason, preserved)
            what = f"drops it{joint}{tail}"
            claim = _massless(robot, dropped.link, dropped.reason)
            why = (
                f"sdformat's URDF converter does not model link `{dropped.link}` ({claim}): it "
                f"drops it{joint_named}{tail_named}"
            )
        elif dropped.reason == "ancestor":
            message = None
            what, claim = f"drops it{joint}", "an ancestor has no mass"
            why = (
                f"Its ancestor `{dropped.cause}` is not modeled (no mass), so sdformat's URDF "
                f"converter drops link `{dropped.link}`{joint_named}"
            )
        else:
            message = None
            what, claim = "drops it", "lumped into a body with no mass"
            why = (
                f"Link `{dropped.link}` is lumped into `{dropped.cause}`, which has no mass and "
                "is not modeled"
            )
        yield event(
            ENGINE,
            Verdict.CHANGES,
            "dropped",
            what,
            message,
            robot.by_name[dropped.link].link.source,
            link=dropped.link,
            joint=dropped.joint,
            claim=claim,
            why=why,
            dropped_links=[dropped.link],
            cause=dropped.cause,
        )
    for body in found.bodies:
        yield from _body_events(robot, body)


def _massless(robot: RobotAnalysis, name: str, reason: str) -> str:
    """Why the converter drops a link: ``no <inertial>`` or its mass (≤ 0)."""
    inertial = robot.by_name[name].link.inertial
    if reason == "no-inertial" or inertial is None:
        return "no <inertial>"
    mass = inertial.mass
    return f"mass {fmt(mass)} kg" if isinstance(mass, float) else "mass ≤ 0"


def _body_events(robot: RobotAnalysis, body: Body) -> Iterator[Event]:
    link = robot.by_name[body.links[0]]
    carrier = next(
        (robot.by_name[n] for n in body.links if robot.by_name[n].link.inertial is not None),
        link,
    )
    inertial = carrier.link.inertial
    source = link.link.source if inertial is None else inertial.source
    if 0 < body.declared_mass < OLD_SDFORMAT_MASS_TOLERANCE:
        message = f"urdf2sdf: link[{body.name}] has no inertia, not modeled in sdf"
        mass = fmt(body.declared_mass)
        yield Event(
            ENGINE,
            Verdict.CHANGES,
            "old-sdformat",
            f"link `{body.name}`: older Gazebo drops it: mass {mass} kg, below "
            f"{fmt(OLD_SDFORMAT_MASS_TOLERANCE)} kg",
            message,
            source,
            link=body.name,
            facts={"mass": body.declared_mass},
            detail=verdict_detail(
                ENGINE,
                "Gazebo with libsdformat before 9.10.1 / 14.1.0 (gazebosim/sdformat#1238) "
                f"compared the mass with 0 within {fmt(OLD_SDFORMAT_MASS_TOLERANCE)} kg: it "
                f"takes the {mass} kg of link `{body.name}` for no mass and drops the link",
                message,
            ),
        )
    properties = body.mass_properties
    if properties is None or gz_mass_matrix_valid(properties.mass, properties.inertia):
        return
    lumped = body.lumped
    where = (
        f"the body `{body.name}` (with {', '.join(f'`{n}`' for n in lumped)} lumped in)"
        if lumped
        else f"link `{body.name}`"
    )
    moments = f"{vector_text(properties.principal_moments)} kg·m²"
    yield event(
        ENGINE,
        Verdict.REFUSES,
        "invalid-inertia",
        "rejects its lumped inertia" if lumped else "rejects its inertia",
        f"A link named {body.name} has invalid inertia.",
        source,
        link=body.name,
        claim=_invalid(properties.mass, properties.principal_moments),
        why=f"gz-math's MassMatrix3::IsValid fails on {where}: mass "
        f"{fmt(properties.mass)} kg, principal moments {moments}; each must be ≥ 0 and at "
        "most the sum of the other two",
        links=list(body.links),
        mass=properties.mass,
        principal_moments=properties.principal_moments.tolist(),
    )


def _invalid(mass: float, principal: NDArray[np.float64]) -> str:
    """What fails gz-math's test, in a few words (the numbers are in the detail)."""
    if not (math.isfinite(mass) and np.isfinite(principal).all()):
        return "a value is not finite"
    if mass < 0:
        return f"mass {fmt(mass)} kg"
    if principal[0] < 0:
        return f"principal moment {fmt(principal[0])} kg·m²"
    return "principal moments break A + B ≥ C"


def _not_modeled(robot: RobotAnalysis, name: str, reason: str, preserved: frozenset[str]) -> str:
    """The warnings sdformat's ``CreateSDF`` prints for a link it does not convert."""
    link = robot.by_name[name]
    what = (
        "no <inertial> block defined. "
        if reason == "no-inertial"
        else "a mass value of less than or equal to zero. "
    )
    lines = [
        f"urdf2sdf: link[{name}] has {what}Please ensure this link has a valid mass to prevent "
        "any missing links or joints in the resulting SDF model."
    ]
    joint = link.parent
    if joint is not None:
        if joint.type == "fixed":
            lines.append(_allow_lumping("parent", joint.name))
        lines.append(f"urdf2sdf: parent joint[{joint.name}] ignored.")
    if link.children:
        for child in link.children:
            if child.type == "fixed" and child.name in preserved:
                lines.append(_allow_lumping("child", child.name))
        lines.append(f"urdf2sdf: [{len(link.children)}] child joints ignored.")
        lines.append(f"urdf2sdf: [{len(link.children)}] child links ignored.")
    lines.append(f"urdf2sdf: link[{name}] is not modeled in sdf.")
    return " ".join(lines)


def _allow_lumping(side: str, joint: str) -> str:
    return (
        "urdf2sdf: allowing joint lumping by removing any <disableFixedJointLumping> or "
        f"<preserveFixedJoint> gazebo tag on fixed {side} joint[{joint}], as well as ensuring "
        "that ParserConfig::URDFPreserveFixedJoint is false, could help resolve this warning. "
        f"See {_URL} for more information about this behavior."
    )
