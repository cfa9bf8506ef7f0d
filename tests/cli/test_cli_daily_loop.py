"""
Small surprises of the daily loop (issue 21), each through the real command: `--add-noqa
--diff` shows the comments and writes nothing; IN041's help suggests a root name the robot does
not use; inertia-fill does not say "nothing to change" after an error.
"""

from __future__ import annotations

from click.testing import CliRunner
from kit.in_process import lint_in_process

from inertia_kit.cli.fill import fill_command
from inertia_kit.cli.lint import lint_command

ROOTED = """<robot name="r">
  <link name="base_footprint">
    <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
    </inertial>
  </link>
  <joint name="j" type="continuous"><parent link="base_footprint"/><child link="arm"/></joint>
  <link name="arm">
    <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
    </inertial>
  </link>
</robot>
"""


def _lint(path, *args: str):
    """`inertia-lint --select IN041 ARGS PATH`, in this process."""
    return CliRunner().invoke(lint_command, ["--select", "IN041", *args, str(path)])


def _rooted(tmp_path, monkeypatch):
    lint_in_process(monkeypatch)
    path = tmp_path / "r.urdf"
    path.write_text(ROOTED)
    return path


def test_add_noqa_with_diff_prints_the_comments_and_writes_nothing(tmp_path, monkeypatch):
    path = _rooted(tmp_path, monkeypatch)
    done = _lint(path, "--add-noqa", "--diff")
    assert done.exit_code == 1, done.output
    assert "+    <!-- inertia-lint: ignore[IN041] -->" in done.stdout
    assert path.read_text() == ROOTED
    # nothing to add: no diff, exit 0
    written = _lint(path, "--add-noqa")
    assert written.exit_code == 0, written.output
    again = _lint(path, "--add-noqa", "--diff")
    assert (again.exit_code, again.stdout) == (0, "")


def test_in041_suggests_a_root_the_robot_does_not_have(tmp_path, monkeypatch):
    done = _lint(_rooted(tmp_path, monkeypatch), "--output-format", "full")
    assert done.exit_code == 1
    assert '<link name="base_footprint_root"/>' in done.output
    assert '<child link="base_footprint"/>' in done.output
    assert '<link name="base_footprint"/>' not in done.output


def test_fill_does_not_say_nothing_to_change_after_an_error(tmp_path):
    bad, good = tmp_path / "bad.urdf", tmp_path / "good.urdf"
    bad.write_text("<robot")
    good.write_text(ROOTED)
    done = CliRunner().invoke(fill_command, [str(bad), str(good)])
    assert done.exit_code == 2
    assert "nothing to change" not in done.output
    assert "inertia-fill: 1 file checked, nothing written (errors above)" in done.output
    alone = CliRunner().invoke(fill_command, [str(good)])
    assert "inertia-fill: 1 file checked, nothing to change" in alone.output
