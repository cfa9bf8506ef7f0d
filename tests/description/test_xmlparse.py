"""
Namespace prefixes used without a declaration, read as TinyXML2 (urdfdom), Drake and PyBullet
read them: the file loads, positions stay exact, every other XML error is still one.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest
from click.testing import CliRunner
from kit import write

from inertia_kit.cli import lint_main
from inertia_kit.description import model
from inertia_kit.description.loader import load
from inertia_kit.errors import InputError

# airo-models' UR5e and Robotiq 2F-85 write `drake:` without an `xmlns:drake`
UNDECLARED = """\
<robot name="r">
  <link name="base"/>
  <joint name="j" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit drake:acceleration="2.5" effort="150.0" lower="-1" upper="1" velocity="3.14"/>
  </joint>
  <link name="arm">
    <inertial><mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><geometry><sphere radius="0.1"/></geometry></collision>
  </link>
  <drake:collision_filter_group name="g">
    <drake:member link="arm"/><drake:ignored_collision_filter_group name="g"/>
  </drake:collision_filter_group>
</robot>
"""


def position(text: str, needle: str) -> tuple[int, int]:
    index = text.index(needle)
    return text.count("\n", 0, index) + 1, index - (text.rfind("\n", 0, index) + 1) + 1


def raises(path: Path) -> InputError:
    with pytest.raises(InputError) as caught:
        load(path)
    return caught.value


def test_undeclared_prefixes_load_as_plain_extensions(tmp_path):
    robot = load(write(tmp_path / "ur.urdf", UNDECLARED))
    assert [link.name for link in robot.links] == ["base", "arm"]
    (joint,) = robot.joints
    assert joint.limit.effort == 150.0 and joint.limit.velocity == 3.14
    assert robot.link("arm").inertial.mass == 2.0
    assert robot.invalid == ()


def test_positions_are_those_of_the_original_text(tmp_path):
    robot = load(write(tmp_path / "ur.urdf", UNDECLARED))
    (joint,) = robot.joints
    assert (joint.limit.source.line, joint.limit.source.column) == position(UNDECLARED, "<limit")
    arm = robot.link("arm")
    assert (arm.source.line, arm.source.column) == position(UNDECLARED, '<link name="arm"')
    sphere = arm.collisions[0].geometry
    assert (sphere.source.line, sphere.source.column) == position(UNDECLARED, "<sphere")


def test_one_line_file_keeps_its_columns(tmp_path):
    """Declarations go into the root's start tag: columns after it on its line must not move."""
    text = '<robot name="r"><link name="a"><drake:x/></link><link name="b" drake:y="1"/></robot>'
    robot = load(write(tmp_path / "one.urdf", text))
    assert robot.link("b").source.column == text.index('<link name="b"') + 1


def test_an_undeclared_geometry_element_is_an_unknown_shape(tmp_path):
    text = UNDECLARED.replace('<sphere radius="0.1"/>', '<drake:capsule radius="0.1" length="1"/>')
    geometry = load(write(tmp_path / "cap.urdf", text)).link("arm").collisions[0].geometry
    assert isinstance(geometry, model.Unknown) and geometry.tag == "drake:capsule"


@pytest.mark.parametrize(
    ("text", "needle", "message"),
    [
        # the error on the root's own line: its column is in the original text
        ('<robot name="r"><drake:x/><link name=a/></robot>\n', "a/></robot>", "AttValue"),
        ('<robot name="r">\n  <drake:x/>\n  <link name="a">\n</robot>\n', "</robot>", "mismatch"),
        # libxml2 reports nothing after the root once a prefix is undeclared: still refused
        (
            '<robot name="r">\n  <drake:x/>\n</robot>\n<robot name="s"/>\n',
            '<robot name="s',
            "Extra",
        ),
        ('<robot name="r"><drake:x/></robot>junk', "junk", "Extra"),
    ],
    ids=["root-line", "later-line", "two-roots", "trailing-junk"],
)
def test_every_other_error_is_still_one(tmp_path, text, needle, message):
    path = write(tmp_path / "bad.urdf", text)
    error = raises(path)
    assert error.message.startswith("not well-formed XML") and message in error.message
    assert error.line == position(text, needle)[0]
    if needle == "a/></robot>":
        assert error.column == position(text, needle)[1]


def test_entities_are_still_refused(tmp_path):
    text = '<!DOCTYPE r [<!ENTITY x "y">]>\n<robot name="&x;"><drake:x/></robot>\n'
    assert "entity" in raises(write(tmp_path / "e.urdf", text)).message


def test_xacro_refuses_undeclared_prefixes_as_xacro_does(tmp_path):
    """xacro parses with namespaces (minidom): "XML parsing error: unbound prefix", exit 2."""
    text = UNDECLARED.replace(
        '<robot name="r">',
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:property name="m" value="2"/>',
    ).replace('<mass value="2"/>', '<mass value="${m}"/>')
    error = raises(write(tmp_path / "ur.urdf.xacro", text))
    assert "unbound prefix" in error.message and "xmlns:" in error.message
    assert (error.line, error.column) == position(text, "<limit drake:acceleration")


def test_xacro_with_declared_prefixes_expands(tmp_path):
    text = UNDECLARED.replace(
        '<robot name="r">',
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro" '
        'xmlns:drake="http://drake.mit.edu"><xacro:property name="m" value="2"/>',
    ).replace('<mass value="2"/>', '<mass value="${m}"/>')
    robot = load(write(tmp_path / "ur.urdf.xacro", text))
    assert robot.link("arm").inertial.mass == 2.0
    assert robot.joints[0].limit.effort == 150.0


def test_inertia_lint_reads_the_file(tmp_path):
    path = write(tmp_path / "ur.urdf", UNDECLARED)
    result = CliRunner().invoke(lint_main, [str(path), "--output-format", "concise"])
    assert result.exit_code in (0, 1), result.output
    assert "Namespace prefix" not in result.output and "could not be read" not in result.output


AIRO = importlib.util.find_spec("airo_models")


@pytest.mark.skipif(AIRO is None, reason="airo-models is not installed")
def test_every_airo_models_file_loads():
    root = Path(next(iter(AIRO.submodule_search_locations)))
    files = sorted(p for p in root.rglob("*") if p.suffix in (".urdf", ".xacro"))
    assert len(files) >= 16
    for path in files:
        robot = load(path)
        assert robot.links, path
    # the three that declare no `xmlns:drake` are among them
    assert {p.name for p in files} >= {"ur3e.urdf", "ur5e.urdf", "robotiq_2f_85.urdf"}
