"""The `concise` format: one line a finding, for editors; colour only when asked for."""

from __future__ import annotations

from output_kit import NO_FINDINGS, NOTE, SUMMARY, lint, no_findings

CONCISE = """\
robots/arm.urdf:10:7: IN097 link `upper`: mass = 0 kg is not positive
robots/arm.urdf:20:7: IN098 link `fore`: 25 kg, more than 10 kg
robots/cart.urdf.xacro:6:7: IN099 0.005 kg
robots/cart.urdf.xacro:10:3: IN097 link `left_wheel`: mass = -1 kg is not positive
"""


def test_concise_exactly(robots):
    assert lint("--output-format", "concise", "robots") == (1, CONCISE, NOTE + SUMMARY)


def test_concise_without_findings(robots):
    assert no_findings("concise") == (0, "", NO_FINDINGS)


def test_colour_only_when_asked_for_or_on_a_terminal(robots, monkeypatch):
    monkeypatch.setenv("FORCE_COLOR", "1")
    code, stdout, _ = lint("--output-format", "concise", "robots/arm.urdf")
    assert code == 1
    assert stdout.startswith("\x1b[1mrobots/arm.urdf:10:7\x1b[0m: \x1b[31m\x1b[1mIN097\x1b[0m link")
    monkeypatch.setenv("NO_COLOR", "1")
    assert "\x1b[" not in lint("--output-format", "concise", "robots/arm.urdf")[1]
