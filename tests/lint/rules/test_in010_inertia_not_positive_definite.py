"""IN010 inertia-not-positive-definite: zero and negative principal moments, and point masses."""

from __future__ import annotations

import math

import pytest

from inertia_kit.physics.formatting import fmt

LIMIT = '<limit lower="-1" upper="1" effort="10" velocity="1"/>'
BOX = '<collision><geometry><box size="0.1 0.1 0.3"/></geometry></collision>'
GOOD = 'ixx="0.025" ixy="0" ixz="0" iyy="0.025" iyz="0" izz="0.005"'


def inertial(mass: str, six: str) -> str:
    return f'<inertial><mass value="{mass}"/><inertia {six}/></inertial>'


def six(ixx=0.0, ixy=0.0, ixz=0.0, iyy=0.0, iyz=0.0, izz=0.0) -> str:
    return f'ixx="{ixx}" ixy="{ixy}" ixz="{ixz}" iyy="{iyy}" iyz="{iyz}" izz="{izz}"'


def arm(body: str, kind: str = "revolute", parent: str = "base") -> str:
    limit = LIMIT if kind == "revolute" else ""
    return (
        f'<joint name="j" type="{kind}"><parent link="{parent}"/><child link="arm"/>'
        f'<axis xyz="0 0 1"/>{limit}</joint><link name="arm">{body}</link>'
    )


def in010(lint, text):
    return [f for f in lint(text, "IN010") if f.code == "IN010"]


def robot(*parts):
    return '<robot name="r"><link name="base"/>' + "".join(parts) + "</robot>"


def test_positive_definite_is_quiet(lint):
    assert in010(lint, robot(arm(inertial("3", GOOD) + BOX))) == []


def test_zero_tensor_on_a_moving_link(lint):
    (finding,) = in010(lint, robot(arm(inertial("3", six()) + BOX)))
    assert "all six `<inertia>` values are 0" in finding.message
    assert "MuJoCo refuses the model" in finding.message
    ixx = 3 * (0.01 + 0.09) / 12
    assert f"ixx = {fmt(ixx, 4)}" in finding.message
    assert finding.expected["ixx"] == pytest.approx(ixx)
    assert finding.expected["izz"] == pytest.approx(3 * 0.02 / 12)


def test_negative_moment_from_large_products(lint):
    # eigenvalues of [[0.01, 0.02], [0.02, 0.01]] are 0.01 ± 0.02
    (finding,) = in010(lint, robot(arm(inertial("1", six(0.01, 0.02, 0, 0.01, 0, 0.02)))))
    assert f"{fmt(0.01 - 0.02, 4)} kg·m² is negative" in finding.message
    assert "Gazebo and Drake reject the tensor" in finding.message


def test_rod_tensor_on_a_moving_link(lint):
    (finding,) = in010(lint, robot(arm(inertial("1", six(0.01, 0, 0, 0.01, 0, 0)))))
    assert "(0, 0.01, 0.01) kg·m²: the smallest is 0" in finding.message


def test_eigenvalue_noise_is_shown_as_zero(lint):
    # rank one: every value 1e-6, eigenvalues (0, 0, 3e-6) up to rounding
    (finding,) = in010(lint, robot(arm(inertial("1", six(*([1e-6] * 6))))))
    assert f"(0, 0, {fmt(3e-6, 4)}) kg·m²" in finding.message


def test_point_mass_welded_to_a_body_is_lumped(lint):
    text = robot(
        arm(inertial("3", GOOD) + BOX),
        '<joint name="imu_joint" type="fixed"><parent link="arm"/><child link="imu"/>'
        '<origin xyz="0 0 0.1"/></joint>',
        f'<link name="imu">{inertial("0.01", six())}</link>',
    )
    assert in010(lint, text) == []


def test_point_mass_welded_to_nothing_with_inertia(lint):
    text = robot(arm(inertial("0.01", six()), kind="fixed"))
    (finding,) = in010(lint, text)
    assert finding.link == "arm"


def test_point_mass_welded_to_world_is_static(lint):
    text = (
        '<robot name="r"><link name="world"/>'
        + arm(inertial("0.01", six()), kind="fixed", parent="world")
        + "</robot>"
    )
    assert in010(lint, text) == []


def test_negative_moment_is_flagged_even_when_welded(lint):
    text = robot(
        arm(inertial("3", GOOD) + BOX),
        '<joint name="w" type="fixed"><parent link="arm"/><child link="cap"/></joint>',
        f'<link name="cap">{inertial("0.1", six(-1e-4, 0, 0, 1e-4, 0, 1e-4))}</link>',
    )
    assert [f.link for f in in010(lint, text)] == ["cap"]


@pytest.mark.parametrize("mass", ["0", "-1", "nan"])
def test_mass_problems_are_other_rules(lint, mass):
    assert in010(lint, robot(arm(inertial(mass, six())))) == []


def test_rotated_axes_do_not_change_the_verdict(lint):
    rotated = (
        f'<inertial><origin rpy="0.3 {math.pi / 4} 1"/><mass value="3"/>'
        f"<inertia {GOOD}/></inertial>"
    )
    assert in010(lint, robot(arm(rotated + BOX))) == []
