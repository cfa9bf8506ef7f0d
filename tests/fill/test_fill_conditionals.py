"""
Fills and ``<xacro:if>``/``<xacro:unless>`` (issue 21, item 1), through the real commands: a
link whose ``<inertial>`` is made under a condition gets its block in the complementary
condition, never beside it; a value defined in branches is written in the branch the given
arguments expand, the other left byte for byte; an expression the arguments choose never
becomes a number; and a second run changes nothing. Each expansion is checked with the real
xacro, for every argument value.
"""

from __future__ import annotations

from pathlib import Path

import pytest
import xacro
from click.testing import CliRunner
from kit.moments import solid_box, solid_cylinder
from lxml import etree

from inertia_kit.cli.fill import fill_command
from inertia_kit.cli.lint import lint_command

# --- franka_ros-like: the fingers' <inertial> only under ${gazebo} -------------------------------

UTILS = """\
<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="inertial_props" params="mass">
    <inertial>
      <mass value="${mass}"/>
      <inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/>
    </inertial>
  </xacro:macro>
</robot>
"""

HAND = """\
<?xml version="1.0"?>
<robot name="hand" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="gazebo" default="false"/>
  <xacro:include filename="utils.xacro"/>
  <xacro:property name="gazebo" value="$(arg gazebo)"/>
  <link name="hand">
    <inertial>
      <mass value="0.73"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.0025" iyz="0" izz="0.0017"/>
    </inertial>
    <collision><geometry><box size="0.05 0.2 0.07"/></geometry></collision>
  </link>
  <joint name="finger_joint" type="prismatic">
    <parent link="hand"/><child link="finger"/>
    <axis xyz="0 1 0"/><limit lower="0" upper="0.04" effort="20" velocity="0.2"/>
  </joint>
  <link name="finger">
    <collision><geometry><box size="0.02 0.02 0.05"/></geometry></collision>
    <xacro:KIND value="${gazebo}">
      <xacro:inertial_props mass="0.015"/>
    </xacro:KIND>
  </link>
</robot>
"""


def fill(*args: str) -> tuple[int, str]:
    result = CliRunner().invoke(fill_command, list(args))
    assert result.exception is None or isinstance(result.exception, SystemExit), result.output
    return result.exit_code, result.stderr


def lint(*args: str) -> tuple[int, str]:
    result = CliRunner().invoke(lint_command, list(args))
    assert result.exception is None or isinstance(result.exception, SystemExit), result.output
    return result.exit_code, result.stdout


def inertials(path: Path, link: str, **arguments: str) -> list[etree._Element]:
    """The ``<inertial>`` elements of ``link`` as the real xacro expands ``path``."""
    document = xacro.process_file(str(path), mappings=arguments)
    tree = etree.fromstring(document.toxml().encode())
    (found,) = tree.findall(f"link[@name='{link}']")
    return found.findall("inertial")


def mass(element: etree._Element) -> float:
    return float(element.find("mass").get("value"))


@pytest.fixture
def hand(tmp_path: Path):
    def make(kind: str) -> Path:
        (tmp_path / "utils.xacro").write_text(UTILS)
        path = tmp_path / "hand.urdf.xacro"
        path.write_text(HAND.replace("KIND", kind))
        return path

    return make


@pytest.mark.parametrize(
    ("kind", "other", "given", "run"),
    [("if", "unless", "true", "false"), ("unless", "if", "false", "true")],
)
@pytest.mark.parametrize("command", ["fill", "lint"])
def test_a_conditional_inertial_gets_the_block_in_the_other_branch(
    hand, kind: str, other: str, given: str, run: str, command: str
):
    """``given``: the value the macro's <inertial> is made for; ``run``: the other, filled."""
    path = hand(kind)
    arguments = ("--xacro-arg", f"gazebo:={run}")
    if command == "fill":
        code, _ = fill(*arguments, str(path))
    else:
        code, _ = lint("--fix", "--unsafe-fixes", "--select", "IN001", *arguments, str(path))
    assert code == (1 if command == "fill" else 0)
    text = path.read_text()
    assert f'<xacro:{other} value="${{gazebo}}">\n      <inertial>' in text
    expected = solid_box((0.02, 0.02, 0.05), density=1000)[0]
    for value in ("true", "false"):
        (found,) = inertials(path, "finger", gazebo=value)  # one <inertial>, never two
        assert mass(found) == pytest.approx(0.015 if value == given else expected, rel=1e-5)
    # a second run, and one with the other argument value, change nothing
    assert fill(*arguments, str(path)) == (0, "inertia-fill: 1 file checked, nothing to change\n")
    assert fill("--xacro-arg", f"gazebo:={given}", str(path))[0] == 0
    assert path.read_text() == text


# --- husarion rosbot-like: the wheel's values defined in both branches ----------------------------

WHEEL = """\
<?xml version="1.0" encoding="utf-8"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="wheel" params="wheel_radius side mecanum y">
    <xacro:if value="${mecanum}">
      <xacro:property name="wheel_thickness" value="0.0455" />
      <xacro:property name="mass" value="0.153" />
      <xacro:property name="ixx" value="0.000111" />
      <xacro:property name="iyy" value="0.000169" />
      <xacro:property name="izz" value="0.000111" />
    </xacro:if>
    <xacro:unless value="${mecanum}">
      <xacro:property name="wheel_thickness" value="0.036" />
      <xacro:property name="mass" value="0.074" />
      <xacro:property name="ixx" value="0.000041" />
      <xacro:property name="iyy" value="0.000067" />
      <xacro:property name="izz" value="0.000041" />
    </xacro:unless>
    <joint name="${side}_wheel_joint" type="continuous">
      <parent link="body_link" />
      <child link="${side}_wheel_link" />
      <origin xyz="0 ${y} 0" />
      <axis xyz="0 1 0" />
    </joint>
    <link name="${side}_wheel_link">
      <collision>
        <geometry><cylinder radius="${wheel_radius}" length="${wheel_thickness}" /></geometry>
        <origin xyz="0 0 0" rpy="${pi/2} 0 0" />
      </collision>
      <inertial>
        <mass value="${mass}" />
        <inertia ixx="${ixx}" ixy="0.0" ixz="0.0" iyy="${iyy}" iyz="0.0" izz="${izz}" />
      </inertial>
    </link>
  </xacro:macro>
</robot>
"""

ROSBOT = """\
<?xml version="1.0"?>
<robot name="rosbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="mecanum" default="false" />
  <xacro:include filename="wheel.urdf.xacro" />
  <link name="body_link">
    <inertial>
      <mass value="1"/>
      <inertia ixx="0.00166667" ixy="0" ixz="0" iyy="0.00166667" iyz="0" izz="0.00166667"/>
    </inertial>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
  <xacro:wheel wheel_radius="0.0425" side="fl" mecanum="$(arg mecanum)" y="0.1"/>
  <xacro:wheel wheel_radius="0.0425" side="fr" mecanum="$(arg mecanum)" y="-0.1"/>
</robot>
"""


def branch(text: str, kind: str) -> str:
    start = text.index(f'<xacro:{kind} value="${{mecanum}}">')
    return text[start : text.index(f"</xacro:{kind}>", start)]


@pytest.mark.parametrize(("arguments", "active", "thickness"), [
    ((), "unless", 0.036),
    (("--xacro-arg", "mecanum:=true"), "if", 0.0455),
])  # fmt: skip
def test_a_value_defined_in_branches_is_written_in_the_one_expanded(
    tmp_path: Path, arguments: tuple[str, ...], active: str, thickness: float
):
    (tmp_path / "wheel.urdf.xacro").write_text(WHEEL)
    path = tmp_path / "rosbot.urdf.xacro"
    path.write_text(ROSBOT)
    code, stderr = fill("--fix", "all", *arguments, str(path))
    assert code == 1, stderr
    text = (tmp_path / "wheel.urdf.xacro").read_text()
    inactive = "if" if active == "unless" else "unless"
    assert branch(text, inactive) == branch(WHEEL, inactive)  # byte for byte
    assert branch(text, active) != branch(WHEEL, active)
    wheel_mass = 0.153 if active == "if" else 0.074  # declared, kept (--fix all keeps masses)
    _, side, _, axial = solid_cylinder(0.0425, thickness, mass=wheel_mass)
    (found,) = inertials(path, "fl_wheel_link", mecanum="true" if active == "if" else "false")
    moments = found.find("inertia")
    assert float(moments.get("ixx")) == pytest.approx(side, rel=1e-5)
    assert float(moments.get("iyy")) == pytest.approx(axial, rel=1e-5)  # the axle, along y
    # the fixed point: rosbot's "Filled 4 links" on every rerun, before
    assert fill("--fix", "all", *arguments, str(path)) == (
        0,
        "inertia-fill: 1 file checked, nothing to change\n",
    )


ARGUMENT = """\
<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="payload" default="2"/>
  <link name="body">
    <inertial>
      <mass value="$(arg payload)"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
</robot>
"""


def test_a_value_read_from_an_argument_never_becomes_a_number(tmp_path: Path):
    path = tmp_path / "r.urdf.xacro"
    path.write_text(ARGUMENT)
    code, stderr = fill("--fix", "all", "--mass", "body=3", str(path))
    assert code == 1
    assert 'its mass is "$(arg payload)", read from an argument' in stderr
    assert path.read_text() == ARGUMENT
    # nor through a property that reads it, or one the arguments choose
    for definition in (
        '<xacro:property name="m" value="$(arg payload)"/>',
        '<xacro:if value="$(arg heavy)"><xacro:property name="m" value="5"/></xacro:if>'
        '<xacro:unless value="$(arg heavy)"><xacro:property name="m" value="2"/></xacro:unless>',
    ):
        text = ARGUMENT.replace("$(arg payload)", "${m}").replace(
            '<link name="body">',
            f'<xacro:arg name="heavy" default="false"/>{definition}\n  <link name="body">',
        )
        path.write_text(text)
        code, stderr = fill("--fix", "all", "--mass", "body=3", str(path))
        assert code == 1 and 'its mass is "${m}", which reads properties the arguments' in stderr
        assert path.read_text() == text


def test_a_fill_whose_edit_the_robot_does_not_read_is_refused(tmp_path: Path):
    """The guard behind the cases above: a plan made again on the files as the first leaves
    them still fills the link (its edit landed where the expansion does not read), so writing
    it would repeat on every run: it and every link sharing its edit are refused instead."""
    from inertia_kit.description.edits import Edit, read_source
    from inertia_kit.fill.plan import FillPlan, LinkFill, _settled
    from inertia_kit.physics.mass import MassProperties

    path = tmp_path / "r.urdf"
    path.write_text('<robot name="r"><link name="a"/><link name="b"/><link name="c"/></robot>\n')
    shared, own = Edit(str(path), 0, 0, "<!-- a, b -->"), Edit(str(path), 1, 1, " ")
    fills = (
        LinkFill("a", MassProperties(1.0), "", False, (shared,)),
        LinkFill("b", MassProperties(1.0), "", False, (shared,)),
        LinkFill("c", MassProperties(1.0), "", False, (own,)),
    )
    plans = iter(
        [FillPlan(str(path), read_source(path), fills=fills)] * 1
        + [FillPlan(str(path), read_source(path), fills=fills[:1])]
    )
    settled = _settled(lambda: next(plans))
    assert [fill.link for fill in settled.fills] == ["c"]
    assert [refusal.link for refusal in settled.refused] == ["a", "b"]
    assert "does not read them" in settled.refused[0].reason
