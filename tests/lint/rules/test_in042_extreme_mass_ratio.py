"""IN042 extreme-mass-ratio: the two sides of a moving joint differ hugely in mass."""

from __future__ import annotations

from kit.urdf import box, box_inertial, collision, inertial, joint, link, robot

from inertia_kit.lint.findings import Severity


def chain(body: float, tip: float, kind: str = "continuous", welded: float | None = None) -> str:
    """base → (yaw) → `body` [welded to `plate`] → (``kind`` `tip_joint`) → `tip`, by mass."""
    weld = (
        ()
        if welded is None
        else (joint("body", "plate", "fixed", name="w"), link("plate", inertial(welded, 1e-4)))
    )
    return robot(
        link("base"),
        joint("base", "body", "continuous", name="yaw"),
        link("body", inertial(body, 1e-4)),
        *weld,
        joint("body", "tip", kind, name="tip_joint"),
        link("tip", inertial(tip, 1e-4)),
    )


def test_ratio_beyond_default_warns(lint):
    findings = lint(chain(20.0, 0.005), "IN042")
    assert len(findings) == 1
    finding = findings[0]
    assert finding.severity == Severity.WARNING
    # no geometry to tell which mass is wrong: the ratio is the joint's, no link is blamed
    assert finding.joint == "tip_joint" and finding.link is None
    assert finding.message == "joint `tip_joint`: `tip` weighs 0.005 kg, 1/4000 of `body` at 20 kg"
    assert len(finding.message) <= 100
    assert finding.detail.startswith(
        "`tip` weighs 0.005 kg, 1/4000 of `body` at 20 kg (beyond 1/1000): the joint's equations "
        "are ill-conditioned"
    )
    assert finding.expected["ratio"] == 4000.0


def test_ratio_within_default_is_quiet(lint):
    assert lint(chain(20.0, 0.05), "IN042") == []


def test_fixed_joint_is_not_compared(lint):
    assert lint(chain(20.0, 0.001, kind="fixed"), "IN042") == []


def test_welded_links_count_as_one_body(lint):
    # 0.5 + 19.5 kg welded: the tip compares with 20 kg
    findings = lint(chain(0.5, 0.005, welded=19.5), "IN042")
    assert len(findings) == 1
    assert "`body` (with 1 welded link) at 20 kg" in findings[0].detail


def test_massless_side_is_skipped(lint):
    # the yaw joint joins a massless base to the body: IN001's business, not a ratio
    assert lint(chain(2000.0, 1000.0), "IN042") == []


def test_heavier_child_is_reported_too(lint):
    findings = lint(chain(0.01, 20.0), "IN042")
    assert len(findings) == 1 and "`body` weighs 0.01 kg" in findings[0].message


def test_max_ratio_option(lint):
    assert lint(chain(20.0, 0.05), "IN042", options={"IN042": {"max_ratio": 100.0}}) != []
    assert lint(chain(20.0, 0.005), "IN042", options={"IN042": {"max_ratio": 1e4}}) == []


def boxed(body: float, tip: float) -> str:
    """base → `body` (a 0.1 m aluminium cube: 2.7 kg) → `tip` (a 2 cm cube: 0.0216 kg), by mass."""
    return robot(
        link("base"),
        joint("base", "body", "continuous", name="yaw"),
        link("body", box_inertial(body, (0.1, 0.1, 0.1)), collision(box(0.1, 0.1, 0.1))),
        joint("body", "tip", name="tip_joint"),
        link("tip", box_inertial(tip, (0.02, 0.02, 0.02)), collision(box(0.02, 0.02, 0.02))),
    )


def test_a_mass_no_material_gives_is_named_on_its_link(lint):
    # the body's mass written in grams: 2700 kg in a 0.1 m cube is 2.7e6 kg/m³, the tip's
    # 0.0216 kg in a 2 cm cube a plausible 2700: the body's mass slipped, not the tip's
    findings = lint(boxed(2700.0, 0.0216), "IN042")
    assert len(findings) == 1
    finding = findings[0]
    assert finding.link == "body" and finding.joint == "tip_joint"
    assert "`tip` weighs 0.0216 kg, 1/125000 of `body` at 2700 kg" in finding.message
    assert finding.message.endswith(" (likely `body`'s mass)")
    assert "`body` is the likely slip: its 2700 kg is 2.7e+06 kg/m³" in finding.detail
    assert "check `body`'s mass" in finding.help


def test_plausible_densities_on_both_sides_blame_neither(lint):
    # a 0.0005 kg tip in its 2 cm cube is 62.5 kg/m³ (foam), the body aluminium: either mass
    # may be the wrong one (GR1-T2's 17 kg torso, its mass tripled, beside a 10 g head link)
    findings = lint(boxed(2.7, 0.0005), "IN042")
    assert [(f.link, f.joint) for f in findings] == [(None, "tip_joint")]
    assert "check both masses" in findings[0].help


def test_a_light_side_too_light_for_any_material_is_named(lint):
    # 0.00002 kg in a 2 cm cube is 2.5 kg/m³, below any material: the tip, whatever the body
    findings = lint(boxed(2.7, 0.00002), "IN042")
    assert [f.link for f in findings] == ["tip"]
    findings = lint(boxed(2700.0, 0.00002), "IN042")
    assert [f.link for f in findings] == ["tip"]


def test_a_negligible_welded_frame_is_not_the_slip_of_its_body(lint):
    # Go1's shape: a 10 g IMU frame in a 1 mm cube (10⁷ kg/m³, denser still than the body)
    # welded to a body whose 2.7 kg were typed in grams (2700 kg: 2.7e6 kg/m³ in its 0.1 m
    # cube): the frame carries 4e-6 of the body and cannot have set its weight
    imu = link("imu", box_inertial(0.01, (0.001,) * 3), collision(box(0.001, 0.001, 0.001)))
    text = boxed(2700.0, 0.0216).replace(
        "</robot>", joint("body", "imu", "fixed", name="imu_joint") + imu + "</robot>"
    )
    (finding,) = lint(text, "IN042")
    assert finding.link == "body"


def test_a_negligible_welded_frame_does_not_hide_the_slipped_mass(lint):
    # HyQ's shape: a 1 µg foot frame (a 2 cm sphere: far too light for any material) welded
    # to the tip; it carries 1/20000 of the tip's body and cannot have set its weight
    text = boxed(2700.0, 0.0216).replace(
        "</robot>",
        joint("tip", "foot", "fixed", name="foot_joint")
        + link("foot", box_inertial(1e-6, (0.02, 0.02, 0.02)), collision(box(0.02, 0.02, 0.02)))
        + "</robot>",
    )
    (finding,) = lint(text, "IN042")
    assert finding.link == "body"
    assert "`body` is the likely slip" in finding.detail
