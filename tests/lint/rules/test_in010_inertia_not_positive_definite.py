"""IN010 inertia-not-positive-definite: zero and negative principal moments, and point masses."""

from __future__ import annotations

import math

import pytest
from kit.moments import box_moments
from kit.urdf import box, collision, inertial, joint, link, moving

from inertia_kit.physics.formatting import fmt

BOX = collision(box(0.1, 0.1, 0.3))
GOOD = (0.025, 0.025, 0.005)


def in010(lint, text):
    return [f for f in lint(text, "IN010") if f.code == "IN010"]


def test_positive_definite_is_quiet(lint):
    assert in010(lint, moving(inertial(3, *GOOD) + BOX)) == []


def test_zero_tensor_on_a_moving_link(lint):
    (finding,) = in010(lint, moving(inertial(3, 0) + BOX))
    assert finding.message == (
        "link `arm`: all six `<inertia>` values are 0: not positive definite"
    )
    assert "MuJoCo refuses the model" in finding.detail
    ixx, _, izz = box_moments(3, (0.1, 0.1, 0.3))
    assert f"ixx = {fmt(ixx, 4)}" in finding.detail
    assert finding.expected["ixx"] == pytest.approx(ixx)
    assert finding.expected["izz"] == pytest.approx(izz)


def test_negative_moment_from_large_products(lint):
    # eigenvalues of [[0.01, 0.02], [0.02, 0.01]] are 0.01 ± 0.02
    (finding,) = in010(lint, moving(inertial(1, 0.01, 0.01, 0.02, ixy=0.02)))
    assert f"{fmt(0.01 - 0.02, 4)} kg·m² is negative" in finding.message
    assert "Gazebo rejects the tensor, Drake replaces it by a sphere of water" in finding.detail


def test_rod_tensor_on_a_moving_link(lint):
    (finding,) = in010(lint, moving(inertial(1, 0.01, 0.01, 0)))
    assert "the smallest principal moment is 0" in finding.message
    assert "principal moments (0, 0.01, 0.01) kg·m²" in finding.detail


def test_eigenvalue_noise_is_shown_as_zero(lint):
    # rank one: every value 1e-6, eigenvalues (0, 0, 3e-6) up to rounding
    (finding,) = in010(lint, moving(inertial(1, 1e-6, ixy=1e-6, ixz=1e-6, iyz=1e-6)))
    assert f"(0, 0, {fmt(3e-6, 4)}) kg·m²" in finding.detail


def test_point_mass_welded_to_a_body_is_lumped(lint):
    imu = joint("arm", "imu", "fixed", xyz="0 0 0.1") + link("imu", inertial(0.01, 0))
    text = moving(inertial(3, *GOOD) + BOX, extra=imu)
    assert in010(lint, text) == []


def test_point_mass_welded_to_nothing_with_inertia(lint):
    text = moving(inertial(0.01, 0), kind="fixed", root="base")
    (finding,) = in010(lint, text)
    assert finding.link == "arm"


def test_point_mass_welded_to_world_is_static(lint):
    text = moving(inertial(0.01, 0), kind="fixed", root="world")
    assert in010(lint, text) == []


def test_negative_moment_is_flagged_even_when_welded(lint):
    cap = joint("arm", "cap", "fixed") + link("cap", inertial(0.1, -1e-4, 1e-4, 1e-4))
    text = moving(inertial(3, *GOOD) + BOX, extra=cap)
    assert [f.link for f in in010(lint, text)] == ["cap"]


@pytest.mark.parametrize("mass", ["0", "-1", "nan"])
def test_mass_problems_are_other_rules(lint, mass):
    assert in010(lint, moving(inertial(mass, 0))) == []


def test_rotated_axes_do_not_change_the_verdict(lint):
    rotated = inertial(3, *GOOD, rpy=f"0.3 {math.pi / 4} 1")
    assert in010(lint, moving(rotated + BOX)) == []


# --- judged whatever is wrong elsewhere ----------------------------------------------------------


@pytest.mark.parametrize("mass", ["abc", "0", "-1"])
def test_a_negative_moment_is_flagged_whatever_the_mass(lint, mass):
    (finding,) = in010(lint, moving(inertial(mass, 0.025, 0.025, -1) + BOX))
    assert "-1 kg·m² is negative" in finding.message
    # no geometry values without a positive mass to scale them
    assert finding.expected is None and "gives" not in finding.detail


def test_a_zero_tensor_with_a_bad_origin_is_flagged_with_the_mass_known(lint):
    (finding,) = in010(lint, moving(inertial(3, 0, xyz="a b c") + BOX))
    assert "all six `<inertia>` values are 0" in finding.message


def test_a_negative_diagonal_value_is_flagged_when_another_value_is_not_a_number(lint):
    for products in ({"ixy": "abc"}, {"ixz": "1,5"}):
        (finding,) = in010(lint, moving(inertial(3, 0.025, 0.025, -0.5, **products) + BOX))
        assert "izz = -0.5 kg·m² is negative" in finding.message
        assert "whatever the other values are" in finding.detail
    text = moving(inertial(3, 0.025, 0.025, -0.5).replace(' ixy="0"', "") + BOX)
    (finding,) = in010(lint, text)
    assert "izz = -0.5 kg·m²" in finding.message
    # a partial tensor with positive diagonal values cannot be judged
    assert in010(lint, moving(inertial(3, *GOOD, ixy="abc") + BOX)) == []


def test_the_message_is_one_short_line_and_the_detail_has_the_basis(lint):
    (finding,) = in010(lint, moving(inertial(1, 0.01, 0.01, 0.02, ixy=0.02) + BOX))
    assert finding.message == (
        f"link `arm`: principal moment {fmt(0.01 - 0.02, 4)} kg·m² is negative: not positive "
        "definite"
    )
    assert len(finding.message) <= 100
    assert finding.detail.startswith(f"principal moments ({fmt(0.01 - 0.02, 4)}, ")
    assert "MuJoCo refuses the model" in finding.detail
    assert "its collision box (0.1 × 0.1 × 0.3 m) with the declared 1 kg gives" in finding.detail
