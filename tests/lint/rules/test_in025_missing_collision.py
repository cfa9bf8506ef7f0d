"""IN025 missing-collision: a link with mass and visual geometry and nothing to collide with."""

from __future__ import annotations

from kit.urdf import box, box_inertial, collision, joint, link, moving, visual
from kit.urdf import robot as robot_of

SIZE = (0.1, 0.1, 0.1)
VISUAL = visual(box(*SIZE))
COLLISION = collision(box(*SIZE))


def robot(arm: str, tool: str | None = None, tool_joint: str = "fixed") -> str:
    """A moving link `arm` holding ``arm``, and a link `tool` on a ``tool_joint`` from it."""
    extra = "" if tool is None else joint("arm", "tool", tool_joint, name="t") + link("tool", tool)
    return moving(arm, extra)


def test_moving_link_with_mass_and_visual_only_fires(lint):
    findings = lint(robot(VISUAL + box_inertial(2.7, SIZE)), "IN025")
    assert [f.link for f in findings] == ["arm"]
    assert findings[0].message == "link `arm` has 2.7 kg and a visual shape but no <collision>"
    assert len(findings[0].message) <= 100
    # the detail: what the body without a surface does, and the visual shape it has
    assert findings[0].detail.startswith("it ends a chain (a foot, wheel, finger or tool)")
    assert findings[0].detail.endswith("(visual only: box 0.1×0.1×0.1)")


def test_link_with_collision_is_quiet(lint):
    assert lint(robot(VISUAL + COLLISION + box_inertial(2.7, SIZE)), "IN025") == []


def test_massless_visual_only_frame_is_quiet(lint):
    assert lint(robot(COLLISION + box_inertial(2.7, SIZE), VISUAL), "IN025") == []


def test_visual_frame_welded_to_a_colliding_body_is_quiet(lint):
    # the tool is lumped into the arm, which collides
    assert (
        lint(robot(COLLISION + box_inertial(2.7, SIZE), VISUAL + box_inertial(0.5, SIZE)), "IN025")
        == []
    )


def test_visual_frame_on_a_moving_joint_fires(lint):
    findings = lint(
        robot(COLLISION + box_inertial(2.7, SIZE), VISUAL + box_inertial(0.5, SIZE), "revolute"),
        "IN025",
    )
    assert [f.link for f in findings] == ["tool"]


def test_negligible_marker_and_option(lint):
    # a 0.1 g marker welded to a 2.7 kg body without collisions at all
    text = robot(box_inertial(2.7, SIZE), VISUAL + box_inertial(0.0001, SIZE))
    assert lint(text, "IN025") == []
    strict = lint(text, "IN025", options={"IN025": {"min_mass_share": 0.0}})
    assert [f.link for f in strict] == ["tool"]


def test_invalid_or_zero_mass_is_not_its_business(lint):
    assert lint(robot(VISUAL + box_inertial(0.0, SIZE)), "IN025") == []
    no_geometry = robot(box_inertial(2.7, SIZE))
    assert lint(no_geometry, "IN025") == []


# --- the detail says what the missing surface does, by the link's place ------------------------

BODY = VISUAL + box_inertial(2.7, SIZE)


def one_detail(lint, text: str) -> str:
    (finding,) = lint(text, "IN025")
    return finding.detail


def test_a_free_base_falls_through_the_floor(lint):
    text = robot_of(link("base", BODY), joint("base", "wheel", "continuous"), link("wheel"))
    assert (
        "it is the robot's free base (not welded to a `world` link): it falls through the floor "
        "unless other links hold it up, and passes through other bodies"
    ) in one_detail(lint, text)
    single = robot_of(link("crate", BODY))
    assert "falls through the floor" in one_detail(lint, single)


def test_a_body_on_a_floating_joint_is_free(lint):
    text = robot_of(
        link("world"), joint("world", "ball", "floating", name="free"), link("ball", BODY)
    )
    assert "it is a free body (floating joint `free`): it falls through" in one_detail(lint, text)


def test_an_interior_link_only_makes_no_contact(lint):
    """Unitree G1's waist, Z1's link05: held by joints on both sides, nothing to fall."""
    text = moving(BODY, joint("arm", "tip", "revolute", name="t") + link("tip", COLLISION))
    detail = one_detail(lint, text)
    assert "falls" not in detail and "sinks" not in detail
    assert (
        "held by its joints it does not fall, but it makes no contact: the floor, other bodies "
        "and the robot's own links pass through it"
    ) in detail


def test_the_end_of_a_chain_sinks_through_the_floor(lint):
    assert (
        "it ends a chain (a foot, wheel, finger or tool), so it sinks through the floor and "
        "passes through whatever it should touch"
    ) in one_detail(lint, robot(BODY))


def test_a_part_fixed_to_the_world_stays_put(lint):
    text = robot_of(link("world"), joint("world", "table", "fixed"), link("table", BODY))
    assert "it is fixed to the world, so it stays put" in one_detail(lint, text)


def test_the_message_is_one_short_line_and_the_detail_keeps_the_basis(lint):
    """The mass in the message; what the body without a surface does and its visual shapes
    in the detail."""
    text = robot_of(link("base", BODY), joint("base", "wheel", "continuous"), link("wheel"))
    (finding,) = lint(text, "IN025")
    assert finding.message == "link `base` has 2.7 kg and a visual shape but no <collision>"
    assert len(finding.message) <= 100
    assert finding.detail == (
        "it is the robot's free base (not welded to a `world` link): it falls through the floor "
        "unless other links hold it up, and passes through other bodies (visual only: box "
        "0.1×0.1×0.1)"
    )
