"""
`-`: the robot read from stdin (issue 13, item 4), through inertia-lint and inertia-fill:
locations told as `-` or as --stdin-filename, the configuration, relative includes and relative
meshes found as if the file stood there, --fix and inertia-fill printing the text on stdout,
unreadable input exit 2, and nothing left behind.
"""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import pytest
from click.testing import CliRunner
from console_scripts import console_script
from kit.meshes import box_triangles, write_binary_stl
from kit.urdf import NEGATIVE_MASS_ARM, box, collision, inertial, joint, link, mesh, robot

from inertia_kit.cli import fill_main, lint_main

#: `arm` has a collision box and no <inertial>: fill (and lint's unsafe fix) write one
MISSING = robot(
    link("world"), joint("world", "arm"), link("arm", collision(box(0.1, 0.1, 0.4))), sep="\n"
)


def run(command, stdin: bytes | str, *args: str):
    data = stdin.encode() if isinstance(stdin, str) else stdin
    return CliRunner().invoke(command, list(args), input=data, catch_exceptions=False)


@pytest.fixture
def here(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "pkg" / "urdf").mkdir(parents=True)
    return tmp_path


def left_behind(folder: Path) -> list[str]:
    return [p.name for p in folder.rglob("*") if p.name.startswith(".inertia-kit-stdin")]


def test_locations_say_dash_without_stdin_filename(here):
    result = run(lint_main, NEGATIVE_MASS_ARM, "--output-format", "concise", "-")
    assert result.exit_code == 1
    assert result.stdout.startswith("-:1:")
    assert "IN002" in result.stdout
    assert left_behind(here) == []


def test_stdin_filename_is_the_location_and_picks_the_configuration(here):
    result = run(
        lint_main,
        NEGATIVE_MASS_ARM,
        "--output-format",
        "json",
        "--stdin-filename",
        "pkg/urdf/r.urdf",
    )
    assert result.exit_code == 1
    assert {f["file"] for f in json.loads(result.stdout)} == {"pkg/urdf/r.urdf"}
    # per-file-ignores judge the name it stands for
    (here / "pkg" / "pyproject.toml").write_text(
        '[tool.inertia-kit.per-file-ignores]\n"urdf/r.urdf" = ["IN002"]\n'
    )
    result = run(lint_main, NEGATIVE_MASS_ARM, "--stdin-filename", "pkg/urdf/r.urdf", "-")
    assert result.exit_code == 0, result.output
    assert (
        run(lint_main, NEGATIVE_MASS_ARM, "-").exit_code == 1
    )  # the current folder: no configuration
    assert left_behind(here) == []


def test_a_relative_mesh_resolves_beside_stdin_filename(here):
    write_binary_stl(here / "pkg" / "urdf" / "part.stl", box_triangles((0.1, 0.1, 0.4)))
    text = robot(link("world"), joint("world", "arm"), link("arm", collision(mesh("part.stl"))))
    beside = run(
        lint_main, text, "--output-format", "concise", "--stdin-filename", "pkg/urdf/r.urdf"
    )
    assert "IN030" not in beside.stdout
    assert "pkg/urdf/r.urdf:" in beside.stdout  # its missing <inertial>, at least
    here_only = run(lint_main, text, "--output-format", "concise", "-")
    assert "-:1:" in here_only.stdout and "IN030" in here_only.stdout  # not found from here


def test_a_relative_xacro_include_resolves_beside_stdin_filename(here):
    xacro = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
    (here / "pkg" / "urdf" / "arm.xacro").write_text(
        f"<robot {xacro}>{link('arm', inertial(-1, 0.01))}</robot>"
    )
    top = (
        f'<robot name="r" {xacro}><xacro:include filename="arm.xacro"/>{link("world")}'
        f"{link('base', inertial(1, 0.01))}{joint('world', 'base', 'fixed')}"
        f"{joint('base', 'arm')}</robot>"
    )
    found = run(
        lint_main, top, "--output-format", "concise", "--stdin-filename", "pkg/urdf/r.xacro"
    )
    assert found.exit_code == 1
    assert "pkg/urdf/arm.xacro:1:" in found.stdout and "IN002" in found.stdout
    lost = run(lint_main, top, "-")
    assert lost.exit_code == 2
    assert "error: -:1:" in lost.stderr and "arm.xacro" in lost.stderr


def test_fix_prints_the_fixed_text_as_fixing_the_file_would(here):
    file = here / "pkg" / "urdf" / "r.urdf"
    file.write_text(MISSING)
    fixed = run(lint_main, MISSING, "--fix", "--unsafe-fixes", "--stdin-filename", str(file))
    assert fixed.exit_code == 0
    assert "Fixed 1 finding" in fixed.stderr
    assert CliRunner().invoke(lint_main, ["--fix", "--unsafe-fixes", str(file)]).exit_code == 0
    assert fixed.stdout_bytes == file.read_bytes() != MISSING.encode()
    assert "<inertial>" in fixed.stdout


def test_inertia_fill_prints_the_filled_text(here):
    file = here / "pkg" / "urdf" / "r.urdf"
    file.write_text(MISSING)
    filled = run(fill_main, MISSING, "-")
    assert filled.exit_code == 1  # as for a file: a link was filled
    assert "Filled 1 link in -: arm 4 kg" in filled.stderr
    CliRunner().invoke(fill_main, [str(file)])
    assert filled.stdout_bytes == file.read_bytes() != MISSING.encode()
    checked = run(fill_main, MISSING, "--check", "-")
    assert (checked.exit_code, checked.stdout) == (1, "")
    diff = run(fill_main, MISSING, "--diff", "--stdin-filename", "pkg/urdf/x.urdf")
    assert diff.stdout.startswith("--- a/pkg/urdf/x.urdf\n+++ b/pkg/urdf/x.urdf\n")
    assert left_behind(here) == []


@pytest.mark.parametrize(
    ("command", "args"),
    [(fill_main, ("--fix", "all")), (lint_main, ("--fix", "--unsafe-fixes"))],
    ids=["fill", "lint --fix"],
)
def test_fixes_of_the_robot_read_from_stdin_write_no_other_file(here, command, args):
    """A fix landing in a file the robot includes is not written (the fixed text alone is
    printed, as a formatter reading stdin writes nothing), and says why (fuzz run)."""
    xacro = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
    part = here / "pkg" / "urdf" / "arm.xacro"
    arm = link("arm", inertial(-1, 0.01), collision(box(0.1, 0.1, 0.4)))
    part.write_text(f"<robot {xacro}>{arm}</robot>")
    top = (
        f'<robot name="r" {xacro}><xacro:include filename="arm.xacro"/>{link("world")}'
        f"{joint('world', 'arm')}</robot>"
    )
    before = part.read_bytes()
    result = run(command, top, *args, "--stdin-filename", "pkg/urdf/r.xacro")
    assert result.exit_code == 1, result.output
    assert part.read_bytes() == before
    assert result.stdout_bytes == top.encode()  # nothing of the robot read could take the fix
    assert "not the robot read from stdin" in result.stderr or "arm.xacro" in result.stderr
    assert left_behind(here) == []


def test_force_exclude_of_the_stdin_filename(here):
    args = ("--force-exclude", "--extend-exclude", "pkg", "--stdin-filename", "pkg/urdf/r.urdf")
    linted = run(lint_main, NEGATIVE_MASS_ARM, *args)
    assert (linted.exit_code, linted.stdout) == (0, "")
    filled = run(fill_main, MISSING, *args)
    assert (filled.exit_code, filled.stdout) == (0, MISSING)  # printed back unchanged


@pytest.mark.parametrize("data", [b"", b"\xff\xfe not xml", b"<robot name='r'><link"])
def test_unreadable_input_is_exit_2(here, data):
    result = run(lint_main, data, "-")
    assert result.exit_code == 2
    assert result.stderr.startswith("error: -:")
    assert run(fill_main, data, "-").exit_code == 2


def test_dash_with_other_paths_or_add_noqa_is_a_usage_error(here):
    (here / "r.urdf").write_text(NEGATIVE_MASS_ARM)
    mixed = run(lint_main, NEGATIVE_MASS_ARM, "-", "r.urdf")
    assert mixed.exit_code == 2 and "`-` (stdin) is the only path" in mixed.stderr
    noqa = run(lint_main, NEGATIVE_MASS_ARM, "--add-noqa", "-")
    assert noqa.exit_code == 2 and "--add-noqa" in noqa.stderr


def test_a_closed_stdin_is_exit_2_through_the_real_script(here):
    done = subprocess.run(
        [console_script("inertia-lint"), "-"],
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        preexec_fn=lambda: os.close(0),
        timeout=120,
    )
    assert done.returncode == 2, done.stderr
    assert "error: -: cannot read stdin: stdin is closed" in done.stderr
