"""IN041 root-link-inertia: the root link carries an <inertial>."""

from __future__ import annotations

from inertia_kit.lint.findings import Severity

INERTIAL = (
    '<inertial><mass value="10"/>'
    '<inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>'
)
JOINT = (
    '<joint name="j" type="revolute"><parent link="base_link"/><child link="arm"/>'
    '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>'
    f'<link name="arm">{INERTIAL}</link>'
)


def test_root_with_inertial_warns_with_kdl_message_and_dummy_root(lint):
    text = f'<robot name="r"><link name="base_link">{INERTIAL}</link>{JOINT}</robot>'
    findings = lint(text, "IN041")
    assert len(findings) == 1
    finding = findings[0]
    assert finding.severity == Severity.WARNING and finding.link == "base_link"
    assert (
        "The root link base_link has an inertia specified in the URDF, but KDL does not "
        "support a root link with an inertia." in finding.message
    )
    assert "(10 kg)" in finding.message and "floating base" in finding.message
    assert '<child link="base_link"/>' in finding.help
    assert finding.expected == {"root": "base_link", "mass": 10.0}


def test_massless_dummy_root_is_quiet(lint):
    text = (
        '<robot name="r"><link name="base_footprint"/>'
        '<joint name="f" type="fixed"><parent link="base_footprint"/>'
        f'<child link="base_link"/></joint><link name="base_link">{INERTIAL}</link>{JOINT}'
        "</robot>"
    )
    assert lint(text, "IN041") == []


def test_single_rigid_object_is_quiet_unless_asked(lint):
    text = f'<robot name="cube"><link name="cube">{INERTIAL}</link></robot>'
    assert lint(text, "IN041") == []
    findings = lint(text, "IN041", options={"IN041": {"single_link": True}})
    assert len(findings) == 1 and findings[0].link == "cube"


def test_several_roots_are_left_to_in040(lint):
    text = (
        f'<robot name="r"><link name="base_link">{INERTIAL}</link>{JOINT}'
        f'<link name="other">{INERTIAL}</link></robot>'
    )
    assert lint(text, "IN041") == []


def test_inertial_without_mass_still_counts(lint):
    text = (
        '<robot name="r"><link name="base_link"><inertial><origin xyz="0 0 0"/></inertial>'
        f"</link>{JOINT}</robot>"
    )
    findings = lint(text, "IN041")
    assert len(findings) == 1 and "kg)" not in findings[0].message
