"""``inertia-lint -q/--quiet`` (only the findings: no notes, no summary; errors still on stderr)
and ``--output-file FILE`` (the report in FILE, written atomically, stdout empty), for every
output format, with the exit codes of a run without them."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import pytest
from click.testing import CliRunner
from console_scripts import console_script
from kit.urdf import box, collision, inertial, link, robot_lines

from inertia_kit.cli import lint_main
from inertia_kit.cli.lint import OUTPUT_FORMATS

WORKTREE = str(Path(__file__).resolve().parents[2])
FRAGMENT = (
    '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
    '  <xacro:macro name="m" params="">\n    <link name="x"/>\n  </xacro:macro>\n</robot>\n'
)


def urdf(*masses: float) -> str:
    return robot_lines(*(f"  {link(f'l{i}', inertial(m, 1))}\n" for i, m in enumerate(masses)))


@pytest.fixture
def here(tmp_path, monkeypatch):
    """A folder with a robot with a zero mass (IN002), a clean one and a xacro fragment."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("FORCE_COLOR", raising=False)
    Path("bad.urdf").write_text(urdf(0.0))
    Path("ok.urdf").write_text(urdf(1.0))
    Path("macros.xacro").write_text(FRAGMENT)
    return tmp_path


def run(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(lint_main, ["--select", "IN002", *args], catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


@pytest.mark.parametrize("output_format", OUTPUT_FORMATS)
def test_quiet_prints_the_same_findings_and_no_note_or_summary(here, output_format):
    files = ("bad.urdf", "ok.urdf", "macros.xacro")
    loud = run("--output-format", output_format, *files)
    quiet = run("--output-format", output_format, "-q", *files)
    assert loud[0] == quiet[0] == 1
    assert quiet[1] == loud[1] and "IN002" in quiet[1]
    assert "note: macros.xacro" in loud[2] and "Found 1 error" in loud[2]
    assert quiet[2] == ""


def test_quiet_keeps_errors_on_stderr_and_exit_2(here):
    Path("empty.urdf").write_text("")
    code, out, err = run("--quiet", "--output-format", "concise", "bad.urdf", "empty.urdf")
    assert code == 2
    assert out.startswith("bad.urdf:") and "IN002" in out
    assert err == "error: empty.urdf: empty file: not a robot description\n"


def test_quiet_on_a_clean_file_prints_nothing_and_exits_0(here):
    assert run("-q", "ok.urdf") == (0, "", "")


@pytest.mark.parametrize("output_format", OUTPUT_FORMATS)
def test_output_file_holds_what_stdout_would(here, output_format):
    code, stdout, stderr = run("--output-format", output_format, "bad.urdf", "ok.urdf")
    written = run(
        "--output-format", output_format, "--output-file", "report", "bad.urdf", "ok.urdf"
    )
    assert written == (code, "", stderr) == (1, "", stderr)
    assert Path("report").read_text() == stdout and "IN002" in stdout
    if output_format in ("json", "sarif"):
        json.loads(Path("report").read_text())


def test_output_file_has_no_colour_even_when_forced(here, monkeypatch):
    monkeypatch.setenv("FORCE_COLOR", "1")
    assert run("-o", "report", "bad.urdf")[:2] == (1, "")
    text = Path("report").read_text()
    assert "IN002" in text and "\x1b[" not in text


def test_output_file_with_statistics_and_diff(here):
    assert run("--statistics", "-o", "stats", "bad.urdf") == (
        1,
        "",
        run("--statistics", "bad.urdf")[2],
    )
    assert "IN002" in Path("stats").read_text()
    boxed = robot_lines(f"  {link('l0', inertial(0.0, 1), collision(box(0.1, 0.2, 0.3)))}\n")
    Path("boxed.urdf").write_text(boxed)
    code, _, _ = run("--diff", "--unsafe-fixes", "-o", "fixes.diff", "boxed.urdf")
    assert code == 1 and Path("fixes.diff").read_text().startswith("--- ")
    assert Path("boxed.urdf").read_text() == boxed  # --diff writes only the report


def test_output_file_replaces_an_old_report_and_keeps_no_temporary(here):
    Path("report").write_text("an older, longer report\n" * 100)
    assert run("-q", "-o", "report", "ok.urdf") == (0, "", "")
    assert Path("report").read_text() == ""
    assert sorted(p.name for p in here.iterdir() if p.name.startswith(".")) == []


def test_output_file_that_cannot_be_written_exits_2(here):
    code, out, err = run("-o", "no/such/folder/report", "bad.urdf")
    assert (code, out) == (2, "")
    assert "error: --output-file: no/such/folder/report" in err and "Traceback" not in err


def test_quiet_and_output_file_through_the_console_script(here):
    env = {**os.environ, "PYTHONPATH": WORKTREE}
    env.pop("FORCE_COLOR", None)
    result = subprocess.run(
        [console_script("inertia-lint"), "-q", "--output-format", "json", "-o", "out.json", "."],
        capture_output=True,
        text=True,
        env=env,
        check=False,
    )
    assert (result.returncode, result.stdout, result.stderr) == (1, "", "")
    codes = {finding["code"] for finding in json.loads(Path("out.json").read_text())}
    assert "IN002" in codes
