"""
Writers against other writers: every writer (``inertia-fill`` in two modes, ``inertia-lint --fix``
with and without unsafe fixes, ``--add-noqa``) edits only the text its findings and edits were
computed on, and otherwise writes nothing and exits 2 "the file changed while it was being
processed".

- An editor's save between the lint and the write, simulated in this process at two steps of
  each writer: right after the robot is loaded and analysed (before any edit is planned), and
  right before the atomic replace. Nothing is written, exit 2.
- Two writers as real processes at once on one file (:mod:`kit.concurrency`): every final state
  is one the two run one after the other give, and every file parses. A few runs per pair here;
  ``benchmarks/concurrency.py`` runs 50.
- A fill killed (SIGKILL) at any moment leaves each file as it was or as the fill writes it.
"""

from __future__ import annotations

import functools
import shutil
import signal
import time
from pathlib import Path

import pytest
from click.testing import CliRunner
from kit.concurrency import (
    CHANGED,
    PROJECTS,
    WRITERS,
    _start,
    harness,
    parses,
    run_writer,
    state,
)
from kit.in_process import lint_in_process

from inertia_kit.cli import main as umbrella

#: for each writer, a step between its lint (the robot loaded, analysed, its findings made) and
#: its first edit planned: (module, function) called once with the robot's text read
AFTER_THE_LINT = {
    "fill": ("inertia_kit.fill.plan", "plan_robot"),
    "fill-all": ("inertia_kit.fill.plan", "plan_robot"),
    "lint-fix": ("inertia_kit.lint.runner", "_with_fixes"),
    "lint-unsafe": ("inertia_kit.lint.runner", "_with_fixes"),
    "add-noqa": ("inertia_kit.lint.add_noqa", "plan"),
}
#: ... and the step that writes, once everything is planned
AT_THE_WRITE = ("inertia_kit.description.edits", "write_all_atomic")

EDITOR = "<!-- saved by an editor while inertia-kit ran -->\n"


def _editor_saves(root: Path, names: list[str]) -> dict[str, bytes]:
    """An editor's save of each file: a line added at the top (every offset moves)."""
    saved = {}
    for name in names:
        path = root / name
        text = path.read_text(encoding="utf-8")
        head, _, rest = text.partition("\n")  # after the XML declaration
        saved[name] = f"{head}\n{EDITOR}{rest}".encode()
        path.write_bytes(saved[name])
    return saved


def _save_first(monkeypatch, step: tuple[str, str], root: Path, names: list[str]) -> dict:
    """Patch ``step`` so that the editor saves ``names`` when it is first called."""
    import importlib

    module = importlib.import_module(step[0])
    original = getattr(module, step[1])
    saved: dict[str, bytes] = {}

    @functools.wraps(original)
    def step_after_a_save(*args, **kwargs):
        if not saved:
            saved.update(_editor_saves(root, names))
        return original(*args, **kwargs)

    monkeypatch.setattr(module, step[1], step_after_a_save)
    return saved


@pytest.mark.parametrize("at", ["after-the-lint", "at-the-write"])
@pytest.mark.parametrize("project", sorted(PROJECTS))
@pytest.mark.parametrize("writer", list(WRITERS))
def test_a_save_while_a_writer_runs_is_never_overwritten(
    tmp_path: Path, monkeypatch, writer: str, project: str, at: str
):
    """The reproducer: the edits were applied at the old offsets to the saved text (a second
    `<inertial>` in the xacro fragment, or one spliced into another tag)."""
    chosen = PROJECTS[project]
    root = chosen.copy(tmp_path / "project")
    monkeypatch.chdir(root)
    monkeypatch.setenv("NO_COLOR", "1")
    lint_in_process(monkeypatch)
    step = AFTER_THE_LINT[writer] if at == "after-the-lint" else AT_THE_WRITE
    saved = _save_first(monkeypatch, step, root, sorted(chosen.files))

    result = CliRunner().invoke(umbrella, [*WRITERS[writer], chosen.robot])

    assert saved, f"{writer} never reached {step[1]}: the test no longer tests anything"
    assert result.exit_code == 2, result.output
    assert CHANGED in result.stderr
    final = dict(state(root, chosen))
    assert final == saved  # the editor's text, and nothing of ours
    assert parses(tuple(final.items()))


def test_a_writer_alone_still_writes_after_the_check(tmp_path: Path, monkeypatch):
    """The check is no veto: a file left alone is written (the same steps, no save)."""
    chosen = PROJECTS["xacro"]
    root = chosen.copy(tmp_path / "project")
    monkeypatch.chdir(root)
    before = state(root, chosen)
    lint_in_process(monkeypatch)
    for writer in WRITERS:
        result = CliRunner().invoke(umbrella, [*WRITERS[writer], chosen.robot])
        assert result.exit_code in (0, 1), (writer, result.output)
    assert state(root, chosen) != before


@pytest.mark.slow
@pytest.mark.parametrize("project", sorted(PROJECTS))
def test_two_writers_at_once_end_as_one_after_the_other(tmp_path: Path, project: str):
    """Every pair of writers (each with itself too), on the URDF robot and on the xacro robot
    with the fragment both edit: two runs per pair, one starting during the other. One test
    per robot (each its own references): two halves xdist runs side by side."""
    reports = harness(2, projects=[project], scratch=tmp_path, in_process_references=True)
    bad = [
        f"{r.project} {r.a} + {r.b}: {run.told()}"
        for r in reports
        for run in r.runs
        if not (run.sequential and run.parses)
    ]
    assert not bad, "\n".join(bad)
    assert len(reports) == len(WRITERS) * (len(WRITERS) + 1) // 2
    assert {r.project for r in reports} == {project}
    shutil.rmtree(tmp_path, ignore_errors=True)


@pytest.mark.parametrize("project", sorted(PROJECTS))
def test_a_fill_killed_at_any_moment_leaves_the_old_or_the_new_file(tmp_path: Path, project):
    chosen = PROJECTS[project]
    initial = state(chosen.copy(tmp_path / "initial"), chosen)
    done = chosen.copy(tmp_path / "done")
    started = time.monotonic()
    run_writer("fill-all", done, chosen)
    took = time.monotonic() - started
    filled = state(done, chosen)
    finals = []
    for number in range(8):
        root = chosen.copy(tmp_path / f"killed-{number}")
        process = _start("fill-all", chosen, root)
        time.sleep(took * (0.6 + 0.5 * number / 8))  # the write comes at the end of a run
        process.send_signal(signal.SIGKILL)
        process.communicate()
        finals.append(state(root, chosen))
    assert all(final in (initial, filled) for final in finals)
    assert all(parses(final) for final in finals)
