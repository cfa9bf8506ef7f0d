"""IN022 implausible-density: mass / volume against 50–25 000 kg/m³."""

from __future__ import annotations

import pytest
from kit.meshes import box_triangles, write_ascii_stl
from kit.urdf import (
    box,
    box_inertial,
    collision,
    inertial,
    joint,
    link,
    mesh,
    moving,
    sphere,
    visual,
)

from inertia_kit.physics.formatting import fmt

SIZE = (0.1, 0.1, 0.1)  # a cube: the shape, and the inertial scaled with the mass
CUBE = collision(box(*SIZE))
VOLUME = 0.1**3


def test_aluminium_is_quiet(lint):
    assert lint(moving(CUBE + box_inertial(2700 * VOLUME, SIZE)), "IN022") == []


def test_grams_written_as_kilograms_is_too_dense(lint):
    mass = 2700.0  # 2.7 kg written in grams
    findings = lint(moving(CUBE + box_inertial(mass, SIZE)), "IN022")
    assert len(findings) == 1
    assert findings[0].expected["density"] == pytest.approx(mass / VOLUME)
    assert findings[0].expected["volume"] == pytest.approx(VOLUME)
    assert findings[0].message == (
        f"link `arm`: 2700 kg in its collision box is {fmt(mass / VOLUME, 4)} kg/m³, above "
        "25000 kg/m³"
    )
    assert len(findings[0].message) <= 100
    assert "box (0.1 × 0.1 × 0.1 m) of 0.001 m³" in findings[0].detail
    assert "above the plausible 25000 kg/m³ (tungsten is 19 300)" in findings[0].detail


def test_placeholder_mass_is_too_light(lint):
    findings = lint(moving(CUBE + box_inertial(0.01, SIZE)), "IN022")
    assert len(findings) == 1 and findings[0].expected["density"] == pytest.approx(10.0)
    assert findings[0].expected["mass_at_1000_kg_m3"] == pytest.approx(1.0)


def test_density_options(lint):
    text = moving(CUBE + box_inertial(8000 * VOLUME, SIZE))
    assert lint(text, "IN022") == []
    assert len(lint(text, "IN022", options={"IN022": {"max_density": 5000.0}})) == 1
    light = moving(CUBE + box_inertial(0.04, SIZE))
    assert len(lint(light, "IN022")) == 1
    assert lint(light, "IN022", options={"IN022": {"min_density": 20.0}}) == []


def test_overlapping_shapes_count_the_shared_volume_once(lint):
    # two 0.1 m cubes overlapping by half: 0.15 × 0.1 × 0.1 = 0.0015 m³, not 0.002
    shapes = CUBE + collision(box(*SIZE), xyz="0.05 0 0")
    findings = lint(moving(shapes + box_inertial(40.0, SIZE)), "IN022")
    assert len(findings) == 1
    assert findings[0].expected["volume"] == pytest.approx(0.0015, rel=1e-4)


def test_a_plausible_visual_clears_an_oversized_collision_shape(lint):
    """A 0.5 kg part in a 0.1 m cube visual, with a loose 0.4 m collision box around it."""
    body = visual(box(*SIZE)) + collision(box(0.4, 0.4, 0.4))
    assert lint(moving(body + box_inertial(0.5, SIZE)), "IN022") == []  # 7.8 kg/m³ vs 500 kg/m³


def test_visual_only_link_uses_the_visual(lint):
    body = visual(sphere(0.1))
    findings = lint(moving(body + box_inertial(500.0, SIZE)), "IN022")
    assert len(findings) == 1 and "its visual sphere" in findings[0].message


def test_mesh_with_scale(lint, tmp_path):
    """A 100 mm cube in millimetres, scaled by 0.001, holds 0.001 m³."""
    write_ascii_stl(tmp_path / "cube.stl", box_triangles((100, 100, 100)))
    cube = collision(mesh("cube.stl", scale="0.001 0.001 0.001"))
    assert lint(moving(cube + box_inertial(2.7, SIZE)), "IN022") == []
    findings = lint(moving(cube + box_inertial(2700.0, SIZE)), "IN022")
    assert len(findings) == 1 and findings[0].expected["volume"] == pytest.approx(0.001)


def test_negligible_dummy_on_a_fixed_joint_is_skipped(lint):
    dummy = joint("arm", "foot", "fixed") + link(
        "foot", collision(sphere(0.02)), inertial("1e-6", "1e-10")
    )
    text = moving(CUBE + box_inertial(2.7, SIZE), dummy)
    assert lint(text, "IN022") == []
    strict = lint(text, "IN022", options={"IN022": {"min_mass_share": 0.0}})
    assert [f.link for f in strict] == ["foot"]


def test_no_mass_or_no_geometry_is_not_its_business(lint):
    assert lint(moving(CUBE), "IN022") == []
    assert lint(moving(box_inertial(1e6, SIZE)), "IN022") == []


@pytest.mark.parametrize(
    ("mass", "fires"),
    [
        (1.0, False),  # 49.99999999999999 kg/m³ in floats: prints as the bound, is at it
        (0.99999, False),  # 49.9995: prints "50", at the bound as far as the message can tell
        (0.9995, True),  # 49.975: prints "49.98", below 50
    ],
)
def test_a_density_that_prints_as_the_bound_is_at_it(lint, mass, fires):
    """The rrbot tutorial's link1 (gazebo_ros_demos): 1 kg in a 0.1 × 0.1 × 2 m box was
    "50 kg/m³, below the plausible 50 kg/m³"; a message never says so now, and one that
    fires prints a density other than its bound."""
    size = (0.1, 0.1, 2.0)
    findings = lint(moving(collision(box(*size)) + box_inertial(mass, size)), "IN022")
    assert len(findings) == int(fires)
    for finding in findings:
        shown = finding.message.split(" is ")[1].split(" kg/m³")[0]
        assert shown != "50" and finding.message.endswith("below 50 kg/m³")
        assert "below the plausible 50 kg/m³" in finding.detail


def test_the_same_holds_at_the_upper_bound(lint):
    size = (0.1, 0.1, 0.1)
    at = 25000.0 * 0.001 * (1 + 1e-9)  # above 25 000 by 2.5e-5 kg/m³ in floats
    assert lint(moving(collision(box(*size)) + box_inertial(at, size)), "IN022") == []
    above = 25010.0 * 0.001
    assert len(lint(moving(collision(box(*size)) + box_inertial(above, size)), "IN022")) == 1
