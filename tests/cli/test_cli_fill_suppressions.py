"""
Every fixer honours suppression comments, as ruff's honour ``noqa``: `inertia-fill` (each mode)
leaves a link whose finding a comment covers, so a repository adopted with `--add-noqa` passes
both hooks in one go (the fill hook no longer fills what was just suppressed, which then made
the lint hook fail on IN090, the comment unused).
"""

from __future__ import annotations

import shutil
from pathlib import Path

from click.testing import CliRunner
from kit import EXAMPLES
from kit.in_process import lint_in_process

from inertia_kit.cli.fill import fill_command
from inertia_kit.cli.lint import lint_command

LIMIT = '<limit lower="-1" upper="1" effort="1" velocity="1"/>'


def _robot(arm_comment: str = "", tip_comment: str = "") -> str:
    """`arm` needs an <inertial> (IN001); `tip` holds an isotropic 0.5 kg·m² (IN013, IN023)."""
    return f"""<robot name="r">
  <link name="world"/>
  <joint name="j" type="revolute"><parent link="world"/><child link="arm"/>{LIMIT}</joint>
  {arm_comment}
  <link name="arm">
    <collision><geometry><box size="0.1 0.1 0.3"/></geometry></collision>
  </link>
  <joint name="j2" type="revolute"><parent link="arm"/><child link="tip"/>{LIMIT}</joint>
  {tip_comment}
  <link name="tip">
    <inertial><mass value="1"/><inertia ixx="0.5" ixy="0" ixz="0" iyy="0.5" iyz="0" izz="0.5"/>
    </inertial>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
</robot>
"""


def _fill(path: Path, *args: str):
    return CliRunner().invoke(fill_command, [*args, str(path)])


def test_fill_leaves_a_missing_inertial_a_comment_covers(tmp_path):
    path = tmp_path / "r.urdf"
    text = _robot(arm_comment="<!-- inertia-lint: ignore[IN001] -->")
    path.write_text(text)
    done = _fill(path)
    assert done.exit_code == 0, done.output
    assert path.read_text() == text
    # named, it is filled whatever the comments
    assert _fill(path, "--link", "arm").exit_code == 1
    assert "<mass" in path.read_text().split('name="arm"')[1]
    # without the comment the same link is filled
    path.write_text(_robot())
    assert _fill(path).exit_code == 1 and "<mass" in path.read_text().split('name="arm"')[1]


def test_fill_invalid_leaves_what_a_comment_covers_and_fixes_the_rest(tmp_path):
    path = tmp_path / "r.urdf"
    text = _robot(tip_comment="<!-- inertia-lint: ignore[IN013, IN020, IN023] -->")
    path.write_text(text)
    done = _fill(path, "--fix", "invalid")
    assert done.exit_code == 1, done.output
    assert "Filled 1 link" in done.output and "arm" in done.output
    assert 'ixx="0.5"' in path.read_text()  # the tip's suppressed values kept


def test_fill_all_keeps_the_values_of_a_link_whose_findings_are_suppressed(tmp_path):
    """--fix all recomputes every link, but not one whose author vouched for its values."""
    path = tmp_path / "r.urdf"
    text = _robot(tip_comment="<!-- inertia-lint: ignore[IN013, IN020, IN023] -->")
    path.write_text(text)
    done = _fill(path, "--fix", "all")
    assert done.exit_code == 1, done.output
    assert "Filled 1 link" in done.output and "tip" not in done.output
    assert 'ixx="0.5"' in path.read_text()
    assert _fill(path, "--fix", "all", "--link", "tip").exit_code == 1  # named: recomputed
    assert 'ixx="0.5"' not in path.read_text()


def test_an_adopted_repository_passes_both_hooks_in_one_go(tmp_path, monkeypatch):
    # the README's adoption: --add-noqa on the examples, then the fill hook changes nothing
    # and the lint hook passes (no IN090: every comment still suppresses its finding)
    lint_in_process(monkeypatch)
    project = tmp_path / "examples"
    shutil.copytree(EXAMPLES, project)
    runner = CliRunner()
    added = runner.invoke(lint_command, ["--add-noqa", str(project)])
    assert added.exit_code == 0, added.output
    before = {p: p.read_bytes() for p in project.rglob("*") if p.is_file()}
    filled = runner.invoke(fill_command, [str(project)])
    assert filled.exit_code == 0, filled.output
    assert {p: p.read_bytes() for p in project.rglob("*") if p.is_file()} == before
    linted = runner.invoke(lint_command, [str(project)])
    assert linted.exit_code == 0, linted.output
