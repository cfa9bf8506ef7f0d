"""IN041 root-link-inertia: the root link carries an <inertial>."""

from __future__ import annotations

from kit.urdf import inertial, joint, link, robot

from inertia_kit.lint.findings import Severity

INERTIAL = inertial(10, 0.1)
JOINT = joint("base_link", "arm", name="j") + link("arm", INERTIAL)


def test_root_with_inertial_warns_with_kdl_message_and_dummy_root(lint):
    text = robot(link("base_link", INERTIAL), JOINT)
    findings = lint(text, "IN041")
    assert len(findings) == 1
    finding = findings[0]
    assert finding.severity == Severity.WARNING and finding.link == "base_link"
    assert (
        finding.message == "root link `base_link` has an <inertial> (10 kg), which KDL leaves out"
    )
    assert len(finding.message) <= 100
    assert (
        "The root link base_link has an inertia specified in the URDF, but KDL does not "
        "support a root link with an inertia." in finding.detail
    )
    assert "floating base" in finding.detail
    assert '<child link="base_link"/>' in finding.help
    assert finding.expected == {"root": "base_link", "mass": 10.0}


def test_the_suggested_root_is_a_name_the_robot_does_not_use(lint):
    # a root named base_footprint: the help suggested a link base_footprint above it, and a
    # joint from base_footprint to itself
    text = robot(link("base_footprint", INERTIAL), joint("base_footprint", "arm", name="j"))
    text = text.replace("</robot>", link("arm", INERTIAL) + "</robot>")
    (finding,) = lint(text, "IN041")
    assert '<link name="base_footprint_root"/>' in finding.help
    assert '<parent link="base_footprint_root"/><child link="base_footprint"/>' in finding.help


def test_massless_dummy_root_is_quiet(lint):
    text = robot(
        link("base_footprint"),
        joint("base_footprint", "base_link", "fixed", name="f"),
        link("base_link", INERTIAL),
        JOINT,
    )
    assert lint(text, "IN041") == []


def test_single_rigid_object_is_quiet_unless_asked(lint):
    text = robot(link("cube", INERTIAL), name="cube")
    assert lint(text, "IN041") == []
    findings = lint(text, "IN041", options={"IN041": {"single_link": True}})
    assert len(findings) == 1 and findings[0].link == "cube"


def test_several_roots_are_left_to_in040(lint):
    text = robot(link("base_link", INERTIAL), JOINT, link("other", INERTIAL))
    assert lint(text, "IN041") == []


def test_inertial_without_mass_still_counts(lint):
    text = robot(link("base_link", '<inertial><origin xyz="0 0 0"/></inertial>'), JOINT)
    findings = lint(text, "IN041")
    assert len(findings) == 1 and "kg)" not in findings[0].message
