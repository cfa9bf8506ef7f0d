"""The `github` format: workflow commands, escaped as GitHub's toolkit escapes them."""

from __future__ import annotations

from output_kit import NO_FINDINGS, NOTE, SUMMARY, lint, no_findings

from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.output import render
from inertia_kit.lint.output.github import _escape_data, _escape_property

GITHUB = """\
::error title=inertia-lint (IN097),file=robots/arm.urdf,line=10,col=7::robots/arm.urdf:10:7: \
IN097 link `upper`: mass = 0 kg is not positive%0Ahelp: give the link's real mass
::warning title=inertia-lint (IN098),file=robots/arm.urdf,line=20,col=7::robots/arm.urdf:20:7: \
IN098 link `fore`: 25 kg, more than 10 kg%0Aa stub's limit: 10 kg
::notice title=inertia-lint (IN099),file=robots/cart.urdf.xacro,line=6,col=7::\
robots/cart.urdf.xacro:6:7: IN099 0.005 kg
::error title=inertia-lint (IN097),file=robots/cart.urdf.xacro,line=10,col=3::\
robots/cart.urdf.xacro:10:3: IN097 link `left_wheel`: mass = -1 kg is not positive%0A\
help: give the link's real mass
"""


def test_github_exactly(robots):
    assert lint("--output-format", "github", "robots") == (1, GITHUB, NOTE + SUMMARY)


def test_github_without_findings(robots):
    assert no_findings("github") == (0, "", NO_FINDINGS)


def test_github_escaping():
    """GitHub's toolkit: % CR LF in data; also : and , in property values."""
    assert _escape_data("50% a,b:c\r\nd") == "50%25 a,b:c%0D%0Ad"
    assert _escape_property("C:\\x,y%\n") == "C%3A\\x%2Cy%25%0A"
    finding = Finding("a,b:c.urdf", 3, None, "IN097", "n", Severity.INFO, "x\ny")
    assert render([finding], "github") == (
        "::notice title=inertia-lint (IN097),file=a%2Cb%3Ac.urdf,line=3::"
        "a,b:c.urdf:3: IN097 x%0Ay\n"
    )
