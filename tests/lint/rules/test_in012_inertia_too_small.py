"""IN012 inertia-too-small: the absolute and radius-of-gyration floors, lumping, options."""

from __future__ import annotations

import math

import pytest
from kit.moments import box_moments
from kit.urdf import box, collision, inertial, joint, link, moving

from inertia_kit.physics.formatting import fmt


def in012(lint, text, **options):
    kw = {"options": {"IN012": options}} if options else {}
    return [f for f in lint(text, "IN012", **kw) if f.code == "IN012"]


def test_below_both_floors(lint):
    (finding,) = in012(lint, moving(inertial(0.3, 1e-10)))
    radius_mm = math.sqrt(1e-10 / 0.3) * 1000
    assert finding.message == (
        f"link `arm`: smallest principal moment {fmt(1e-10, 3)} kg·m² is below "
        f"{fmt(0.3 * 1e-6, 3)} kg·m²"
    )
    assert f"radius of gyration {fmt(radius_mm, 3)} mm for 0.3 kg" in finding.detail
    # the binding floor is the larger: m·(1 mm)² = 3e-7 kg·m²
    assert f"{fmt(0.3 * 1e-6, 3)} kg·m², a 1 mm radius of gyration" in finding.detail
    assert finding.expected == {"min_moment": 0.3 * 1e-6}
    assert finding.severity.name == "WARNING"


def test_heavy_link_with_a_placeholder(lint):
    # 2 kg with 1e-6 kg·m²: above 1e-9 but a 0.71 mm radius of gyration
    (finding,) = in012(lint, moving(inertial(2, 1e-6, 1e-3, 1e-3)))
    assert f"radius of gyration {fmt(math.sqrt(1e-6 / 2) * 1000, 3)} mm" in finding.detail
    assert in012(lint, moving(inertial(2, 1e-6, 1e-3, 1e-3)), min_radius=0.0005) == []


def test_light_part_against_the_absolute_floor(lint):
    # 1 g with 5e-9 kg·m²: a 2.2 mm radius of gyration, above both default floors
    text = moving(inertial(0.001, 5e-9))
    assert in012(lint, text) == []
    (finding,) = in012(lint, text, min_moment=1e-8)
    assert f"is below {fmt(1e-8)} kg·m²" in finding.message
    assert f"mm for 0.001 kg, below the floor of {fmt(1e-8)} kg·m²" in finding.detail


def test_a_real_gripper_finger_is_quiet(lint):
    # a 5 g finger, a 4 × 1 × 1 cm box: its smallest moment m(b² + c²)/12 is 8.3e-8 kg·m²
    m, a, b, c = 0.005, 0.04, 0.01, 0.01
    moments = box_moments(m, (a, b, c))
    assert in012(lint, moving(inertial(m, *moments))) == []


def test_geometry_values_when_there_is_geometry(lint):
    (finding,) = in012(lint, moving(inertial(3, 1e-9) + collision(box(0.1, 0.1, 0.3))))
    moments = sorted(box_moments(3, (0.1, 0.1, 0.3)))
    assert finding.expected["geometry_principal_moments"] == pytest.approx(moments)
    assert len(finding.message) <= 100
    assert "its collision box (0.1 × 0.1 × 0.3 m) with the declared 3 kg gives principal " in (
        finding.detail
    )


def test_welded_to_a_body_that_carries_the_inertia(lint):
    extra = joint("arm", "screw", "fixed") + link("screw", inertial(0.002, 1e-12))
    assert in012(lint, moving(inertial(3, 0.02, 0.02, 0.01), extra=extra)) == []


def test_welded_to_nothing_bigger(lint):
    assert len(in012(lint, moving(inertial(0.3, 1e-10), kind="fixed", root="base"))) == 1


def test_welded_to_world_is_static(lint):
    assert in012(lint, moving(inertial(0.3, 1e-10), kind="fixed", root="world")) == []


def test_zero_moment_is_in010s(lint):
    assert in012(lint, moving(inertial(0.3, 0))) == []


def test_an_origin_that_is_not_a_number_hides_nothing(lint):
    (finding,) = in012(lint, moving(inertial(0.3, 1e-10, rpy="a b c")))
    assert f"smallest principal moment {fmt(1e-10, 3)} kg·m²" in finding.message


@pytest.mark.parametrize("mass", ["abc", "0"])
def test_without_a_positive_mass_there_is_no_floor(lint, mass):
    # a massless frame may carry any tensor: IN002/IN004 report the mass
    assert in012(lint, moving(inertial(mass, 1e-12))) == []
