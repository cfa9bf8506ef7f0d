"""IN022 implausible-density: mass / volume against 50–25 000 kg/m³."""

from __future__ import annotations

import pytest
from kit import moving


def arm(body: str, extra: str = "") -> str:
    return moving(body, name="arm", extra=extra)


def inertial(mass: float) -> str:
    moment = mass * (0.1**2 + 0.1**2) / 12  # a 0.1 m cube's, scaled with the mass
    return (
        f'<inertial><mass value="{mass}"/><inertia ixx="{moment}" ixy="0" ixz="0" '
        f'iyy="{moment}" iyz="0" izz="{moment}"/></inertial>'
    )


CUBE = '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
VOLUME = 0.1**3


def test_aluminium_is_quiet(lint):
    assert lint(arm(CUBE + inertial(2700 * VOLUME)), "IN022") == []


def test_grams_written_as_kilograms_is_too_dense(lint):
    mass = 2700.0  # 2.7 kg written in grams
    findings = lint(arm(CUBE + inertial(mass)), "IN022")
    assert len(findings) == 1
    assert findings[0].expected["density"] == pytest.approx(mass / VOLUME)
    assert findings[0].expected["volume"] == pytest.approx(VOLUME)
    assert "above the plausible 25000 kg/m³" in findings[0].message


def test_placeholder_mass_is_too_light(lint):
    findings = lint(arm(CUBE + inertial(0.01)), "IN022")
    assert len(findings) == 1 and findings[0].expected["density"] == pytest.approx(10.0)
    assert findings[0].expected["mass_at_1000_kg_m3"] == pytest.approx(1.0)


def test_density_options(lint):
    text = arm(CUBE + inertial(8000 * VOLUME))
    assert lint(text, "IN022") == []
    assert len(lint(text, "IN022", options={"IN022": {"max_density": 5000.0}})) == 1
    light = arm(CUBE + inertial(0.04))
    assert len(lint(light, "IN022")) == 1
    assert lint(light, "IN022", options={"IN022": {"min_density": 20.0}}) == []


def test_overlapping_shapes_count_the_shared_volume_once(lint):
    # two 0.1 m cubes overlapping by half: 0.15 × 0.1 × 0.1 = 0.0015 m³, not 0.002
    shapes = (
        '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
        '<collision><origin xyz="0.05 0 0"/><geometry><box size="0.1 0.1 0.1"/></geometry>'
        "</collision>"
    )
    findings = lint(arm(shapes + inertial(40.0)), "IN022")
    assert len(findings) == 1
    assert findings[0].expected["volume"] == pytest.approx(0.0015, rel=1e-4)


def test_a_plausible_visual_clears_an_oversized_collision_shape(lint):
    """A 0.5 kg part in a 0.1 m cube visual, with a loose 0.4 m collision box around it."""
    body = (
        '<visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>'
        '<collision><geometry><box size="0.4 0.4 0.4"/></geometry></collision>'
    )
    assert lint(arm(body + inertial(0.5)), "IN022") == []  # 7.8 kg/m³ vs 500 kg/m³


def test_visual_only_link_uses_the_visual(lint):
    body = '<visual><geometry><sphere radius="0.1"/></geometry></visual>'
    findings = lint(arm(body + inertial(500.0)), "IN022")
    assert len(findings) == 1 and "its visual sphere" in findings[0].message


def test_mesh_with_scale(lint, tmp_path):
    """A 100 mm cube in millimetres, scaled by 0.001, holds 0.001 m³."""
    corners = [(x, y, z) for x in (0, 100) for y in (0, 100) for z in (0, 100)]
    faces = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1),
             (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]  # fmt: skip
    text = "solid c\n"
    for face in faces:
        text += "facet normal 0 0 0\nouter loop\n"
        text += "".join(f"vertex {' '.join(map(str, corners[i]))}\n" for i in face)
        text += "endloop\nendfacet\n"
    (tmp_path / "cube.stl").write_text(text + "endsolid c\n")
    mesh = (
        '<collision><geometry><mesh filename="cube.stl" scale="0.001 0.001 0.001"/>'
        "</geometry></collision>"
    )
    assert lint(arm(mesh + inertial(2.7)), "IN022") == []
    findings = lint(arm(mesh + inertial(2700.0)), "IN022")
    assert len(findings) == 1 and findings[0].expected["volume"] == pytest.approx(0.001)


def test_negligible_dummy_on_a_fixed_joint_is_skipped(lint):
    dummy = """
  <joint name="f" type="fixed"><parent link="arm"/><child link="foot"/></joint>
  <link name="foot">
    <collision><geometry><sphere radius="0.02"/></geometry></collision>
    <inertial><mass value="1e-6"/>
      <inertia ixx="1e-10" ixy="0" ixz="0" iyy="1e-10" iyz="0" izz="1e-10"/></inertial>
  </link>"""
    text = arm(CUBE + inertial(2.7), dummy)
    assert lint(text, "IN022") == []
    strict = lint(text, "IN022", options={"IN022": {"min_mass_share": 0.0}})
    assert [f.link for f in strict] == ["foot"]


def test_no_mass_or_no_geometry_is_not_its_business(lint):
    assert lint(arm(CUBE), "IN022") == []
    assert lint(arm(inertial(1e6)), "IN022") == []
