"""
IN090 unused-suppression, through `inertia-lint`: a comment, or a code in it, that suppressed
nothing is reported at the comment with a safe fix (the comment with its line, or the code);
only codes of rules that ran are judged; a comment in a fragment is judged over every robot of
the run that includes it; superseded findings and `disable-file` count.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

from click.testing import CliRunner
from kit import EXAMPLES

from inertia_kit.cli import lint_main
from inertia_kit.description.edits import apply_edits

BOX = (
    '<inertial><mass value="10"/>'
    '<inertia ixx="0.0833333" ixy="0" ixz="0" iyy="0.1416667" iyz="0" izz="0.2083333"/>'
    "</inertial>"
    '<collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>'
)
# a box link that no rule flags, alone in its robot (no joint: IN041 does not apply either)
CLEAN = f'<robot name="r">\n  {{comment}}\n  <link name="base_link">{BOX}</link>\n</robot>\n'
COMMENT = "<!-- inertia-lint: ignore[{}] -->"


def lint(*args) -> tuple[int, list[dict]]:
    result = CliRunner().invoke(lint_main, ["--output-format", "json", *map(str, args)])
    assert result.exit_code in (0, 1), result.output
    return result.exit_code, json.loads(result.stdout)


def unused(findings: list[dict]) -> list[dict]:
    return [f for f in findings if f["code"] == "IN090"]


def fixed(path: Path, finding: dict) -> str:
    """The file's text with the finding's fix applied, as `inertia-lint --fix` applies it."""
    fix = finding["fix"]
    assert fix["safety"] == "safe"
    edits = [_edit(e) for e in fix["edits"]]
    assert {e.path for e in edits} == {str(path)}
    text, applied = apply_edits(path.read_text(), edits)
    assert len(applied) == len(edits)
    return text


def _edit(data: dict):
    from inertia_kit.description.edits import Edit

    return Edit(data["path"], data["start"], data["end"], data["content"])


def test_a_comment_that_suppresses_nothing_is_reported_where_it_stands(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_text(CLEAN.format(comment=COMMENT.format("IN012")))
    code, findings = lint(path)
    assert code == 1
    (finding,) = findings
    assert finding["code"] == "IN090" and finding["severity"] == "warning"
    assert (finding["file"], finding["line"], finding["column"]) == (str(path), 2, 3)
    assert finding["message"] == "`ignore[IN012]`: the comment suppresses nothing"
    assert len(finding["message"]) <= 100
    assert finding["detail"] == "no finding of `IN012` on the element it covers (line 3)"
    # the fix takes the comment with its line, and the robot lints clean
    assert fixed(path, finding) == CLEAN.replace("  {comment}\n", "")
    path.write_text(fixed(path, finding))
    assert lint(path) == (0, [])


def test_only_the_unused_code_is_removed_when_another_is_used(tmp_path):
    path = tmp_path / "r.urdf"
    # IN025: the link has mass and a visual but no collision
    text = (
        '<robot name="r">\n'
        "  <!-- inertia-lint: ignore[IN012, missing-collision] the visual is a placeholder -->\n"
        '  <link name="base_link"><inertial><mass value="10"/>'
        '<inertia ixx="0.0833333" ixy="0" ixz="0" iyy="0.1416667" iyz="0" izz="0.2083333"/>'
        '</inertial><visual><geometry><box size="0.4 0.3 0.1"/></geometry></visual></link>\n'
        "</robot>\n"
    )
    path.write_text(text)
    _, findings = lint(path)
    (finding,) = unused(findings)
    assert "`IN012` in it suppresses nothing" in finding["message"]
    assert fixed(path, finding) == text.replace("[IN012, missing-collision]", "[missing-collision]")
    path.write_text(fixed(path, finding))
    assert lint(path) == (0, [])


def test_an_inline_comment_is_removed_alone(tmp_path):
    path = tmp_path / "r.urdf"
    comment = COMMENT.format("IN012")
    text = f'<robot name="r">\n  <link name="base_link">{comment}{BOX}</link>\n</robot>\n'
    path.write_text(text)
    (finding,) = unused(lint(path)[1])
    assert fixed(path, finding) == text.replace(comment, "")


def test_crlf_the_comment_goes_with_its_line_ending(tmp_path):
    path = tmp_path / "r.urdf"
    text = CLEAN.format(comment=COMMENT.format("IN012")).replace("\n", "\r\n")
    path.write_bytes(text.encode())
    (finding,) = unused(lint(path)[1])
    fix = finding["fix"]["edits"]
    new, _ = apply_edits(path.read_bytes().decode(), [_edit(e) for e in fix])
    assert new == CLEAN.replace("  {comment}\n", "").replace("\n", "\r\n")


def test_codes_of_rules_that_did_not_run_are_not_judged(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_text(CLEAN.format(comment=COMMENT.format("IN012, IN070")))
    # IN070 is MuJoCo's engine rule: not run without --engine mujoco, so not judged
    (finding,) = unused(lint(path)[1])
    assert "`IN012` in it suppresses nothing" in finding["message"]
    assert "IN070`" not in finding["message"].split("suppresses nothing")[1]
    assert "IN070`" not in finding["detail"]
    # IN012 not selected: nothing to judge
    assert lint("--select", "IN02", path) == (0, [])
    # an engine rule's code is judged when its engine is chosen
    path.write_text(CLEAN.format(comment=COMMENT.format("IN071")))
    assert lint(path) == (0, [])
    (finding,) = unused(lint("--engine", "gazebo", path)[1])
    assert "`IN071`" in finding["detail"]
    # a prefix is judged only when every rule it picks ran: IN070, IN072.. did not
    path.write_text(CLEAN.format(comment=COMMENT.format("IN07")))
    assert lint("--engine", "gazebo", path) == (0, [])
    # not selected, it reports nothing
    path.write_text(CLEAN.format(comment=COMMENT.format("IN012")))
    assert lint("--ignore", "IN090", path) == (0, [])


def test_a_comment_covering_a_superseded_finding_is_used(tmp_path):
    # the seed mrm arm: IN060 (inertia about the joint) replaces IN020 and IN023 on link_02
    arm = tmp_path / "mrm_description"
    shutil.copytree(EXAMPLES / "mrm_description", arm)
    path = arm / "urdf" / "mrm.xacro"
    text = path.read_text()
    call = '  <xacro:m_link_cylinder name="${link_02_name}"'
    path.write_text(text.replace(call, f"  {COMMENT.format('IN020, IN023')}\n{call}"))
    assert unused(lint(path)[1]) == []
    # without IN060 the comment is what keeps IN020 and IN023 of link_02 quiet
    _, findings = lint("--ignore", "IN060", path)
    assert not [f for f in findings if f["link"] == "link_02"]


FRAGMENT = """\
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="part" params="name mass">
    <link name="${name}">
      <!-- inertia-lint: ignore[IN002] -->
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
</robot>
"""


def robot(mass: float) -> str:
    return (
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="parts.xacro"/>\n  <link name="world"/>\n'
        f'  <xacro:part name="a" mass="{mass}"/>\n</robot>\n'
    )


def test_a_comment_in_a_fragment_is_judged_over_every_robot_that_includes_it(tmp_path):
    (tmp_path / "parts.xacro").write_text(FRAGMENT)
    (tmp_path / "bad.urdf.xacro").write_text(robot(-1))  # needs the comment
    (tmp_path / "good.urdf.xacro").write_text(robot(1))  # does not
    assert lint(tmp_path) == (0, [])  # one robot needs it: used
    assert lint(tmp_path / "bad.urdf.xacro") == (0, [])
    _, findings = lint(tmp_path / "good.urdf.xacro")
    (finding,) = unused(findings)
    assert (finding["file"], finding["line"]) == (str(tmp_path / "parts.xacro"), 4)
    # neither needs it: reported once, over the two robots
    (tmp_path / "bad.urdf.xacro").write_text(robot(2))
    _, findings = lint(tmp_path)
    (finding,) = unused(findings)
    assert "in any of the 2 linted robots that include it" in finding["detail"]
    # the fragment given alone is linted through the robots that include it: judged over both
    _, findings = lint(tmp_path / "parts.xacro")
    (finding,) = unused(findings)
    assert (finding["file"], finding["line"]) == (str(tmp_path / "parts.xacro"), 4)
    # a fragment no robot includes is no robot: its comments are not judged
    (tmp_path / "bad.urdf.xacro").unlink()
    (tmp_path / "good.urdf.xacro").unlink()
    assert lint(tmp_path / "parts.xacro") == (0, [])


def test_robots_with_comments_of_their_own_are_each_judged_once(tmp_path):
    # each robot's findings are told as it is linted (a streamed report); judging the comments
    # shared by several robots at the end must not judge, and tell, these again
    for name in ("a", "b"):
        (tmp_path / f"{name}.urdf").write_text(CLEAN.format(comment=COMMENT.format("IN012")))
    for output_format in ("json", "concise"):
        result = CliRunner().invoke(lint_main, ["--output-format", output_format, str(tmp_path)])
        assert result.exit_code == 1, result.output
        assert result.stdout.count("IN090") == 2
    _, findings = lint(tmp_path)
    for finding in unused(findings):
        assert fixed(Path(finding["file"]), finding) == CLEAN.replace("  {comment}\n", "")


def test_a_disabled_file_is_not_judged(tmp_path):
    path = tmp_path / "r.urdf"
    text = CLEAN.format(comment=COMMENT.format("IN012"))
    path.write_text("<!-- inertia-lint: disable-file -->\n" + text)
    assert lint(path) == (0, [])


def test_a_comment_whose_finding_a_per_file_ignore_also_drops_is_used(tmp_path):
    (tmp_path / "parts.xacro").write_text(FRAGMENT)
    (tmp_path / "bad.urdf.xacro").write_text(robot(-1))
    (tmp_path / "pyproject.toml").write_text(
        '[tool.inertia-kit]\nper-file-ignores = { "*.xacro" = ["IN002"] }\n'
    )
    assert lint(tmp_path / "bad.urdf.xacro") == (0, [])


def test_no_removal_is_offered_on_a_text_the_lint_did_not_read(tmp_path):
    """The comment's line is the one the lint read: a file saved since (or read differently by
    two robots) gets the finding, without a fix computed on the other text."""
    from inertia_kit.description.reads import digest
    from inertia_kit.lint.comment_use import CommentUse
    from inertia_kit.lint.rules import RuleContext, in090_unused_suppression

    path = tmp_path / "robot.urdf"
    path.write_text(CLEAN.format(comment=COMMENT.format("IN012")))

    def fixes(read):
        use = CommentUse(str(path), 2, ("IN012",), (3, 3), {"IN012"}, digest=read)
        ctx = RuleContext(in090_unused_suppression, {}, None)
        return [f.fix for f in in090_unused_suppression.check([use], ctx)]

    [fix] = fixes(digest(path.read_bytes()))
    assert fix is not None
    assert fixes(digest(b"<robot/>")) == [None]
    assert fixes(None) == [None]
