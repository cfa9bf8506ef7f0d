"""
The last resort of every command (cli/guard.py): an exception inertia-kit did not foresee is
exit 2 with "internal error" and the file, never 1 (findings); Ctrl-C is exit 130; never a
traceback. Faults are injected by replacing a function the command calls.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest
from click.testing import CliRunner
from kit import REPO, write
from kit.in_process import lint_in_process
from kit.urdf import box, collision, inertial, joint, link, robot

from inertia_kit.cli import fill_main, lint_main, main

GOOD = robot(link("base"), joint("base", "arm"), link("arm", inertial(0, 0.01)))
EMPTY_ARM = robot(link("base"), joint("base", "arm"), link("arm", collision(box(0.1, 0.1, 0.1))))


def boom(*_args, **_kwargs):
    raise RuntimeError("boom")


def failing_for(name, original):
    """``original``, raising ``RuntimeError("boom")`` when its first argument names ``name``."""

    def wrapper(first, *args, **kwargs):
        if name in str(getattr(getattr(first, "source", None), "path", first)):
            raise RuntimeError("boom")
        return original(first, *args, **kwargs)

    return wrapper


@pytest.fixture
def two_files(tmp_path):
    return write(tmp_path / "bad.urdf", GOOD), write(tmp_path / "good.urdf", GOOD)


@pytest.mark.parametrize(
    "output_format", ["full", "concise", "json", "github", "sarif", "junit", "gitlab"]
)
def test_lint_reports_an_internal_error_for_its_file_and_lints_the_others(
    two_files, monkeypatch, output_format
):
    from inertia_kit.lint import runner

    monkeypatch.setattr(runner, "analyse", failing_for("bad.urdf", runner.analyse))
    lint_in_process(monkeypatch)
    bad, good = two_files
    result = CliRunner().invoke(
        lint_main, ["--select", "IN002", "--output-format", output_format, str(bad), str(good)]
    )
    assert result.exit_code == 2  # never 1: a crash is not a finding
    assert f"error: {bad}: internal error: RuntimeError: boom; this is a bug" in result.stderr
    assert "please report it" in result.stderr and "Traceback" not in result.output
    # the other file was linted (gitlab tells paths relative to the current folder)
    shown = os.path.relpath(good) if output_format == "gitlab" else str(good)
    assert "IN002" in result.stdout and shown in result.stdout
    assert "an internal error in 1 file" in result.stderr
    if output_format == "json":
        finding, crash = json.loads(result.stdout)
        assert (finding["file"], finding["code"]) == (str(good), "IN002")
        assert (crash["file"], crash["code"], crash["name"]) == (
            str(bad),
            "IN000",
            "internal-error",
        )
        assert crash["message"].startswith("internal error: RuntimeError: boom")
    if output_format == "github":
        head = f"::error title=inertia-lint (IN000),file={bad}::{bad}: IN000 internal-error: "
        assert head + "internal error: RuntimeError: boom" in result.stdout
    if output_format == "junit":
        assert '<error message="internal error: RuntimeError: boom' in result.stdout
        assert 'type="internal-error"' in result.stdout
    if output_format == "gitlab":
        crash = json.loads(result.stdout)[-1]
        assert (crash["check_name"], crash["severity"]) == ("IN000", "critical")
        assert crash["description"].startswith("IN000: internal-error: internal error: Runtime")
    if output_format == "sarif":
        (invocation,) = json.loads(result.stdout)["runs"][0]["invocations"]
        assert invocation["executionSuccessful"] is False
        (note,) = invocation["toolExecutionNotifications"]
        assert note["message"]["text"].startswith("internal error: RuntimeError: boom")


def test_an_internal_error_outside_a_file_is_exit_2_too(two_files, monkeypatch):
    from inertia_kit.lint import merge

    monkeypatch.setattr(merge, "merge", boom)
    result = CliRunner().invoke(main, ["lint", str(two_files[1])])
    assert result.exit_code == 2
    assert result.stderr.startswith("error: internal error: RuntimeError: boom")


def test_traceback_on_request(two_files, monkeypatch):
    from inertia_kit.lint import runner

    monkeypatch.setattr(runner, "analyse", boom)
    monkeypatch.setenv("INERTIA_KIT_TRACEBACK", "1")
    result = CliRunner().invoke(lint_main, [str(two_files[0])])
    assert result.exit_code == 2
    assert "Traceback (most recent call last)" in result.stderr
    assert "RuntimeError: boom" in result.stderr


@pytest.mark.parametrize("command", [lint_main, fill_main])
def test_ctrl_c_is_exit_130_without_a_traceback(two_files, monkeypatch, command):
    from inertia_kit.description import loader

    def interrupted(*_args, **_kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(loader, "load", interrupted)
    result = CliRunner().invoke(command, [str(two_files[0])])
    assert (result.exit_code, result.stderr) == (130, "interrupted\n")


def test_fill_reports_an_internal_error_for_its_file_and_fills_the_others(tmp_path, monkeypatch):
    from inertia_kit.fill import plan

    bad = write(tmp_path / "bad.urdf", EMPTY_ARM)
    good = write(tmp_path / "good.urdf", EMPTY_ARM)
    monkeypatch.setattr(plan, "plan_fill", failing_for("bad.urdf", plan.plan_fill))
    result = CliRunner().invoke(main, ["fill", str(bad), str(good)])
    assert result.exit_code == 2
    assert f"error: {bad}: internal error: RuntimeError: boom" in result.stderr
    assert f"Filled 1 link in {good}" in result.stderr
    assert bad.read_text() == EMPTY_ARM and "<inertial>" in good.read_text()


def test_fill_an_internal_error_while_writing(tmp_path, monkeypatch):
    from inertia_kit.fill import plan

    path = write(tmp_path / "robot.urdf", EMPTY_ARM)
    monkeypatch.setattr(plan, "apply", boom)
    result = CliRunner().invoke(fill_main, [str(path)])
    assert result.exit_code == 2
    assert f"error: {path}: internal error: RuntimeError: boom" in result.stderr
    assert path.read_text() == EMPTY_ARM


def test_report_names_the_file(two_files, monkeypatch):
    from inertia_kit.report import robot as report

    monkeypatch.setattr(report, "render", boom)
    result = CliRunner().invoke(main, ["report", str(two_files[0])])
    assert result.exit_code == 2
    assert result.stderr.startswith(f"error: {two_files[0]}: internal error: RuntimeError: boom")


def test_mass_is_guarded(monkeypatch):
    from inertia_kit.report import mass

    monkeypatch.setattr(mass, "render", boom)
    result = CliRunner().invoke(main, ["mass", "sphere", "--radius", "0.1"])
    assert result.exit_code == 2
    assert result.stderr.startswith("error: internal error: RuntimeError: boom")


def test_usage_errors_keep_their_own_exit_code():
    result = CliRunner().invoke(main, ["mass", "sphere"])
    assert result.exit_code == 2 and "Missing option '--radius'" in result.output
    assert CliRunner().invoke(main, ["--version"]).exit_code == 0


# the real process: its exit status and stderr, as a shell or CI sees them
_INJECT = """
import sys
from inertia_kit.description import loader
def fault(*args, **kwargs):
    raise {error}
loader.load = fault
from inertia_kit.cli import lint_main
sys.argv = ["inertia-lint", {path!r}]
lint_main()
"""


@pytest.mark.parametrize(
    ("error", "status", "stderr"),
    [
        ("KeyboardInterrupt", 130, "interrupted\n"),
        ("ZeroDivisionError('x')", 2, "internal error: ZeroDivisionError: x"),
    ],
)
def test_in_a_real_process(two_files, error, status, stderr):
    code = _INJECT.format(error=error, path=str(two_files[0]))
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=os.environ.copy()
    )
    assert done.returncode == status
    assert stderr in done.stderr and "Traceback" not in done.stderr


def test_a_terminal_that_cannot_show_a_character_gets_it_escaped(tmp_path):
    """`inertia-lint examples/` on a latin-1 terminal: IN060's help writes `d dᵀ`, which latin-1
    cannot encode; it is shown as `\\u1d40` and the run ends with its findings (exit 1), not an
    internal error (exit 2)."""
    from console_scripts import console_script

    repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    done = subprocess.run(
        [console_script("inertia-lint"), os.path.join(repo, "examples", "mrm_description")],
        capture_output=True,
        env={**os.environ, "PYTHONIOENCODING": "latin-1"},
        cwd=tmp_path,
    )
    assert done.returncode == 1, done.stderr
    assert b"d d\\u1d40" in done.stdout
    assert b"internal error" not in done.stderr and b"Traceback" not in done.stderr


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="no /dev/full on this system")
def test_a_full_disk_under_stdout_is_no_bug():
    with open("/dev/full", "w") as full:
        done = subprocess.run(
            [sys.executable, "-m", "inertia_kit", "lint", "examples/mrm_description"],
            stdout=full,
            stderr=subprocess.PIPE,
            text=True,
            cwd=REPO,
        )
    assert done.returncode == 2
    assert done.stderr.endswith("error: cannot write: No space left on device\n"), done.stderr
    assert "bug" not in done.stderr and "Traceback" not in done.stderr
