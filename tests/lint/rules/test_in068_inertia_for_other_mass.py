"""IN068 inertia-for-other-mass: a tensor kept while the mass was changed."""

from __future__ import annotations

import pytest
from kit.moments import box_moments
from kit.urdf import box, collision, inertial, moving, sphere


def codes(lint, text):
    return {f.code for f in lint(text)}


def in068(lint, text):
    return [f for f in lint(text, "IN068") if f.code == "IN068"]


def test_a_tensor_for_a_third_of_the_mass(lint):
    ixx, iyy, izz = box_moments(2.0, (0.4, 0.2, 0.1))
    body = inertial(6.0, ixx, iyy, izz) + collision(box(0.4, 0.2, 0.1))
    (finding,) = in068(lint, moving(body))
    assert (
        finding.message == "link `arm`: inertia fits its geometry for 2 kg, not the declared 6 kg"
    )
    assert len(finding.message) <= 100
    # the detail: the geometry, the factor on every principal moment and how alike they are
    assert finding.detail.startswith(
        "the tensor is its collision box (0.4 × 0.2 × 0.1 m)'s for 2 kg, not the declared 6 kg: "
        "every principal moment is 1/3 of the geometry's at the declared mass (alike within a "
        "factor of "
    )
    assert "multiply the six values by 3" in finding.help
    assert finding.expected["tensor_mass"] == pytest.approx(2.0)
    assert finding.expected["factor"] == pytest.approx(1 / 3)
    assert finding.severity.name == "WARNING"
    # it replaces IN020's symptom
    assert "IN020" not in codes(lint, moving(body))


def test_the_right_mass_a_placeholder_and_a_unit_are_not_it(lint):
    ixx, iyy, izz = box_moments(2.0, (0.4, 0.2, 0.1))
    assert in068(lint, moving(inertial(2.0, ixx, iyy, izz) + collision(box(0.4, 0.2, 0.1)))) == []
    assert in068(lint, moving(inertial(0.06, 1.0) + collision(sphere(0.02)))) == []  # IN013's
    # the tensor in kg·mm²: IN063's
    mm2 = (ixx * 1e6, iyy * 1e6, izz * 1e6)
    assert in068(lint, moving(inertial(2.0, *mm2) + collision(box(0.4, 0.2, 0.1)))) == []


def _twins(left_mass: float, right_mass: float) -> str:
    from kit.urdf import joint, link, robot

    # a CAD part's tensor: the box's at 2 kg times 1.8, 0.6 and 1 along its axes, too unlike its
    # geometry in shape (0.56 in log, over SHAPE) for the geometry alone to say "another mass"
    ixx, iyy, izz = box_moments(2.0, (0.4, 0.2, 0.1))
    values = (1.8 * ixx, 0.6 * iyy, izz)
    shape = collision(box(0.4, 0.2, 0.1))
    return robot(
        link("world"),
        joint("world", "base", "fixed"),
        link("base"),
        joint("base", "left_leg"),
        link("left_leg", inertial(left_mass, *values), shape),
        joint("base", "right_leg"),
        link("right_leg", inertial(right_mass, *values), shape),
    )


def test_a_mass_changed_beside_its_twin(lint):
    assert in068(lint, _twins(2.0, 2.0)) == []
    # the right leg's mass retyped: its twin, same shape and values, says the tensor is for 2 kg
    (finding,) = in068(lint, _twins(2.0, 6.0))
    assert finding.link == "right_leg"
    assert finding.message == (
        "link `right_leg`: inertia is `left_leg`'s, for its 2 kg, not the declared 6 kg"
    )
    assert finding.detail == (
        "its six `<inertia>` values are those of `left_leg`, whose geometry is the same shape "
        "per kilogram, but its mass is 3 times `left_leg`'s (6 kg against 2 kg): the mass was "
        "likely changed after the tensor was computed"
    )
    assert finding.expected["tensor_mass"] == pytest.approx(2.0)
    assert "multiply the six values by 3" in finding.help
    # one finding for the slip: IN013 leaves the copy alone
    assert [f.link for f in lint(_twins(2.0, 6.0), "IN013")] == []
    # a factor within real parts' scatter (2) is not named
    assert in068(lint, _twins(2.0, 4.0)) == []


def test_long_names_leave_the_other_link_to_the_detail(lint):
    """Two names of 40 characters would make the line too long: the message says "another
    link's", the detail names it."""
    left, right = (
        "left_hind_leg_lower_segment_with_the_foot",
        "right_hind_leg_lower_segment_with_foot",
    )
    text = _twins(2.0, 6.0).replace('"left_leg"', f'"{left}"').replace('"right_leg"', f'"{right}"')
    (finding,) = in068(lint, text)
    assert finding.message == (
        f"link `{right}`: inertia is another link's, for its 2 kg, not the declared 6 kg"
    )
    assert len(finding.message) <= 120  # the hard limit, with a name of 38 characters
    assert f"are those of `{left}`" in finding.detail
