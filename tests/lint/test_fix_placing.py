"""
A run that neither applies, shows nor writes out fixes does not place their edits (issue 23):
each finding still carries its fix's title and safety, so ``[*]``, "N fixable" and the hidden
unsafe fixes are those of a run that places them; where the edits go is looked for only when
they are asked for.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from kit.in_process import lint_in_process, run_split

from inertia_kit.lint.applying import applicable, hidden
from inertia_kit.lint.paths import lint_paths

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
ROBOTS = sorted(p for p in EXAMPLES.iterdir() if p.is_dir())


def _fixes(results) -> list[tuple]:
    return [
        (
            f.path,
            f.line,
            f.code,
            f.fix and f.fix.title,
            f.fix and f.fix.safety,
            *(applicable(f, unsafe) for unsafe in (False, True)),
            *(hidden(f, unsafe) for unsafe in (False, True)),
        )
        for result in results
        for f in result.findings
    ]


@pytest.mark.parametrize("robot", ROBOTS, ids=lambda p: p.name)
def test_unplaced_fixes_are_the_placed_ones_without_their_edits(robot, monkeypatch):
    placed = lint_paths([robot])
    import inertia_kit.description.placement as placement

    def refuse(*args, **kwargs):
        raise AssertionError("placed a fix nobody asked for")

    monkeypatch.setattr(placement, "place", refuse)
    unplaced = lint_paths([robot], place_fixes=False)
    assert _fixes(unplaced) == _fixes(placed)
    findings = [f for result in unplaced for f in result.findings if f.fix is not None]
    assert all(not f.fix.placed and not f.fix.edits for f in findings)


def test_the_seed_arm_has_fixes_to_tell():
    """The comparison above is not vacuous: the examples have safe and unsafe fixes."""
    results = lint_paths(ROBOTS, place_fixes=False)
    findings = [f for result in results for f in result.findings]
    assert any(applicable(f, False) for f in findings)
    assert any(hidden(f, False) for f in findings)


@pytest.mark.parametrize("output_format", ["concise", "github", "junit", "gitlab"])
def test_the_formats_that_tell_no_edit_do_not_place_them(output_format, monkeypatch):
    """Their output is that of a run that places every fix (the summary's counts included)."""
    import inertia_kit.description.placement as placement
    from inertia_kit.cli import lint_main, runs

    lint_in_process(monkeypatch)
    args = ["--output-format", output_format, "--unsafe-fixes", "--statistics", str(EXAMPLES)]
    calls = []
    original = placement.place
    monkeypatch.setattr(placement, "place", lambda *a, **k: calls.append(1) or original(*a, **k))
    monkeypatch.setattr(
        runs, "PLACES_FIXES", ("full", "concise", "json", "github", "sarif", "junit", "gitlab")
    )
    placed = run_split(lint_main, args)
    assert calls
    calls.clear()
    monkeypatch.setattr(runs, "PLACES_FIXES", ("full", "json", "sarif"))
    assert run_split(lint_main, args) == placed
    assert not calls
    assert "fixable" in placed[1] + placed[2] or output_format != "concise"
