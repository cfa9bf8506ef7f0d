"""
File discovery through inertia-lint and inertia-fill (issue 13, item 3): a colcon workspace,
exclude and extend-exclude from the configuration and the command line, .gitignore files,
files given by name with and without --force-exclude, --show-files.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner
from kit.urdf import NEGATIVE_MASS_ARM

from inertia_kit.cli import fill_main, lint_main


def write(root: Path, *names: str, text: str = NEGATIVE_MASS_ARM) -> None:
    for name in names:
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text)


def run(command, *args: str):
    return CliRunner().invoke(command, list(args), catch_exceptions=False)


def shown(command, *args: str) -> list[str]:
    result = run(command, "--show-files", *args)
    assert result.exit_code == 0, result.output
    return result.stdout.splitlines()


@pytest.fixture
def workspace(tmp_path, monkeypatch):
    """A colcon workspace after `colcon build`: the robot in src, copies in build/install/log."""
    write(
        tmp_path,
        "src/pkg/urdf/robot.urdf",
        "build/pkg/urdf/robot.urdf",
        "install/pkg/share/pkg/urdf/robot.urdf",
        "log/latest_build/pkg/robot.urdf",
    )
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_a_colcon_workspace_lints_only_src(workspace):
    assert shown(lint_main, ".") == ["src/pkg/urdf/robot.urdf"]
    result = run(lint_main, "--output-format", "concise", ".")
    assert result.exit_code == 1
    located = {line.split(":")[0] for line in result.stdout.splitlines()}
    assert located == {"src/pkg/urdf/robot.urdf"}
    assert "in 1 file" in result.stderr


def test_build_install_log_are_skipped_by_colcon_markers_without_a_src_folder(tmp_path):
    # colcon writes COLCON_IGNORE into its output folders; a package's own build/ is kept
    write(tmp_path, "ws/build/pkg/robot.urdf", "ws/install/robot.urdf", "pkg/build/robot.urdf")
    (tmp_path / "ws/build/COLCON_IGNORE").write_text("")
    (tmp_path / "ws/install/.colcon_install_layout").write_text("isolated")
    assert shown(lint_main, str(tmp_path)) == [str(tmp_path / "pkg/build/robot.urdf")]


@pytest.mark.parametrize("marker", ["COLCON_IGNORE", "AMENT_IGNORE", "CATKIN_IGNORE"])
def test_a_folder_with_an_ignore_marker_is_skipped_even_with_exclude_set(tmp_path, marker):
    write(tmp_path, "a/robot.urdf", "b/robot.urdf")
    (tmp_path / "b" / marker).write_text("")
    assert shown(lint_main, "--exclude", "nothing", str(tmp_path)) == [
        str(tmp_path / "a/robot.urdf")
    ]


def test_exclude_replaces_the_defaults_and_extend_exclude_adds(workspace):
    write(workspace, ".hidden/robot.urdf", "src/pkg/urdf/old.urdf")
    everything = shown(lint_main, "--exclude", "log", ".")
    assert everything == [
        ".hidden/robot.urdf",
        "build/pkg/urdf/robot.urdf",
        "install/pkg/share/pkg/urdf/robot.urdf",
        "src/pkg/urdf/old.urdf",
        "src/pkg/urdf/robot.urdf",
    ]
    assert shown(lint_main, "--extend-exclude", "old.urdf", ".") == ["src/pkg/urdf/robot.urdf"]
    # comma-separated and repeatable, anchored to the current folder when the pattern has a /
    assert shown(lint_main, "--exclude", "/build,install", "--exclude", "log/", ".") == [
        ".hidden/robot.urdf",
        "src/pkg/urdf/old.urdf",
        "src/pkg/urdf/robot.urdf",
    ]


def test_exclude_from_the_configuration_is_relative_to_its_folder(workspace):
    write(workspace, "src/pkg/urdf/gen/robot.urdf", "src/other/gen/robot.urdf")
    (workspace / "src/pkg/pyproject.toml").write_text(
        '[tool.inertia-kit]\nextend-exclude = ["/urdf/gen"]\n'
    )
    assert shown(lint_main, "src/pkg") == ["src/pkg/urdf/robot.urdf"]
    # another package's gen/ is not below the configuration's folder: not excluded
    assert shown(lint_main, "src/other") == ["src/other/gen/robot.urdf"]
    (workspace / "pyproject.toml").write_text('[tool.inertia-kit]\nexclude = ["src"]\n')
    assert shown(lint_main, ".") == [
        "build/pkg/urdf/robot.urdf",
        "install/pkg/share/pkg/urdf/robot.urdf",
        "log/latest_build/pkg/robot.urdf",
    ]


def test_a_bad_pattern_is_a_usage_error(workspace):
    (workspace / "pyproject.toml").write_text('[tool.inertia-kit]\nexclude = "src"\n')
    result = run(lint_main, "--show-files", ".")
    assert result.exit_code == 2
    assert "`tool.inertia-kit.exclude`: expected a list of patterns" in result.stderr


def test_gitignore_nested_with_negation_and_info_exclude(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / ".git" / "info").mkdir(parents=True)
    (tmp_path / ".git" / "info" / "exclude").write_text("scratch.urdf\n")
    write(tmp_path, "a.urdf", "scratch.urdf", "gen/x.urdf", "gen/keep.urdf", "sub/gen/y.urdf")
    write(tmp_path, "sub/local.urdf", "sub/back.urdf")
    (tmp_path / ".gitignore").write_text("gen/*\n!gen/keep.urdf\n")
    (tmp_path / "sub" / ".gitignore").write_text("local.urdf\n")
    expected = ["a.urdf", "gen/keep.urdf", "sub/back.urdf", "sub/gen/y.urdf"]
    assert shown(lint_main, ".") == expected
    assert len(shown(lint_main, "--no-respect-gitignore", ".")) == 7
    (tmp_path / "pyproject.toml").write_text("[tool.inertia-kit]\nrespect-gitignore = false\n")
    assert len(shown(lint_main, ".")) == 7
    assert shown(lint_main, "--respect-gitignore", ".") == expected


def test_a_file_given_by_name_is_linted_unless_force_exclude(workspace):
    given = "build/pkg/urdf/robot.urdf"
    assert shown(lint_main, given) == [given]
    assert run(lint_main, given).exit_code == 1
    assert shown(lint_main, "--force-exclude", given) == []
    result = run(lint_main, "--force-exclude", given, "src/pkg/urdf/robot.urdf")
    assert result.exit_code == 1
    assert "in 1 file" in result.stderr
    assert given not in result.stdout
    # as a pattern on the command line, and from the configuration
    assert shown(lint_main, "--force-exclude", "--extend-exclude", "src", "src/pkg/urdf") == []
    (workspace / "pyproject.toml").write_text("[tool.inertia-kit]\nforce-exclude = true\n")
    assert shown(lint_main, given) == []
    assert shown(lint_main, "--no-force-exclude", given) == [given]


def test_only_excluded_files_given_is_a_warning_not_a_failure(workspace):
    result = run(lint_main, "--force-exclude", "build/pkg/urdf/robot.urdf")
    assert result.exit_code == 0
    assert "no robot descriptions" in result.stderr


def test_inertia_fill_walks_folders_as_inertia_lint_does(workspace):
    write(workspace, "src/pkg/urdf/old.urdf")
    args = ("--extend-exclude", "old.urdf", ".")
    assert shown(fill_main, *args) == shown(lint_main, *args) == ["src/pkg/urdf/robot.urdf"]
    result = run(fill_main, "--check", "--fix", "invalid", *args)
    assert result.exit_code == 1
    assert "src/pkg/urdf/robot.urdf" in result.stderr
    assert "old.urdf" not in result.stderr and "build/" not in result.stderr


def test_show_files_lints_nothing_and_keeps_the_order_given(workspace):
    write(workspace, "b.urdf", "a.urdf")
    assert shown(lint_main, "b.urdf", "src", "a.urdf", "b.urdf") == [
        "b.urdf",
        "src/pkg/urdf/robot.urdf",
        "a.urdf",
    ]
    assert run(lint_main, "--show-files", "--output-format", "json", "b.urdf").stderr == ""


def test_a_fragment_is_linted_through_the_robots_of_src_not_their_build_copies(workspace):
    xacro = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
    fragment = f'<robot {xacro}><xacro:macro name="m"><link name="x"/></xacro:macro></robot>'
    top = f'<robot name="r" {xacro}><xacro:include filename="parts.xacro"/><xacro:m/></robot>'
    for folder in ("src/pkg/urdf", "build/pkg/urdf", "install/pkg/share/pkg/urdf"):
        write(workspace, f"{folder}/parts.xacro", text=fragment)
        write(workspace, f"{folder}/robot.xacro", text=top)
    (workspace / ".git").mkdir()
    result = run(lint_main, "src/pkg/urdf/parts.xacro")
    assert "linted through the robots that include it: src/pkg/urdf/robot.xacro\n" in result.stderr
