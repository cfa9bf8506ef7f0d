"""The `full` format, the default: location, source line, caret, macro body line, help."""

from __future__ import annotations

from output_kit import NO_FINDINGS, NOTE, SUMMARY, lint, no_findings

from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.output import render

FULL = """\
robots/arm.urdf:10:7: IN097 [error] link `upper`: mass = 0 kg is not positive
   |
10 |       <mass value="0"/>
   |       ^^^^^
   = help: give the link's real mass

robots/arm.urdf:20:7: IN098 [warning] link `fore`: 25 kg, more than 10 kg
   |
20 |       <mass value="25"/>
   |       ^^^^^

robots/cart.urdf.xacro:6:7: IN099 [info] 0.005 kg
  |
6 |       <mass value="0.005"/>
  |       ^^^^^

robots/cart.urdf.xacro:10:3: IN097 [error] link `left_wheel`: mass = -1 kg is not positive
   |
10 |   <xacro:wheel name="left" mass="-1"/>
   |   ^^^^^^^^^^^^
   = in the macro body: robots/wheel.xacro:10
   |
10 |         <mass value="${mass}"/>
   |         ^^^^^
   = help: give the link's real mass

"""


def test_full_exactly(robots):
    assert lint("--output-format", "full", "robots") == (1, FULL, NOTE + SUMMARY)


def test_full_is_the_default(robots):
    assert lint("robots") == (1, FULL, NOTE + SUMMARY)


def test_full_without_findings(robots):
    assert no_findings("full") == (0, "", NO_FINDINGS)


def test_full_without_a_source_line_and_with_tabs(tmp_path):
    tabbed = tmp_path / "t.urdf"
    tabbed.write_text("<robot>\n\t<link name='a'/>\n</robot>\n")
    findings = [
        Finding(str(tabbed), 2, 2, "IN097", "n", Severity.WARNING, "tabbed"),
        Finding(str(tmp_path / "gone.urdf"), 4, 1, "IN097", "n", Severity.ERROR, "no file"),
        Finding(str(tabbed), None, None, "IN097", "n", Severity.ERROR, "whole robot"),
    ]
    assert render(findings, "full") == (
        f"{tabbed}:2:2: IN097 [warning] tabbed\n"
        "  |\n"
        "2 |     <link name='a'/>\n"
        "  |     ^^^^^\n"
        "\n"
        f"{tmp_path / 'gone.urdf'}:4:1: IN097 [error] no file\n"
        "\n"
        f"{tabbed}: IN097 [error] whole robot\n"
        "\n"
    )
