"""IN025 missing-collision: a link with mass and visual geometry and nothing to collide with."""

from __future__ import annotations

from kit import moving

VISUAL = '<visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>'
COLLISION = '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'


def inertial(mass: float) -> str:
    moment = mass * 0.02 / 12
    return (
        f'<inertial><mass value="{mass}"/><inertia ixx="{moment}" ixy="0" ixz="0" '
        f'iyy="{moment}" iyz="0" izz="{moment}"/></inertial>'
    )


def robot(arm: str, tool: str | None = None, tool_joint: str = "fixed") -> str:
    extra = ""
    if tool is not None:
        limit = '<limit lower="-1" upper="1" effort="1" velocity="1"/>'
        extra = f"""
  <joint name="t" type="{tool_joint}"><parent link="arm"/><child link="tool"/>
    <axis xyz="0 0 1"/>{limit if tool_joint != "fixed" else ""}</joint>
  <link name="tool">{tool}</link>"""
    return moving(arm, name="arm", extra=extra)


def test_moving_link_with_mass_and_visual_only_fires(lint):
    findings = lint(robot(VISUAL + inertial(2.7)), "IN025")
    assert [f.link for f in findings] == ["arm"]
    assert "no <collision>" in findings[0].message and "2.7 kg" in findings[0].message


def test_link_with_collision_is_quiet(lint):
    assert lint(robot(VISUAL + COLLISION + inertial(2.7)), "IN025") == []


def test_massless_visual_only_frame_is_quiet(lint):
    assert lint(robot(COLLISION + inertial(2.7), VISUAL), "IN025") == []


def test_visual_frame_welded_to_a_colliding_body_is_quiet(lint):
    # the tool is lumped into the arm, which collides
    assert lint(robot(COLLISION + inertial(2.7), VISUAL + inertial(0.5)), "IN025") == []


def test_visual_frame_on_a_moving_joint_fires(lint):
    findings = lint(robot(COLLISION + inertial(2.7), VISUAL + inertial(0.5), "revolute"), "IN025")
    assert [f.link for f in findings] == ["tool"]


def test_negligible_marker_and_option(lint):
    # a 0.1 g marker welded to a 2.7 kg body without collisions at all
    text = robot(inertial(2.7), VISUAL + inertial(0.0001))
    assert lint(text, "IN025") == []
    strict = lint(text, "IN025", options={"IN025": {"min_mass_share": 0.0}})
    assert [f.link for f in strict] == ["tool"]


def test_invalid_or_zero_mass_is_not_its_business(lint):
    assert lint(robot(VISUAL + inertial(0.0)), "IN025") == []
    no_geometry = robot(inertial(2.7))
    assert lint(no_geometry, "IN025") == []
