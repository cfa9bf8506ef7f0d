"""IN060 inertia-about-other-point: expected numbers from closed forms computed here."""

from __future__ import annotations

import pytest
from kit import EXAMPLES
from kit.moments import cylinder_moments
from kit.urdf import collision, cylinder, inertial, joint, link, moving, sphere, visual

from inertia_kit.lint.findings import Severity
from inertia_kit.lint.runner import Selection, lint_file


def drum(mass=2.0, radius=0.1, length=0.1, about_origin=True):
    """A cylinder standing on the link origin, its tensor about that origin or its centre."""
    transverse, _, axial = cylinder_moments(mass, radius, length)
    centre = length / 2
    if about_origin:
        transverse += mass * centre**2
    return collision(cylinder(radius, length), xyz=f"0 0 {centre}") + inertial(
        mass, transverse, transverse, axial, xyz=f"0 0 {centre}"
    )


def test_tensor_about_the_link_origin_fires_with_the_corrected_tensor(lint):
    findings = lint(moving(drum()))
    assert [f.code for f in findings] == ["IN060"]
    finding = findings[0]
    transverse, _, axial = cylinder_moments(2.0, 0.1, 0.1)
    # about the COM the written tensor has ∫z² dm = m l²/12 + m (l/2)² = m l²/3, more than the
    # m (l/2)² any mass in the drum's length can have (IN023's bound along a direction)
    assert finding.severity == Severity.ERROR and finding.link == "arm"
    assert (
        finding.message == "link `arm`: inertia written about the link origin, 0.05 m from the COM"
    )
    assert finding.detail.endswith("as written no mass inside the geometry can have it (IN023)")
    assert "about the link origin (0, 0, 0), not about the COM (0, 0, 0.05)" in finding.detail
    assert "2 kg × (0.05 m)²" in finding.detail
    expected = finding.expected
    assert expected["ixx"] == pytest.approx(transverse) and expected["iyy"] == pytest.approx(
        transverse
    )
    assert expected["izz"] == pytest.approx(axial)
    assert expected["point"] == [0.0, 0.0, 0.0] and expected["point_name"] == "the link origin"
    assert expected["mass"] == 2.0 and expected["xyz"] == [0.0, 0.0, 0.05]
    assert "subtract the parallel-axis term" in finding.help


def test_named_by_the_visual_mesh_when_the_crude_collision_only_comes_closer(lint):
    # a calf: a cylinder drawn, a foot sphere for collision; its real-part tensor (1.3 and 0.8
    # times the cylinder's) written about the knee. The cylinder names the slip; against the
    # sphere nothing lands in the band, but undoing it comes closer there too: it stands
    mass, radius, length, centre = 1.2, 0.02, 0.2, 0.1
    transverse, _, axial = cylinder_moments(mass, radius, length)
    transverse, axial = 1.3 * transverse, 0.8 * axial
    about_knee = transverse + mass * centre**2
    body = (
        visual(cylinder(radius, length), xyz=f"0 0 {-centre}")
        + collision(sphere(0.02), xyz=f"0 0 {-2 * centre}")
        + inertial(mass, about_knee, about_knee, axial, xyz=f"0 0 {-centre}")
    )
    findings = [f for f in lint(moving(body)) if f.code != "IN024"]
    assert [f.code for f in findings] == ["IN060"]
    assert findings[0].expected["ixx"] == pytest.approx(transverse)


def test_the_right_tensor_is_quiet(lint):
    assert lint(moving(drum(about_origin=False))) == []


def test_it_replaces_in020_only_while_enabled(lint):
    # a rod about its end: ×4 across, beyond what any mass inside it has (IN023 too)
    text = moving(drum(mass=2.0, radius=0.05, length=0.4))
    findings = lint(text)
    assert [f.code for f in findings] == ["IN060"]
    assert findings[0].severity == Severity.ERROR  # it stands for IN023's error
    assert "no mass inside the geometry can have it (IN023)" in findings[0].detail
    alone = lint(text, ("IN0",), ignore=("IN060",))
    assert [f.code for f in alone] == ["IN020", "IN023"]
    assert "likely the declared inertia is the tensor about the link origin" in alone[0].detail
    assert alone[0].message.endswith(", likely about another point (IN060)")


def test_beyond_the_bound_of_visual_geometry_only_stays_a_warning(lint):
    """IN060 stands for IN023's error only when that error is firm (analysis.firmness)."""
    text = moving(drum(mass=2.0, radius=0.05, length=0.4).replace("collision", "visual"))
    (finding,) = lint(text, ("IN0",), ignore=("IN025",))
    assert finding.code == "IN060" and finding.severity == Severity.WARNING
    assert "(IN023)" not in finding.message + finding.detail


def test_severity_is_configurable(lint):
    findings = lint(moving(drum()), "IN060", severities={"IN060": Severity.INFO})
    assert [f.severity for f in findings] == [Severity.INFO]


def test_a_child_joint_origin_is_named(lint):
    """The tensor taken about the joint at the far end (z = 0.4) of a link whose COM is at 0.1."""
    mass, radius, length = 3.0, 0.05, 0.2
    transverse, _, axial = cylinder_moments(mass, radius, length)
    shifted = transverse + mass * 0.3**2
    body = collision(cylinder(radius, length), xyz="0 0 0.1") + inertial(
        mass, shifted, shifted, axial, xyz="0 0 0.1"
    )
    tip = joint("arm", "tool", "fixed", name="tip", xyz="0 0 0.4") + link("tool")
    findings = lint(moving(body, tip), "IN060")
    assert len(findings) == 1
    assert "about the origin of joint `tip` (0, 0, 0.4)" in findings[0].detail
    assert findings[0].message.endswith(
        "inertia written about joint `tip`'s origin, 0.3 m from the COM"
    )
    assert findings[0].expected["ixx"] == pytest.approx(transverse)
    assert findings[0].expected["point_name"] == "the origin of joint `tip`"


def test_the_message_is_one_short_line_and_the_detail_has_the_arithmetic(lint):
    """The claim and its key number in the message; the point, the arithmetic and the geometry
    in the detail. A joint name that would make the line too long is left to the detail."""
    mass, radius, length = 3.0, 0.05, 0.2
    transverse, _, axial = cylinder_moments(mass, radius, length)
    shifted = transverse + mass * 0.3**2
    body = collision(cylinder(radius, length), xyz="0 0 0.1") + inertial(
        mass, shifted, shifted, axial, xyz="0 0 0.1"
    )
    for name in ("tip", "a_rather_long_tool_flange_mounting_joint"):
        tip = joint("arm", "tool", "fixed", name=name, xyz="0 0 0.4") + link("tool")
        (finding,) = lint(moving(body, tip), "IN060")
        assert len(finding.message) <= 100
        assert finding.message.endswith(", 0.3 m from the COM")
        detail = finding.detail
        assert f"the tensor about the origin of joint `{name}` (0, 0, 0.4)" in detail
        assert "not about the COM (0, 0, 0.1)" in detail and "3 kg × (0.3 m)²" in detail
        assert "the collision cylinder (r = 0.05 m, l = 0.2 m) gives" in detail
    assert "about a joint's origin" in finding.message


def _seed(path: str, packages: tuple[str, ...] = ()) -> list:
    result = lint_file(EXAMPLES / path, Selection(), package_paths=packages)
    assert result.error is None
    return result.findings


def test_seed_mrm_cylinders_are_about_the_link_origin_and_the_base_is_quiet():
    """The issue's acceptance: link_01 … link_05 explained, corrected values about the COM."""
    findings = _seed("mrm_description/urdf/mrm.xacro", (str(EXAMPLES),))
    forensic = [f for f in findings if f.code == "IN060"]
    assert sorted(f.link for f in forensic) == [f"link_0{i}" for i in range(1, 6)]
    assert not [f for f in findings if f.code == "IN020"]  # replaced
    assert not [f for f in findings if f.link == "base_link" and f.code in ("IN020", "IN060")]
    link_01 = next(f for f in forensic if f.link == "link_01")
    assert "about the link origin (0, 0, 0), not about the COM (0, 0, 0.2)" in link_01.detail
    assert (
        link_01.message
        == "link `link_01`: inertia written about the link origin, 0.2 m from the COM"
    )
    # the declared 13.235 less the parallel-axis term m d²: the cylinder's m (3r² + l²) / 12
    mass = 157.633
    assert link_01.expected["ixx"] == pytest.approx(13.235 - mass * 0.2**2)
    assert link_01.expected["ixx"] == pytest.approx(cylinder_moments(mass, 0.35, 0.4)[0], rel=1e-3)
    assert round(link_01.expected["ixx"], 2) == 6.93 and link_01.expected["izz"] == 9.655
    link_02 = next(f for f in forensic if f.link == "link_02")
    assert link_02.expected["ixx"] == pytest.approx(12.679 - 57.906 * 0.4**2)
