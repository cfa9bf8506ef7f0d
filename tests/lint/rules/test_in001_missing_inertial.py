"""IN001 missing-inertial: which massless bodies are flagged, and the values the message gives."""

from __future__ import annotations

import pytest

from inertia_kit.physics.formatting import fmt

LIMIT = '<limit lower="-1" upper="1" effort="10" velocity="1"/>'
BOX = '<collision><geometry><box size="0.1 0.1 0.3"/></geometry></collision>'
MASS = (
    '<inertial><mass value="3"/>'
    '<inertia ixx="0.025" ixy="0" ixz="0" iyy="0.025" iyz="0" izz="0.005"/></inertial>'
)


def joint(name: str, parent: str, child: str, kind: str = "revolute", extra: str = "") -> str:
    limit = LIMIT if kind in ("revolute", "prismatic") else ""
    return (
        f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
        f'<axis xyz="0 0 1"/>{limit}{extra}</joint>'
    )


def robot(*parts: str) -> str:
    return '<robot name="r">' + "".join(parts) + "</robot>"


def link(name: str, body: str = "") -> str:
    return f'<link name="{name}">{body}</link>'


def in001(lint, text: str, **options):
    kw = {"options": {"IN001": options}} if options else {}
    return [f for f in lint(text, "IN001", **kw) if f.code == "IN001"]


def test_moving_link_without_inertial_gives_geometry_values(lint):
    findings = in001(lint, robot(link("base"), joint("j", "base", "arm"), link("arm", BOX)))
    assert [f.link for f in findings] == ["arm"]
    (finding,) = findings
    volume = 0.1 * 0.1 * 0.3
    mass = 1000.0 * volume
    ixx = mass * (0.1**2 + 0.3**2) / 12
    izz = mass * (0.1**2 + 0.1**2) / 12
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
    (finding,) = in001(lint, robot(link("base"), joint("j", "base", "arm"), link("arm")))
    assert "mjMINVAL" in finding.message and finding.expected is None


@pytest.mark.parametrize("kind", ["continuous", "prismatic", "floating", "planar"])
def test_every_moving_joint_type(lint, kind):
    findings = in001(lint, robot(link("base"), joint("j", "base", "arm", kind), link("arm", BOX)))
    assert [f.link for f in findings] == ["arm"]


def test_mimic_joint_moves(lint):
    text = robot(
        link("base"),
        joint("j", "base", "a"),
        link("a", MASS + BOX),
        joint("m", "base", "b", extra='<mimic joint="j" multiplier="1" offset="0"/>'),
        link("b", BOX),
    )
    assert [f.link for f in in001(lint, text)] == ["b"]


def test_massless_frames_on_fixed_joints_are_fine(lint):
    text = robot(
        link("base"),
        joint("j", "base", "arm"),
        link("arm", MASS + BOX),
        joint("tool", "arm", "tool0", "fixed"),
        link("tool0"),
        joint("cam", "arm", "camera", "fixed"),
        link("camera", '<visual><geometry><box size="0.02 0.02 0.02"/></geometry></visual>'),
    )
    assert in001(lint, text) == []


def test_massless_moving_link_welded_to_a_link_with_mass_is_lumped(lint):
    text = robot(
        link("base"),
        joint("j", "base", "motor"),
        link("motor"),
        joint("w", "motor", "arm", "fixed"),
        link("arm", MASS + BOX),
    )
    assert in001(lint, text) == []


def test_the_inertial_belongs_where_the_geometry_is(lint):
    text = robot(
        link("base"),
        joint("j", "base", "motor"),
        link("motor"),
        joint("w", "motor", "shell", "fixed"),
        link("shell", BOX),
    )
    (finding,) = in001(lint, text)
    assert finding.link == "shell"
    assert "`motor`" in finding.message and "revolute joint `j`" in finding.message
    assert finding.expected["mass"] == pytest.approx(3.0)


def test_root_frame_is_a_fixed_base_unless_told_otherwise(lint):
    text = robot(link("base"), joint("j", "base", "arm"), link("arm", MASS + BOX))
    assert in001(lint, text) == []
    (finding,) = in001(lint, text, floating_base=True)
    assert finding.link == "base" and "carries moving links" in finding.message


def test_root_with_collision_geometry_needs_mass(lint):
    text = robot(link("base", BOX), joint("j", "base", "arm"), link("arm", MASS + BOX))
    (finding,) = in001(lint, text)
    assert finding.link == "base" and "root" in finding.message
    assert "Gazebo drops it and the whole model" in finding.message


def test_root_welded_to_a_world_link_is_static(lint):
    text = robot(
        link("world"),
        joint("anchor", "world", "base", "fixed"),
        link("base", BOX),
        joint("j", "base", "arm"),
        link("arm", MASS + BOX),
    )
    assert in001(lint, text) == []


def test_visual_only_root_alone_is_not_simulated(lint):
    text = robot(link("deco", '<visual><geometry><box size="1 1 1"/></geometry></visual>'))
    assert in001(lint, text) == []


def test_a_broken_inertial_is_left_to_other_rules(lint):
    zero = '<inertial><mass value="0"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>'
    text = robot(link("base"), joint("j", "base", "arm"), link("arm", zero + "</inertial>" + BOX))
    assert in001(lint, text) == []


def test_one_finding_per_body(lint):
    text = robot(
        link("base"),
        joint("j", "base", "arm"),
        link("arm", BOX),
        joint("w", "arm", "cover", "fixed"),
        link("cover", BOX),
    )
    (finding,) = in001(lint, text)
    assert finding.link == "arm" and "`cover`" in finding.message
