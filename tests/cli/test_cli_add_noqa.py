"""
`inertia-lint --add-noqa`: a suppression comment for every current finding, so that only new
findings fail; where it goes (before the element, before the macro call of the instance, before
<robot> for a finding without a line), merged into a comment already there, the file's
indentation and newline kept, nothing else changed, a second run adds nothing.
"""

from __future__ import annotations

import difflib
import re
import shutil
import types
from pathlib import Path

import pytest
from click.testing import CliRunner
from kit import EXAMPLES
from kit.in_process import lint_in_process

from inertia_kit.cli import lint_main
from inertia_kit.cli.add_noqa import writable_under
from inertia_kit.lint import catalog
from inertia_kit.lint.findings import Severity

COMMENT = re.compile(r"[ \t]*<!-- inertia-lint: ignore\[(IN\d{3}(, IN\d{3})*)\] -->\r?\n?")

MACRO_ROBOT = """\
<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="part" params="name mass">
    <link name="${name}">
      <inertial>
        <mass value="${mass}"/>
        <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/>
      </inertial>
    </link>
    <joint name="j_${name}" type="revolute">
      <parent link="world"/><child link="${name}"/>
      <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/>
    </joint>
  </xacro:macro>
  <link name="world"/>
  <xacro:part name="a" mass="-1"/>
  <xacro:part name="b" mass="1"/>
</robot>
"""


def lint(*args: str):
    return CliRunner().invoke(lint_main, [*map(str, args)])


def snapshot(folder: Path) -> dict[str, bytes]:
    files = sorted(p for p in folder.rglob("*") if p.suffix in (".urdf", ".xacro"))
    return {str(p.relative_to(folder)): p.read_bytes() for p in files}


def only_comments_inserted(before: bytes, after: bytes) -> bool:
    """Whether ``after`` is ``before`` with whole comment lines inserted, and nothing else."""
    old = before.decode().splitlines(keepends=True)
    new = after.decode().splitlines(keepends=True)
    for op, _, _, j1, j2 in difflib.SequenceMatcher(None, old, new).get_opcodes():
        if op == "equal":
            continue
        if op != "insert" or not all(COMMENT.fullmatch(line) for line in new[j1:j2]):
            return False
    return True


@pytest.fixture
def examples(tmp_path: Path) -> Path:
    copy = tmp_path / "examples"
    shutil.copytree(EXAMPLES, copy, ignore=shutil.ignore_patterns("*.stl", "*.dae", "*.obj"))
    return copy


def test_the_seed_examples_adopt_then_lint_clean(examples):
    assert lint(examples).exit_code == 1  # the seed robots have findings
    before = snapshot(examples)
    result = lint("--add-noqa", examples)
    assert result.exit_code == 0, result.output
    after = snapshot(examples)
    changed = [name for name in before if before[name] != after[name]]
    assert changed, "nothing was written"
    for name in changed:
        assert only_comments_inserted(before[name], after[name]), name
    # how many, where
    written = sum(after[n].decode().count("inertia-lint: ignore[") for n in changed) - sum(
        before[n].decode().count("inertia-lint: ignore[") for n in changed
    )
    assert f"Added {written} suppression comments in {len(changed)} files." in result.output
    assert lint(examples).exit_code == 0
    again = lint("--add-noqa", examples)
    assert again.exit_code == 0 and "Added 0 suppression comments." in again.output
    assert snapshot(examples) == after


def test_a_wheel_macro_broken_in_the_wheeled_robot(examples):
    robot = examples / "my_robot_description" / "urdf"
    wheels = robot / "wheels.xacro"
    text = wheels.read_text()
    broken = text.replace('name="wheel_mass" value="0.3"', 'name="wheel_mass" value="-5"')
    assert broken != text
    wheels.write_text(broken)
    findings = lint("--output-format", "concise", "--select", "IN002", robot)
    assert findings.exit_code == 1 and findings.output.count("IN002") == 2
    result = lint("--add-noqa", robot)
    assert result.exit_code == 0, result.output
    # each wheel is a call of the macro: each call gets its own comment, the macro body none
    calls = (robot / "robot.xacro").read_text()
    written = re.findall(r"<!-- inertia-lint: ignore\[([^\]]*)\] -->\n  <xacro:wheel ", calls)
    assert len(written) == 2 and all("IN002" in codes for codes in written)  # and IN010
    assert wheels.read_text() == broken
    assert lint(robot).exit_code == 0


def test_the_comment_before_a_macro_call_suppresses_that_instance_only(tmp_path):
    path = tmp_path / "r.urdf.xacro"
    path.write_text(MACRO_ROBOT)
    assert lint("--add-noqa", path).exit_code == 0
    text = path.read_text()
    assert text == MACRO_ROBOT.replace(
        '  <xacro:part name="a"', '  <!-- inertia-lint: ignore[IN002] -->\n  <xacro:part name="a"'
    )
    path.write_text(text.replace('name="b" mass="1"', 'name="b" mass="-1"'))
    result = lint("--output-format", "concise", path)
    assert result.exit_code == 1
    assert f"{path}:18:3: IN002 link `b`" in result.output  # the new finding fails
    assert "link `a`" not in result.output


def test_codes_are_added_to_a_comment_already_there(tmp_path):
    path = tmp_path / "r.urdf.xacro"
    kept = "<!-- inertia-lint: ignore[IN041] reason: a floating base -->"
    path.write_text(
        MACRO_ROBOT.replace('  <xacro:part name="a"', f'  {kept}\n  <xacro:part name="a"')
    )
    # 1: the IN041 there suppresses nothing (IN090), which --add-noqa leaves to its fix
    result = lint("--add-noqa", path)
    assert result.exit_code == 1
    assert "Added 1 suppression comment (1 already there, given codes) in 1 file." in result.output
    text = path.read_text()
    assert "<!-- inertia-lint: ignore[IN041, IN002] reason: a floating base -->" in text
    assert text.count("inertia-lint") == 1
    # IN041 suppresses nothing there: the run after adoption says so (and nothing else fails)
    result = lint("--output-format", "concise", path)
    assert ": IN090 [*] `ignore[IN041, IN002]`: `IN041` in it suppresses nothing" in result.output
    assert ": IN002 " not in result.output


def test_indentation_and_line_endings_are_the_files(tmp_path):
    path = tmp_path / "r.urdf.xacro"
    text = MACRO_ROBOT.replace("\n  ", "\n\t").replace("\n", "\r\n")
    path.write_bytes(text.encode())
    assert lint("--add-noqa", path).exit_code == 0
    expected = text.replace(
        '\t<xacro:part name="a"', '\t<!-- inertia-lint: ignore[IN002] -->\r\n\t<xacro:part name="a"'
    )
    assert path.read_bytes() == expected.encode()
    assert lint(path).exit_code == 0


def test_an_element_not_first_on_its_line_gets_the_comment_inline(tmp_path):
    path = tmp_path / "r.urdf"
    body = '<inertial><mass value="-1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>'
    text = (
        '<robot name="r"><link name="world"/>\n'
        '  <joint name="j" type="revolute"><parent link="world"/><child link="a"/>'
        '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        f'<link name="a">{body}</inertial></link>\n</robot>\n'
    )
    path.write_text(text)
    assert lint("--add-noqa", "--select", "IN002", path).exit_code == 0
    # the line holds the joint and the link: the finding's column says it is the <mass>
    comment = "<!-- inertia-lint: ignore[IN002] -->"
    assert path.read_text() == text.replace("<inertial><mass", f"<inertial>{comment}<mass")
    assert lint("--select", "IN002", path).exit_code == 0


def test_select_and_ignore_are_honoured(examples):
    arm = examples / "simple_arm"
    assert lint("--add-noqa", "--select", "IN041", arm).exit_code == 0
    text = (arm / "urdf" / "simple_arm.urdf.xacro").read_text()
    assert re.findall(r"ignore\[([^\]]*)\]", text) == ["IN041"]
    assert lint("--select", "IN041", arm).exit_code == 0
    assert lint(arm).exit_code == 1  # what was not selected still fails
    assert lint("--add-noqa", "--ignore", "IN062", arm).exit_code == 0
    assert lint("--ignore", "IN062", arm).exit_code == 0
    assert "IN062" not in (arm / "urdf" / "simple_arm.urdf.xacro").read_text()


def _robot_rule(monkeypatch):
    """A stub robot rule whose finding has no line, next to the real rules."""
    rule = types.ModuleType("inertia_kit.lint.rules.in089_stub_robot")
    rule.CODE, rule.NAME, rule.SEVERITY, rule.SCOPE = (
        "IN089",
        "stub-robot",
        Severity.WARNING,
        "robot",
    )
    rule.SUMMARY = "a stub"
    rule.check = lambda robot, ctx: iter([ctx.finding("about the robot", None)])
    monkeypatch.setattr(catalog, "RULES", (*catalog.RULES, rule))
    lint_in_process(monkeypatch)


def test_a_finding_without_a_line_is_suppressed_before_the_robot(tmp_path, monkeypatch):
    _robot_rule(monkeypatch)
    path = tmp_path / "r.urdf.xacro"
    path.write_text(MACRO_ROBOT)
    assert lint("--select", "IN089", path).exit_code == 1
    assert lint("--add-noqa", "--select", "IN089", path).exit_code == 0
    assert path.read_text() == MACRO_ROBOT.replace(
        "<robot ", "<!-- inertia-lint: ignore[IN089] -->\n<robot "
    )
    assert lint("--select", "IN089", path).exit_code == 0


def test_a_finding_in_a_file_outside_the_paths_given_is_listed(tmp_path, monkeypatch):
    shared = tmp_path / "shared" / "parts.xacro"
    shared.parent.mkdir()
    shared.write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <link name="a"><inertial><mass value="-1"/>'
        '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>\n'
        "</robot>\n"
    )
    robot = tmp_path / "robot" / "r.urdf.xacro"
    robot.parent.mkdir()
    robot.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        f'  <xacro:include filename="{shared}"/>\n'
        "</robot>\n"
    )
    monkeypatch.chdir(robot.parent)
    before = shared.read_bytes()
    result = lint("--add-noqa", "--select", "IN002", robot)
    assert result.exit_code == 1
    assert f"note: {shared}:2: IN002 not suppressed: {shared} is outside the paths given" in (
        result.output
    )
    assert shared.read_bytes() == before
    assert lint("--add-noqa", "--select", "IN002", tmp_path).exit_code == 0
    assert "<inertial><!-- inertia-lint: ignore[IN002] --><mass" in shared.read_text()


def test_writable_files_are_under_the_paths_given(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "urdf").mkdir()
    writable = writable_under([str(tmp_path / "urdf")])
    assert writable(str(tmp_path / "urdf" / "a.xacro"))
    assert writable(str(tmp_path / "other" / "a.xacro"))  # the current folder holds urdf/
    assert not writable(str(tmp_path / ".venv" / "lib" / "a.xacro"))
    assert not writable(str(tmp_path / "lib" / "site-packages" / "pkg" / "a.xacro"))
    assert not writable(str(tmp_path.parent / "elsewhere.xacro"))


def test_an_unused_suppression_is_not_suppressed_but_listed(tmp_path):
    path = tmp_path / "r.urdf.xacro"
    path.write_text(
        MACRO_ROBOT.replace(
            '  <xacro:part name="b"',
            '  <!-- inertia-lint: ignore[IN002] -->\n  <xacro:part name="b"',
        )
    )
    result = lint("--add-noqa", path)
    assert result.exit_code == 1
    assert (
        "IN090 not suppressed: an unused suppression: remove it (its fix is safe)" in result.output
    )
    assert "IN090 unused-suppression" in result.output  # still failing, listed


NESTED = """\
<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="body" params="name mass">
    <link name="${name}">
      <inertial>
        <mass value="${mass}"/>
        <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/>
      </inertial>
    </link>
  </xacro:macro>
  <xacro:macro name="part" params="name mass">
    <xacro:body name="${name}" mass="${mass}"/>
    <joint name="j_${name}" type="revolute">
      <parent link="world"/><child link="${name}"/>
      <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/>
    </joint>
  </xacro:macro>
  <link name="world"/>
  <xacro:part name="a" mass="-1"/>
  <xacro:part name="b" mass="1"/>
</robot>
"""


def test_a_finding_reported_in_a_macro_body_is_suppressed_there(tmp_path):
    # nested macros: the finding is reported at the innermost call, which stands in the body of
    # `part`; the comment goes there, so it covers that call in every instance of `part`
    path = tmp_path / "r.urdf.xacro"
    path.write_text(NESTED)
    assert lint("--add-noqa", path).exit_code == 0
    call = '    <xacro:body name="${name}"'
    assert path.read_text() == NESTED.replace(
        call, f"    <!-- inertia-lint: ignore[IN002] -->\n{call}"
    )
    path.write_text(path.read_text().replace('name="b" mass="1"', 'name="b" mass="-1"'))
    assert lint(path).exit_code == 0  # the comment in the body covers the new instance too


def test_the_configuration_is_honoured(examples):
    arm = examples / "simple_arm"
    (arm / "pyproject.toml").write_text('[tool.inertia-kit]\nignore = ["IN062"]\n')
    assert lint("--add-noqa", arm).exit_code == 0
    text = (arm / "urdf" / "simple_arm.urdf.xacro").read_text()
    # IN062 ignored: what it explained (IN020, IN023) is reported, and suppressed, instead
    assert re.findall(r"ignore\[([^\]]*)\]", text) == ["IN041"] + ["IN020, IN021, IN023"] * 2
    assert lint(arm).exit_code == 0


def test_an_unreadable_file_is_reported_and_the_others_adopt(tmp_path):
    (tmp_path / "r.urdf.xacro").write_text(MACRO_ROBOT)
    (tmp_path / "broken.urdf").write_text('<robot name="b"><link name="a">\n')
    result = lint("--add-noqa", tmp_path)
    assert result.exit_code == 2
    assert f"error: {tmp_path / 'broken.urdf'}:2" in result.output
    assert "Added 1 suppression comment in 1 file." in result.output
    assert "ignore[IN002]" in (tmp_path / "r.urdf.xacro").read_text()


def test_quiet_writes_the_comments_and_says_nothing(examples):
    before = snapshot(examples)
    result = lint("--add-noqa", "-q", examples)
    assert result.exit_code == 0, result.output
    assert snapshot(examples) != before  # written all the same
    assert result.output == ""  # no "Added ...", no per-file list, no notes
    assert lint(examples).exit_code == 0


def test_output_file_has_no_report_to_write(examples, tmp_path):
    before = snapshot(examples)
    result = lint("--add-noqa", "-o", tmp_path / "report.txt", examples)
    assert result.exit_code == 2
    assert "--output-file" in result.output and "--add-noqa" in result.output
    assert snapshot(examples) == before and not (tmp_path / "report.txt").exists()
