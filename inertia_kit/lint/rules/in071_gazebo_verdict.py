"""IN071 gazebo-verdict: what SDFormat's URDF converter (Gazebo) does with each link."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.engines.lumping import (
    OLD_SDFORMAT_MASS_TOLERANCE,
    gz_mass_matrix_valid,
    preserved_joints,
    simulated_bodies,
)
from inertia_kit.engines.vocabulary import Verdict, verdict_expected, verdict_message
from inertia_kit.lint.findings import Finding, Severity, severity_of
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt

CODE = "IN071"
NAME = "gazebo-verdict"
ENGINE = "gazebo"
SEVERITY = Severity.WARNING
SCOPE = "robot"
SUMMARY = (
    "Gazebo (sdformat's URDF converter) drops a massless link with its joint and subtree, "
    "or rejects a lumped body's invalid inertia"
)
OPTIONS: dict[str, type] = {}
DEFAULTS: dict[str, object] = {}

_URL = "http://sdformat.org/tutorials?tut=sdformat_urdf_extensions"


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
            lines.append(
                "urdf2sdf: allowing joint lumping by removing any <disableFixedJointLumping> or "
                f"<preserveFixedJoint> gazebo tag on fixed parent joint[{joint.name}], as well as "
                "ensuring that ParserConfig::URDFPreserveFixedJoint is false, could help resolve "
                f"this warning. See {_URL} for more information about this behavior."
            )
        lines.append(f"urdf2sdf: parent joint[{joint.name}] ignored.")
    if link.children:
        for child in link.children:
            if child.type == "fixed" and child.name in preserved:
                lines.append(
                    "urdf2sdf: allowing joint lumping by removing any <disableFixedJointLumping> "
                    f"or <preserveFixedJoint> gazebo tag on fixed child joint[{child.name}], as "
                    "well as ensuring that ParserConfig::URDFPreserveFixedJoint is false, could "
                    f"help resolve this warning. See {_URL} for more information about this "
                    "behavior."
                )
        lines.append(f"urdf2sdf: [{len(link.children)}] child joints ignored.")
        lines.append(f"urdf2sdf: [{len(link.children)}] child links ignored.")
    lines.append(f"urdf2sdf: link[{name}] is not modeled in sdf.")
    return " ".join(lines)


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    found = simulated_bodies(robot, ENGINE)
    preserved = preserved_joints(robot.robot)
    for dropped in found.dropped:
        link = robot.by_name[dropped.link]
        joint_words = f" with its joint `{dropped.joint}`" if dropped.joint else ""
        if dropped.link == dropped.cause:
            below = found.dropped_below(dropped.cause)
            below = tuple(b for b in below if found.dropped_link(b).reason == "ancestor")
            tail = ""
            if below:
                names = ", ".join(f"`{b}`" for b in below)
                tail = f" and the {len(below)} link{'s' * (len(below) > 1)} below it ({names})"
            message = _not_modeled(robot, dropped.link, dropped.reason, preserved)
            what = f"drops link `{dropped.link}`{joint_words}{tail}"
        elif dropped.reason == "ancestor":
            message = None
            what = (
                f"drops link `{dropped.link}`{joint_words}: its ancestor `{dropped.cause}` is "
                "not modeled (no mass)"
            )
        else:
            message = None
            what = (
                f"drops link `{dropped.link}`: it is lumped into `{dropped.cause}`, which has "
                "no mass and is not modeled"
            )
        yield ctx.finding(
            verdict_message(ENGINE, Verdict.CHANGES, message, what),
            link.link.source,
            link=dropped.link,
            joint=dropped.joint,
            expected=verdict_expected(
                ENGINE, Verdict.CHANGES, message, dropped_links=[dropped.link], cause=dropped.cause
            ),
            severity=severity_of(Verdict.CHANGES),
            help="give the link its real <inertial> (inertia-fill computes one from the geometry),"
            " or attach a massless frame with a fixed joint so that it is lumped",
        )
    for body in found.bodies:
        link = robot.by_name[body.links[0]]
        carrier = next(
            (robot.by_name[n] for n in body.links if robot.by_name[n].link.inertial is not None),
            link,
        )
        inertial = carrier.link.inertial
        source = link.link.source if inertial is None else inertial.source
        if 0 < body.declared_mass < OLD_SDFORMAT_MASS_TOLERANCE:
            message = f"urdf2sdf: link[{body.name}] has no inertia, not modeled in sdf"
            yield ctx.finding(
                f"Gazebo with libsdformat before 9.10.1 / 14.1.0 drops link `{body.name}`: its "
                f"mass {fmt(body.declared_mass)} kg is below the 1e-06 kg it took for zero "
                f"({message})",
                source,
                link=body.name,
                expected=verdict_expected(
                    ENGINE, Verdict.CHANGES, message, mass=body.declared_mass
                ),
                severity=severity_of(Verdict.CHANGES),
                help="use a realistic mass (≥ 1e-6 kg), or no <inertial> on a fixed-joint frame",
            )
        properties = body.mass_properties
        if properties is None or gz_mass_matrix_valid(properties.mass, properties.inertia):
            continue
        message = f"A link named {body.name} has invalid inertia."
        lumped = body.lumped
        where = (
            f"the body `{body.name}` (with {', '.join(f'`{n}`' for n in lumped)} lumped in)"
            if lumped
            else f"link `{body.name}`"
        )
        moments = ", ".join(fmt(m, 4) for m in properties.principal_moments)
        yield ctx.finding(
            verdict_message(
                ENGINE,
                Verdict.REFUSES,
                message,
                f"rejects the inertia of {where}, principal moments ({moments}) kg·m²",
            ),
            source,
            link=body.name,
            expected=verdict_expected(
                ENGINE,
                Verdict.REFUSES,
                message,
                links=list(body.links),
                mass=properties.mass,
                principal_moments=properties.principal_moments.tolist(),
            ),
            severity=severity_of(Verdict.REFUSES),
            help="every principal moment must be ≥ 0 and each at most the sum of the other two "
            "(gz-math MassMatrix3::IsValid); recompute the tensor about the centre of mass",
        )
