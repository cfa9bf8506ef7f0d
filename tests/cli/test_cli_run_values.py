"""
One run value, thin commands (issue 21, item 8): ``inertia-lint`` and ``inertia-fill`` parse the
command line and the configuration once into a frozen value (``cli.runs``), loop over what the
layer below gives back in input order, print it, and exit. The command functions stay short;
the work gives results back and prints nothing itself; ``-`` tells its report in the order a
file's run does (the summary after the findings); ``--help`` says what happens to fragments.
"""

from __future__ import annotations

import dataclasses
import inspect
import time

import pytest
from click.testing import CliRunner
from kit.urdf import box, collision, inertial, joint, link, robot
from kit.xacro_projects import LEAF, project
from kit.xacro_projects import robot as xacro_robot

from inertia_kit.cli import lint_main
from inertia_kit.cli.fill import fill, fill_command
from inertia_kit.cli.lint import lint, lint_command
from inertia_kit.cli.runs import FillRun, LintRun
from inertia_kit.lint import parallel

#: the most lines a command's function may take, from its `def` to its end, docstring included
THIN = 60

#: `arm` has a collision box and no <inertial> (IN001, an unsafe fix only); `b` a negative mass
#: and no geometry to compute one from (IN002, no fix)
TWO_FINDINGS = robot(
    link("world"),
    joint("world", "arm"),
    link("arm", collision(box(0.1, 0.1, 0.4))),
    link("b", inertial(-1, 0.01)),
    joint("arm", "b"),
    sep="\n",
)


def own_lines(function) -> int:
    """The lines of ``function`` from its ``def`` (its decorators, click's options, left out)."""
    lines = inspect.getsource(function).splitlines()
    start = next(i for i, line in enumerate(lines) if line.lstrip().startswith("def "))
    return len(lines) - start


@pytest.mark.parametrize(
    "function",
    [lint_command.callback, fill_command.callback, lint, fill],
    ids=["lint_command", "fill_command", "lint", "fill"],
)
def test_the_command_functions_are_thin(function):
    assert own_lines(function) <= THIN


def test_the_run_values_are_frozen(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    options = {"select": ("IN002",), "xacro_args": ("a:=1",), "show_diff": True}
    run = LintRun.parse(("robot.urdf",), options)
    assert (run.select, run.xacro_args, run.diff) == (("IN002",), {"a": "1"}, True)
    with pytest.raises(dataclasses.FrozenInstanceError):
        run.quiet = True
    filled = FillRun.parse(("robot.urdf",), {"mass_options": ("arm=2",), "check": True})
    assert (filled.masses, filled.writes) == ({"arm": 2.0}, False)
    with pytest.raises(dataclasses.FrozenInstanceError):
        filled.density = 1.0
    assert LintRun.parse((), {"stdin_filename": "r.urdf"}).paths == ("-",)


def slow_square(number: int) -> int:
    time.sleep(0.05 * number)
    return number * number


def test_results_come_back_in_input_order_and_closing_ends_the_workers():
    """The pool gives results back, the caller prints them in input order; a caller that stops
    (Ctrl-C while it prints) closes the iteration, which ends the workers."""
    steps = list(parallel.in_order(slow_square, [4, 1, 2, 3], 2, failed=lambda i, e: -1))
    assert [index for step in steps for index, _ in step.ready] == [0, 1, 2, 3]
    assert [result for step in steps for _, result in step.ready] == [16, 1, 4, 9]
    assert [step.done for step in steps] == [1, 2, 3, 4]

    import multiprocessing

    before = set(multiprocessing.active_children())
    running = parallel.in_order(slow_square, [1, 40, 40], 2, failed=lambda i, e: -1)
    next(running)
    workers = set(multiprocessing.active_children()) - before
    running.close()
    assert all(not worker.is_alive() for worker in workers)


def test_fill_gives_back_what_it_did_and_prints_nothing(tmp_path, monkeypatch, capsys):
    from inertia_kit.cli.filling import Finished, Planned, filling

    monkeypatch.chdir(tmp_path)
    for name in ("a.urdf", "b.urdf"):
        (tmp_path / name).write_text(TWO_FINDINGS)
    told = list(filling(FillRun.parse(("b.urdf", "a.urdf"), {"check": True})))
    assert [type(t) for t in told] == [Planned, Planned, Finished, Finished]
    assert [t.target.robot for t in told[:2]] == ["b.urdf", "a.urdf"]
    assert [t.plan.path for t in told[2:]] == ["b.urdf", "a.urdf"]
    assert capsys.readouterr() == ("", "")
    assert (tmp_path / "a.urdf").read_text() == TWO_FINDINGS  # --check writes nothing


def test_lint_fix_on_stdin_tells_the_summary_after_the_findings(tmp_path, monkeypatch):
    """(a) `--fix -` printed the summary, then the findings; it tells them as for a file (the
    report on stderr, since the fixed text goes to stdout)."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("FORCE_COLOR", raising=False)
    (tmp_path / "r.urdf").write_text(TWO_FINDINGS)
    runner = CliRunner()
    piped = runner.invoke(lint_main, ["--fix", "-"], input=TWO_FINDINGS, catch_exceptions=False)
    on_file = runner.invoke(lint_main, ["--fix", "r.urdf"], catch_exceptions=False)
    assert piped.exit_code == on_file.exit_code == 1
    assert piped.stdout == TWO_FINDINGS  # nothing the safe fixes could change
    found = piped.stderr.index("-:5:26: IN002")
    assert piped.stderr.index("-:4:1: IN001") < found < piped.stderr.index("Found 2 errors")
    assert piped.stderr == on_file.output.replace("r.urdf", "-")


def test_stdin_keeps_the_order_of_the_report_and_the_messages(tmp_path, monkeypatch):
    """Without --fix the findings go to stdout and the summary to stderr, in the order written,
    as for a file."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("FORCE_COLOR", raising=False)
    (tmp_path / "r.urdf").write_text(TWO_FINDINGS)
    runner = CliRunner()
    args = ["--output-format", "concise"]
    piped = runner.invoke(lint_main, [*args, "-"], input=TWO_FINDINGS, catch_exceptions=False)
    on_file = runner.invoke(lint_main, [*args, "r.urdf"], catch_exceptions=False)
    assert piped.output == on_file.output.replace("r.urdf", "-")
    assert piped.output.index("IN002") < piped.output.index("Found 2 errors")


def test_help_says_what_happens_to_a_fragment_and_it_does(tmp_path, monkeypatch):
    """(b) --help said fragments are skipped; a fragment robots include is linted through them,
    its findings told `via` the robot, and one no robot includes gets a note."""
    help_text = " ".join(CliRunner().invoke(lint_main, ["--help"]).output.split())
    assert "skipped" not in help_text
    assert (
        "A xacro file (or a file without links) that robots of its repository include is "
        "linted through them too: their findings located in it are reported, each saying "
        "`via` which robot (a robot also given reports them as its own)."
    ) in help_text
    assert "one no robot includes gets a note, nothing to lint" in help_text

    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("FORCE_COLOR", raising=False)
    project(
        tmp_path,
        {"urdf/leaf.xacro": LEAF, "urdf/arm.urdf.xacro": xacro_robot("leaf.xacro", "a=-2")},
    )
    project(tmp_path / "lone", {"urdf/leaf.xacro": LEAF})  # a repository of its own
    args = ["--select", "IN002", "--output-format", "concise"]
    through = CliRunner().invoke(lint_main, [*args, "arm_description/urdf/leaf.xacro"])
    assert through.exit_code == 1
    assert through.stdout.startswith("arm_description/urdf/leaf.xacro:")
    assert through.stdout.rstrip().endswith("(via arm_description/urdf/arm.urdf.xacro)")
    assert "linted through the robots that include it" in through.stderr
    lone = CliRunner().invoke(lint_main, [*args, "lone/arm_description/urdf/leaf.xacro"])
    assert (lone.exit_code, lone.stdout) == (0, "")
    assert "includes; nothing to lint" in lone.stderr
