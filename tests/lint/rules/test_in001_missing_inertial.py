"""IN001 missing-inertial: which massless bodies are flagged, and the values the message gives."""

from __future__ import annotations

import pytest
from kit.moments import box_moments
from kit.urdf import LIMIT, box, collision, inertial, joint, link, robot, visual

from inertia_kit.physics.formatting import fmt

BOX = collision(box(0.1, 0.1, 0.3))
MASS = inertial(3, 0.025, 0.025, 0.005)


def in001(lint, text: str, **options):
    kw = {"options": {"IN001": options}} if options else {}
    return [f for f in lint(text, "IN001", **kw) if f.code == "IN001"]


def test_moving_link_without_inertial_gives_geometry_values(lint):
    findings = in001(lint, robot(link("base"), joint("base", "arm", name="j"), link("arm", BOX)))
    assert [f.link for f in findings] == ["arm"]
    (finding,) = findings
    volume = 0.1 * 0.1 * 0.3
    mass = 1000.0 * volume
    ixx, _, izz = box_moments(mass, (0.1, 0.1, 0.3))
    message = finding.message
    assert "revolute joint `j`" in message and "`<inertial>`" in message
    assert f"{fmt(mass, 4)} kg at 1000 kg/m³" in message
    assert f"ixx = {fmt(ixx, 4)}" in message and f"izz = {fmt(izz, 4)}" in message
    assert "Gazebo drops it" in message and "MuJoCo fills in mass" in message
    assert "PyBullet gives it 1 kg" in message
    expected = finding.expected
    assert expected["mass"] == pytest.approx(mass)
    assert expected["volume"] == pytest.approx(volume)
    assert expected["ixx"] == pytest.approx(ixx) and expected["izz"] == pytest.approx(izz)
    assert expected["density"] == 1000.0
    assert finding.severity.name == "ERROR"


def test_without_collision_mujoco_refuses(lint):
    (finding,) = in001(lint, robot(link("base"), joint("base", "arm", name="j"), link("arm")))
    assert "mjMINVAL" in finding.message and finding.expected is None


@pytest.mark.parametrize("kind", ["continuous", "prismatic", "floating", "planar"])
def test_every_moving_joint_type(lint, kind):
    findings = in001(
        lint, robot(link("base"), joint("base", "arm", kind, name="j"), link("arm", BOX))
    )
    assert [f.link for f in findings] == ["arm"]


def test_mimic_joint_moves(lint):
    text = robot(
        link("base"),
        joint("base", "a", name="j"),
        link("a", MASS + BOX),
        '<joint name="m" type="revolute"><parent link="base"/><child link="b"/>'
        f'<axis xyz="0 0 1"/>{LIMIT}<mimic joint="j" multiplier="1" offset="0"/></joint>',
        link("b", BOX),
    )
    assert [f.link for f in in001(lint, text)] == ["b"]


def test_massless_frames_on_fixed_joints_are_fine(lint):
    text = robot(
        link("base"),
        joint("base", "arm", name="j"),
        link("arm", MASS + BOX),
        joint("arm", "tool0", "fixed", name="tool"),
        link("tool0"),
        joint("arm", "camera", "fixed", name="cam"),
        link("camera", visual(box(0.02, 0.02, 0.02))),
    )
    assert in001(lint, text) == []


def test_massless_moving_link_welded_to_a_link_with_mass_is_lumped(lint):
    text = robot(
        link("base"),
        joint("base", "motor", name="j"),
        link("motor"),
        joint("motor", "arm", "fixed", name="w"),
        link("arm", MASS + BOX),
    )
    assert in001(lint, text) == []


def test_the_inertial_belongs_where_the_geometry_is(lint):
    text = robot(
        link("base"),
        joint("base", "motor", name="j"),
        link("motor"),
        joint("motor", "shell", "fixed", name="w"),
        link("shell", BOX),
    )
    (finding,) = in001(lint, text)
    assert finding.link == "shell"
    assert "`motor`" in finding.message and "revolute joint `j`" in finding.message
    assert finding.expected["mass"] == pytest.approx(3.0)


def test_root_frame_is_a_fixed_base_unless_told_otherwise(lint):
    text = robot(link("base"), joint("base", "arm", name="j"), link("arm", MASS + BOX))
    assert in001(lint, text) == []
    (finding,) = in001(lint, text, floating_base=True)
    assert finding.link == "base" and "carries moving links" in finding.message


def test_root_with_collision_geometry_needs_mass(lint):
    text = robot(link("base", BOX), joint("base", "arm", name="j"), link("arm", MASS + BOX))
    (finding,) = in001(lint, text)
    assert finding.link == "base" and "root" in finding.message
    assert "Gazebo drops it and the whole model" in finding.message


def test_root_welded_to_a_world_link_is_static(lint):
    text = robot(
        link("world"),
        joint("world", "base", "fixed", name="anchor"),
        link("base", BOX),
        joint("base", "arm", name="j"),
        link("arm", MASS + BOX),
    )
    assert in001(lint, text) == []


def test_visual_only_root_alone_is_not_simulated(lint):
    text = robot(link("deco", visual(box(1, 1, 1))))
    assert in001(lint, text) == []


def test_a_broken_inertial_is_left_to_other_rules(lint):
    zero = inertial(0, 0)
    text = robot(link("base"), joint("base", "arm", name="j"), link("arm", zero + BOX))
    assert in001(lint, text) == []


def test_one_finding_per_body(lint):
    text = robot(
        link("base"),
        joint("base", "arm", name="j"),
        link("arm", BOX),
        joint("arm", "cover", "fixed", name="w"),
        link("cover", BOX),
    )
    (finding,) = in001(lint, text)
    assert finding.link == "arm" and "`cover`" in finding.message
