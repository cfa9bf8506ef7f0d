"""
Fixes as a xacro author writes them (issue 12, item 4), through ``inertia-fill`` on the seed
robots: a value that does not change keeps its text, a value that changes is written where it
is written (a number, an argument, the macro's own property, as the formula of the link's
shape), the seed arm's slip is undone by giving the ``<inertial>`` the collision's ``<origin>``
through new optional macro parameters, and a link whose expression had to become a number is
reported. Every byte outside the edited spans stays; a second run changes nothing; the result
lints clean.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from kit import EXAMPLES
from kit import write as write_file
from kit.moments import solid_cylinder
from kit.urdf import joint

from inertia_kit.analysis.declared import declared
from inertia_kit.cli.fill import fill_command
from inertia_kit.cli.lint import lint_command
from inertia_kit.description.loader import load

XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def copy_example(name: str, tmp_path: Path) -> Path:
    shutil.copytree(EXAMPLES / name, tmp_path / name)
    return tmp_path / name


def snapshot(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in folder.rglob("*") if p.is_file()}


def fill(*args: str):
    return CliRunner().invoke(fill_command, list(args))


def assert_settled(path: Path, *args: str, besides: tuple[str, ...] = ()):
    """A second run changes nothing, --check passes, and the expanded robot lints clean
    (``besides``: findings about what a fill does not touch, e.g. IN041 on the seed arm's
    root link, which has its <inertial> before and after)."""
    folder = path.parent
    before = snapshot(folder)
    again = fill(*args, str(path))
    assert again.exit_code == 0, again.stderr
    assert snapshot(folder) == before
    assert fill(*args, "--check", str(path)).exit_code == 0
    select = ["--ignore", ",".join(besides)] if besides else []
    linted = CliRunner().invoke(lint_command, [*select, str(path)])
    assert linted.exit_code == 0, linted.output


# --- the seed simple arm --------------------------------------------------------------------

ARM_MACRO = '<xacro:macro name="cylinder_inertia" params="mass radius length">\n    <inertial>\n'
ARM_MACRO_FIXED = (
    '<xacro:macro name="cylinder_inertia" params="mass radius length '
    "origin_xyz:='0 0 0' origin_rpy:='0 0 0'\">\n"
    "    <inertial>\n"
    '      <origin xyz="${origin_xyz}" rpy="${origin_rpy}"/>\n'
)
ARM_CALL = (
    '<xacro:cylinder_inertia mass="${link_mass}" radius="${link_radius}" length="${link_length}"/>'
)
ARM_CALL_FIXED = ARM_CALL.replace(
    "/>", ' origin_xyz="${link_length/2} 0 0" origin_rpy="0 ${pi/2} 0"/>'
)


@pytest.mark.parametrize("mode", ["all", "invalid"])
def test_seed_simple_arm_gets_the_collision_origin_and_keeps_its_formula(mode, tmp_path):
    """The cylinder formula is right in the rod's own axes: the <inertial> takes the
    collision's <origin> as the collision writes it, through optional parameters of the
    macro (the base's call, needing none, stays); the properties stay used."""
    folder = copy_example("simple_arm", tmp_path)
    path = folder / "urdf" / "simple_arm.urdf.xacro"
    original = path.read_text()
    result = fill("--fix", mode, str(path))
    assert result.exit_code == 1, result.stderr
    assert "Filled 2 links" in result.stderr and "no longer parametric" not in result.stderr
    expected = original.replace(ARM_MACRO, ARM_MACRO_FIXED).replace(ARM_CALL, ARM_CALL_FIXED)
    assert original.count(ARM_CALL) == 2
    assert path.read_text() == expected  # every other byte as it was
    for name in ("${link_mass}", "${link_radius}", "${link_length}"):
        assert name in expected.split("<!-- Link 1 -->")[1]
    # in link axes: the rod along x about its centre
    m, r, length = 1.0, 0.02, 0.3
    robot = load(path)
    for link in robot.links[1:]:
        properties = declared(link)
        assert properties.com == pytest.approx((length / 2, 0, 0))
        side = m * (3 * r * r + length**2) / 12
        assert np.diag(properties.inertia) == pytest.approx((m * r * r / 2, side, side))
    assert_settled(path, "--fix", mode, besides=("IN041",))


def test_seed_simple_arm_stays_parametric(tmp_path):
    """After the fix, a longer link moves its centre of mass and inertia with it."""
    folder = copy_example("simple_arm", tmp_path)
    path = folder / "urdf" / "simple_arm.urdf.xacro"
    assert fill("--fix", "all", str(path)).exit_code == 1
    path.write_text(
        path.read_text().replace(
            '<xacro:property name="link_length" value="0.3"/>',
            '<xacro:property name="link_length" value="0.5"/>',
        )
    )
    link = load(path).links[1]
    properties = declared(link)
    assert properties.com == pytest.approx((0.25, 0, 0))
    assert properties.inertia[1, 1] == pytest.approx(1.0 * (3 * 0.02**2 + 0.5**2) / 12)
    assert_settled(path, "--fix", "all", besides=("IN041",))


# --- the seed wheeled robot -----------------------------------------------------------------

WHEEL_PROPERTY = (
    '<xacro:property name="inertia_{axis}" '
    'value="${{0.5 * wheel_mass * wheel_radius * wheel_radius}}" />'
)
WHEEL_FORMULA = (
    '<xacro:property name="inertia_{axis}" '
    'value="${{wheel_mass * (3 * wheel_radius**2 + wheel_width**2) / 12}}" />'
)


def test_seed_wheeled_robot_keeps_its_property_expressions(tmp_path):
    """The wheel (a cylinder r = 0.05 m, h = 0.02 m turned onto y, 0.3 kg declared) had the
    disc's axial moment on every axis: ixx and izz become the cylinder's side moment, written
    as its formula in the properties they were written in; `${wheel_mass}` and
    `${inertia_ixx}`..`${inertia_izz}` stay; iyy was right and keeps its text."""
    folder = copy_example("my_robot_description", tmp_path)
    before = snapshot(folder)
    path = folder / "urdf" / "robot.xacro"
    result = fill("--fix", "all", str(path))
    assert result.exit_code == 1, result.stderr
    assert "no longer parametric" not in result.stderr
    after = snapshot(folder)
    changed = {name for name in after if after[name] != before[name]}
    # the lidar, a visual-only part welded to the base, is a helper link: not given mass
    assert changed == {"urdf/base.xacro", "urdf/wheels.xacro"}
    wheels = before["urdf/wheels.xacro"].decode()
    expected = wheels
    for axis in ("ixx", "izz"):
        expected = expected.replace(
            WHEEL_PROPERTY.format(axis=axis), WHEEL_FORMULA.format(axis=axis)
        )
    assert after["urdf/wheels.xacro"].decode() == expected
    assert '<mass value="${wheel_mass}" />' in expected
    assert 'ixx="${inertia_ixx}"' in expected and 'izz="${inertia_izz}"' in expected
    _, side, _, axial = solid_cylinder(0.05, 0.02, mass=0.3)
    for link in load(path).links:
        if link.name.endswith("wheel_link"):
            assert (link.inertial.ixx, link.inertial.iyy, link.inertial.izz) == pytest.approx(
                (side, axial, side)
            )
    assert_settled(path, "--fix", "all")


# --- what cannot stay parametric is said --------------------------------------------------------

SHAPED = f"""<robot name="r" {XACRO_NS}>
  <xacro:property name="size" value="0.1 0.2 0.4"/>
  <link name="world"/>
  {joint("world", "arm")}
  <link name="arm">
    <collision><geometry><box size="${{size}}"/></geometry></collision>
    <inertial>
      <mass value="2"/>
      <inertia ixx="${{2 * 0.01}}" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/>
    </inertial>
  </link>
</robot>
"""


def test_an_expression_that_cannot_stay_is_a_number_and_the_link_is_named(tmp_path):
    """The box's size is one property (`${size}`), not three terms: no formula can be
    written, so ixx becomes a number and the fill says the link is no longer parametric."""
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(SHAPED)
    result = fill("--fix", "all", str(path))
    assert result.exit_code == 1, result.stderr
    assert "link `arm` is no longer parametric: its ixx is written as" in result.stderr
    assert 'where "${2 * 0.01}" was' in result.stderr
    text = path.read_text()
    assert "${2 * 0.01}" not in text and '<box size="${size}"/>' in text
    assert '<mass value="2"/>' in text  # kept: the mass did not change
    assert_settled(path, "--fix", "all")


# --- where each value is written ----------------------------------------------------------------

NESTED = f"""<robot name="r" {XACRO_NS}>
  <xacro:macro name="inertia_of" params="m ixx iyy izz">
    <inertial>
      <mass value="${{m}}"/>
      <inertia ixx="${{ixx}}" ixy="0" ixz="0" iyy="${{iyy}}" iyz="0" izz="${{izz}}"/>
    </inertial>
  </xacro:macro>
  <xacro:macro name="rod" params="name length mass ixx iyy izz">
    <link name="${{name}}">
      <collision><geometry><cylinder radius="0.05" length="${{length}}"/></geometry></collision>
      <xacro:inertia_of m="${{mass}}" ixx="${{ixx}}" iyy="${{iyy}}" izz="${{izz}}"/>
    </link>
  </xacro:macro>
  <link name="world"/>
  <xacro:rod name="short" length="0.2" mass="1.5" ixx="1" iyy="1" izz="1"/>
  <xacro:rod name="long" length="0.8" mass="3" ixx="2" iyy="2" izz="2"/>
  {joint("world", "short")}
  {joint("world", "long")}
</robot>
"""


def n(value: float) -> str:
    from inertia_kit.physics.formatting import xml_number

    return xml_number(value, 6)


def test_values_passed_through_two_macros_are_written_at_the_outer_calls(tmp_path):
    """`ixx` goes from the robot's call of `rod` through `rod`'s call of `inertia_of`: the
    numbers at the outer calls change, both macros stay as written."""
    path = write_file(tmp_path / "robot.urdf.xacro", NESTED)
    result = fill("--fix", "all", str(path))
    assert result.exit_code == 1, result.stderr
    expected = NESTED
    for length, mass, old in ((0.2, 1.5, "1"), (0.8, 3.0, "2")):
        _, side, _, axial = solid_cylinder(0.05, length, mass=mass)
        expected = expected.replace(
            f'ixx="{old}" iyy="{old}" izz="{old}"/>',
            f'ixx="{n(side)}" iyy="{n(side)}" izz="{n(axial)}"/>',
        )
    assert path.read_text() == expected
    assert_settled(path, "--fix", "all")


PROPERTY = f"""<robot name="r" {XACRO_NS}>
  <xacro:macro name="wheel" params="side">
    <xacro:property name="spin" value="0.5"/>
    <link name="${{side}}_wheel">
      <collision><geometry><sphere radius="0.1"/></geometry></collision>
      <inertial>
        <mass value="2"/>
        <inertia ixx="${{spin}}" ixy="0" ixz="0" iyy="${{0.5 * 1}}" iyz="0" izz="0.008"/>
      </inertial>
    </link>
    {joint("world", "${side}_wheel")}
  </xacro:macro>
  <link name="world"/>
  <xacro:wheel side="left"/>
  <xacro:wheel side="right"/>
</robot>
"""


def test_a_value_read_from_the_macros_property_is_written_in_the_property(tmp_path):
    """`ixx="${spin}"`: the property's number changes and `${spin}` stays used; iyy's
    expression of numbers becomes the number (said); izz (already 2/5 m r²) keeps its text."""
    path = write_file(tmp_path / "robot.urdf.xacro", PROPERTY)
    result = fill("--fix", "all", str(path))
    assert result.exit_code == 1, result.stderr
    moment = 2 * 2.0 * 0.1**2 / 5
    assert n(moment) == "0.008"
    expected = PROPERTY.replace('value="0.5"', f'value="{n(moment)}"').replace(
        "${0.5 * 1}", n(moment)
    )
    assert path.read_text() == expected
    # the sphere is written in numbers: its formula would hold no name, only numbers
    assert "its iyy is written as 0.008 (" in result.stderr
    assert_settled(path, "--fix", "all")


OTHER_SCOPE = f"""<robot name="r" {XACRO_NS}>
  <xacro:property name="length" value="0.4"/>
  <xacro:macro name="rod_inertia" params="">
    <inertial>
      <origin xyz="0 0 0" rpy="0 0 0"/>
      <mass value="1"/>
      <inertia ixx="${{(0.02**2 * 3 + length**2) / 12}}" ixy="0" ixz="0"
               iyy="${{(0.02**2 * 3 + length**2) / 12}}" iyz="0" izz="${{0.02**2 / 2}}"/>
    </inertial>
  </xacro:macro>
  <link name="world"/>
  {joint("world", "rod")}
  <link name="rod">
    <collision>
      <origin xyz="${{length/2}} 0 0" rpy="0 ${{pi/2}} 0"/>
      <geometry><cylinder radius="0.02" length="${{length}}"/></geometry>
    </collision>
    <xacro:rod_inertia/>
  </link>
</robot>
"""


def test_a_shape_origin_read_in_another_scope_is_written_as_numbers_and_said(tmp_path):
    """The <inertial> (in a macro used once) takes the collision's axes, but its written origin
    reads `length` and `pi` in the link's scope: the numbers are written and the note says
    so."""
    path = write_file(tmp_path / "robot.urdf.xacro", OTHER_SCOPE)
    result = fill("--fix", "all", str(path))
    assert result.exit_code == 1, result.stderr
    assert "link `rod` is no longer parametric: its xyz is written as 0.2" in result.stderr
    assert 'not as its shape\'s <origin> writes it ("${length/2} 0 0"' in result.stderr
    text = path.read_text()
    assert '<origin xyz="0.2 0 0" rpy="0 1.5708 0"/>' in text
    assert "${(0.02**2 * 3 + length**2) / 12}" in text  # the formula in the rod's axes stays
    assert_settled(path, "--fix", "all", besides=("IN041",))
