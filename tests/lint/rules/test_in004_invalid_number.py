"""IN004 invalid-number: every numeric attribute, grouped per element, with PyBullet's reading."""

from __future__ import annotations

import math

import pytest

from inertia_kit.lint.rules.in004_invalid_number import strtod

SIX = 'ixx="0.025" ixy="0" ixz="0" iyy="0.025" iyz="0" izz="0.005"'


def robot(mass: str = "3", six: str = SIX, origin: str = "0 0 0", limit: str = "10") -> str:
    return (
        '<robot name="r"><link name="base"/>\n'
        '<joint name="j" type="revolute"><parent link="base"/><child link="arm"/>\n'
        f'<origin xyz="{origin}"/><axis xyz="0 0 1"/>\n'
        f'<limit lower="-1" upper="1" effort="{limit}" velocity="1"/></joint>\n'
        f'<link name="arm"><inertial><mass value="{mass}"/>\n<inertia {six}/></inertial>\n'
        '<collision><geometry><box size="0.1 0.1 0.3"/></geometry></collision></link>\n'
        "</robot>"
    )


def in004(lint, text):
    return [f for f in lint(text, "IN004") if f.code == "IN004"]


def test_valid_numbers_are_quiet(lint):
    assert in004(lint, robot()) == []


def test_mass_with_a_unit(lint):
    (finding,) = in004(lint, robot(mass="3kg"))
    assert finding.link == "arm" and finding.line == 5
    assert finding.message == "link `arm`: `<mass value>` = '3kg' (not a number)"
    assert "ROS (urdfdom) and Gazebo refuse the file" in finding.detail
    assert "MuJoCo refuses the file" in finding.detail
    assert "PyBullet silently reads '3kg' as 3" in finding.detail


def test_nan_and_inf_mujoco_reads_them(lint):
    (finding,) = in004(lint, robot(mass="nan"))
    assert "not a number" in finding.message and "MuJoCo reads nan/inf" in finding.detail
    (finding,) = in004(lint, robot(six=SIX.replace('izz="0.005"', 'izz="inf"')))
    assert "`<inertia izz>` = 'inf' (infinite)" in finding.message


def test_overflow_is_infinite(lint):
    (finding,) = in004(lint, robot(mass="1e999"))
    assert "(infinite)" in finding.message and "MuJoCo refuses" in finding.detail


def test_attributes_of_one_element_are_reported_together(lint):
    six = SIX.replace('ixx="0.025"', 'ixx="a"').replace('iyy="0.025"', 'iyy="b"')
    (finding,) = in004(lint, robot(six=six))
    assert "`<inertia ixx>` = 'a'" in finding.message
    assert "`<inertia iyy>` = 'b'" in finding.message
    assert "'a' as 0, 'b' as 0" in finding.detail


def test_elements_are_reported_separately(lint):
    findings = in004(lint, robot(mass="x", limit="ten"))
    assert sorted((f.line, f.joint, f.link) for f in findings) == [
        (4, "j", None),
        (5, None, "arm"),
    ]
    limit = next(f for f in findings if f.joint == "j")
    assert "joint `j`: `<limit effort>` = 'ten'" in limit.message


@pytest.mark.parametrize(
    ("origin", "described", "read"),
    [
        ("0,0,0", "1 values, not 3", '0 0 0 ("Couldn\'t parse vector3")'),
        ("0.07, 0, -0.69", "not three plain numbers", "0.07 0 -0.69"),
        ("1 2 3 4", "4 values, not 3", "1 2 3"),
    ],
)
def test_vectors(lint, origin, described, read):
    (finding,) = in004(lint, robot(origin=origin))
    assert f"`<joint><origin xyz>` = {origin!r} ({described})" in finding.message
    assert f"as {read}" in finding.detail


@pytest.mark.parametrize(
    ("text", "value"),
    [("2kg", 2.0), ("1.5.2", 1.5), ("abc", 0.0), ("-1.57.", -1.57), (" .5e1x", 5.0), ("", 0.0)],
)
def test_strtod_reads_the_numeric_prefix(text, value):
    assert strtod(text) == value


def test_strtod_nan():
    assert math.isnan(strtod("nan"))


@pytest.mark.parametrize(
    ("six", "item"),
    [
        (SIX.replace('izz="0.005"', 'izz="-1e308"'), "`<inertia izz>` = '-1e308' (beyond ±1e50)"),
        (SIX.replace('ixy="0"', 'ixy="1e-320"'), "`<inertia ixy>` = '1e-320' (subnormal: "),
        # found by hypothesis: a normal but tiny moment overflowed the tensor comparison
        (
            SIX.replace('ixx="0.025"', 'ixx="2.2250738585072014e-308"'),
            "`<inertia ixx>` = '2.2250738585072014e-308' (non-zero below 1e-50)",
        ),
        (SIX.replace('izz="0.005"', 'izz="-1e-60"'), "`<inertia izz>` = '-1e-60' (non-zero below"),
    ],
)
def test_numbers_no_arithmetic_can_use(lint, six, item):
    (finding,) = in004(lint, robot(six=six))
    assert item in finding.message
    assert "no robot has such a value" in finding.detail
    assert "refuse the file" not in finding.detail  # every parser reads it


def test_vectors_name_the_unusable_values(lint):
    (finding,) = in004(lint, robot(origin="1e308 1e308 1e308"))
    assert "`<joint><origin xyz>` = '1e308 1e308 1e308' (beyond ±1e50)" in finding.message
    (finding,) = in004(lint, robot(origin="0 1e51 5e-324"))
    assert "(1e51 is beyond ±1e50, 5e-324 is subnormal" in finding.message


def test_a_tiny_mass_is_unusable_a_tiny_product_is_not(lint):
    """A mass or a moment is divided by; a product of inertia only adds to the tensor."""
    (finding,) = in004(lint, robot(mass="2.2250738585072014e-308"))
    assert "`<mass value>` = '2.2250738585072014e-308' (non-zero below 1e-50)" in finding.message
    assert in004(lint, robot(six=SIX.replace('ixy="0"', 'ixy="1e-300"'))) == []


def test_cad_noise_for_zero_is_quiet(lint):
    """iCub (example-robot-data) writes xyz="0.032 -2.67276e-51 0" and rpy 5.77686e-66."""
    text = robot(origin="0.032 -2.67276e-51 0", six=SIX.replace('ixy="0"', 'ixy="2.40741e-35"'))
    assert in004(lint, text.replace("<origin xyz=", '<origin rpy="0 5.77686e-66 0" xyz=')) == []


def test_joint_limits_only_need_to_be_finite(lint):
    assert in004(lint, robot(limit="1e308")) == []
    (finding,) = in004(lint, robot(limit="1e999"))
    assert "(infinite)" in finding.message


def test_a_broken_and_an_extreme_value_together(lint):
    six = SIX.replace('ixx="0.025"', 'ixx="a"').replace('iyy="0.025"', 'iyy="1e308"')
    (finding,) = in004(lint, robot(six=six))
    assert "`<inertia iyy>` = '1e308' (beyond ±1e50)" in finding.message
    assert "ROS (urdfdom) and Gazebo refuse the file" in finding.detail
    assert (
        "PyBullet silently reads 'a' as 0" in finding.detail and "'1e308' as" not in finding.detail
    )


def test_the_message_is_one_short_line_and_the_detail_has_the_basis(lint):
    six = " ".join(f'{n}="{n}_value"' for n in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"))
    (finding,) = in004(lint, robot(six=six))
    assert len(finding.message) <= 100
    assert finding.message.startswith("link `arm`: `<inertia ixx>` = 'ixx_value' (not a number)")
    assert finding.message.endswith(" more)")
    # every value, whole, and what each parser does with them
    for name in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"):
        assert f"`<inertia {name}>` = '{name}_value' (not a number)" in finding.detail
    assert "PyBullet silently reads 'ixx_value' as 0" in finding.detail


def test_a_long_text_is_cut_short_in_the_message(lint):
    expression = "${" + "+".join(["mass_of_the_upper_arm_link"] * 4) + "}"
    (finding,) = in004(lint, robot(mass=expression))
    assert len(finding.message) <= 100 and "…" in finding.message
    assert repr(expression) in finding.detail
