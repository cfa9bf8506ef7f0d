"""IN066 copied-inertial: a link's whole `<inertial>` is another link's, made for other geometry."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.copies import Copy, copies
from inertia_kit.analysis.expected import basis_text, geometry_tensor
from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.engines.shares import share
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt, vector_text

CODE = "IN066"
NAME = "copied-inertial"
SEVERITY = Severity.WARNING
SCOPE = "robot"
SUMMARY = (
    "a link's whole `<inertial>` (mass, centre of mass, tensor) is another link's, and fits "
    "that link's geometry, not its own"
)


def _negligible(robot: RobotAnalysis, name: str) -> bool:
    """A helper frame welded into a far larger body: what it declares cannot matter."""
    found = share(robot, name)
    return found is not None and found.negligible


def _message(copy: Copy) -> str:
    return (
        f"link `{copy.link.name}`: <inertial> copied from `{copy.original.name}`, whose "
        "geometry it fits"
    )


def _detail(copy: Copy) -> str:
    """The block that is the same, and how far it is from each link's geometry."""
    link, original = copy.link.name, copy.original.name
    declared = copy.link.declared
    assert declared is not None
    block = f"{fmt(declared.mass)} kg at {vector_text(declared.com)} m and the same six values"
    return (
        f"the `<inertial>` of `{link}` is the one of `{original}`, copied ({block}): it "
        f"fits `{original}`'s geometry ({copy.theirs.text()}) far better than its own "
        f"({copy.mine.text()})"
    )


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    for copy in copies(robot):
        link = copy.link
        if _negligible(robot, link.name):
            continue
        declared, inertial = link.declared, link.link.inertial
        assert declared is not None and inertial is not None
        own = link.geometry.at_mass(declared.mass)
        written = geometry_tensor(link, declared.mass)
        expected: dict = {"original": copy.original.name}
        if own is not None and written is not None:
            expected |= {"mass": declared.mass, "com": [float(v) for v in own.com]}
            expected |= written.fields
        geometry = (
            "" if written is None else f" ({basis_text(link, declared.mass)} {written.text()})"
        )
        yield ctx.finding(
            _message(copy),
            inertial.source,
            link=link.name,
            detail=_detail(copy),
            expected=expected,
            help=(
                f"give `{link.name}` its own mass, centre of mass and tensor, from its CAD part "
                f"or from its geometry{geometry}"
            ),
        )
