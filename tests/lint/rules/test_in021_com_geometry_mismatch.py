"""IN021 com-geometry-mismatch: outside the hull (error), far from the centroid (warning)."""

from __future__ import annotations

import pytest
from kit.urdf import box, collision, cylinder, inertial, joint, link, moving, sphere, visual

from inertia_kit.lint.findings import Severity


def inertial_at(xyz: str) -> str:
    # the tensor of a 0.4 × 0.2 × 0.1 box of 2 kg: only the COM varies in these tests
    return inertial(2.0, 0.00833, 0.0283, 0.0333, xyz=xyz)


BOX = collision(box(0.4, 0.2, 0.1), xyz="0.2 0 0")


def test_com_at_the_centroid_is_quiet(lint):
    assert lint(moving(BOX + inertial_at("0.2 0 0")), "IN021") == []


def test_com_offset_within_the_limit_is_quiet(lint):
    # 0.1 m towards +x of a 0.2 m half-length: 50 % of the way, under the default 60 %
    assert lint(moving(BOX + inertial_at("0.3 0 0")), "IN021") == []


def test_com_far_from_the_centroid_warns_with_the_centroid(lint):
    # at the joint, the end of the box: 100 % of the way to the edge
    findings = lint(moving(BOX + inertial_at("0 0 0")), "IN021")
    assert len(findings) == 1
    finding = findings[0]
    assert finding.severity == Severity.WARNING
    assert finding.expected["xyz"] == pytest.approx([0.2, 0.0, 0.0])
    assert finding.expected["offset_fraction"] == pytest.approx(1.0)
    assert (
        finding.message
        == "link `arm`: centre of mass 0.2 m from its box's centroid (100% to the edge)"
    )
    assert "0.2 m from the centroid (0.2, 0, 0) m of its collision box" in finding.detail


def test_max_offset_option(lint):
    text = moving(BOX + inertial_at("0.3 0 0"))
    findings = lint(text, "IN021", options={"IN021": {"max_offset": 0.4}})
    assert len(findings) == 1 and findings[0].expected["offset_fraction"] == pytest.approx(0.5)


def test_com_outside_the_hull_is_an_error(lint):
    # 0.25 m beyond the far end (x = 0.4) of a geometry 0.4 m across: margin 2 % = 8 mm
    findings = lint(moving(BOX + inertial_at("0.65 0 0")), "IN021")
    assert len(findings) == 1
    assert findings[0].severity == Severity.ERROR
    assert "0.25 m outside its collision box" in findings[0].message
    assert "the centre of mass (0.65, 0, 0) m lies at least 0.25 m outside" in findings[0].detail


def test_margin_option(lint):
    text = moving(BOX + inertial_at("0.42 0 0"))  # 2 cm outside: 5 % of 0.4 m
    assert lint(text, "IN021")[0].severity == Severity.ERROR
    relaxed = lint(text, "IN021", options={"IN021": {"margin": 0.1}})
    assert [f.severity for f in relaxed] == [Severity.WARNING]  # still far from the centroid


def test_rotated_geometry_in_link_axes(lint):
    """A cylinder along x (rpy pitch 90°): a COM 0.12 m along x is inside, 0.12 m along z not."""
    rod = collision(cylinder(0.02, 0.3), rpy="0 1.5707963267948966 0")
    assert lint(moving(rod + inertial_at("0.05 0 0")), "IN021") == []
    findings = lint(moving(rod + inertial_at("0 0 0.12")), "IN021")
    assert len(findings) == 1 and findings[0].severity == Severity.ERROR


def test_com_between_two_shapes_is_inside_their_hull(lint):
    """A dumbbell: the COM between two spheres is in no sphere, yet where the mass balances."""
    dumbbell = collision(sphere(0.05), xyz="-0.2 0 0") + collision(sphere(0.05), xyz="0.2 0 0")
    assert lint(moving(dumbbell + inertial_at("0 0 0")), "IN021") == []


def test_near_the_visual_centroid_is_quiet(lint):
    """A small collision box at one end of a long visual: the visual basis clears it."""
    body = visual(box(0.4, 0.2, 0.1), xyz="0.2 0 0") + collision(box(0.1, 0.2, 0.1), xyz="0.35 0 0")
    assert lint(moving(body + inertial_at("0.2 0 0")), "IN021") == []


def test_negligible_link_on_a_fixed_joint_is_skipped(lint):
    marker = joint("arm", "marker", "fixed") + link(
        "marker", collision(sphere(0.01)), inertial(0.001, "1e-8", xyz="1 0 0")
    )
    text = moving(BOX + inertial_at("0.2 0 0"), marker)
    assert lint(text, "IN021") == []
    strict = lint(text, "IN021", options={"IN021": {"min_mass_share": 0.0}})
    assert [f.link for f in strict] == ["marker"]


def test_no_inertial_or_no_geometry_is_not_its_business(lint):
    assert lint(moving(BOX), "IN021") == []
    assert lint(moving(inertial_at("5 5 5")), "IN021") == []


@pytest.mark.parametrize(
    "inertial_text",
    [
        '<inertial><origin xyz="2 0 0"/><mass value="2"/></inertial>',  # no <inertia>: IN003
        '<inertial><origin xyz="2 0 0"/><mass value="2kg"/>'
        '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>',  # IN004
        inertial(2.0, 0.00833, 0.0283, 0.0333, xyz="2 0 0", ixy="abc"),  # IN004
    ],
    ids=["no-inertia", "mass-not-a-number", "product-not-a-number"],
)
def test_the_com_is_judged_whatever_the_rest_of_the_inertial(lint, inertial_text):
    (finding,) = lint(moving(BOX + inertial_text), "IN021")
    assert finding.severity == Severity.ERROR and "outside" in finding.message


def test_a_massless_link_has_no_centre_of_mass(lint):
    assert lint(moving(BOX + inertial(0, 0, xyz="2 0 0")), "IN021") == []


def test_the_message_is_one_short_line_and_the_detail_keeps_the_basis(lint):
    """The simple arm's pattern: the distance and the fraction in the message; the centre of
    mass, the centroid and the geometry's dimensions in the detail."""
    (finding,) = lint(moving(BOX + inertial_at("0 0 0")), "IN021")
    assert len(finding.message) <= 100
    assert finding.detail == (
        "the centre of mass (0, 0, 0) m is 0.2 m from the centroid (0.2, 0, 0) m of its "
        "collision box (0.4 × 0.2 × 0.1 m), 100% of the way to its edge"
    )
