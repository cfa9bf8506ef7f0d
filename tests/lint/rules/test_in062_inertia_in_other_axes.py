"""IN062 inertia-in-other-axes: a tensor written for another frame's axes."""

from __future__ import annotations

import math

import numpy as np
import pytest
from kit import EXAMPLES
from kit.moments import cylinder_moments
from kit.urdf import collision, cylinder, inertial, moving

from inertia_kit.lint.runner import Selection, lint_file
from inertia_kit.physics.frames import rpy_matrix


def rod(inertial_rpy="0 0 0", shape_rpy=f"0 {math.pi / 2} 0"):
    """A 0.3 m rod along the link's x (``shape_rpy``), its tensor written in ``inertial_rpy``."""
    mass, radius, length = 1.0, 0.02, 0.3
    transverse, _, axial = cylinder_moments(mass, radius, length)
    written = inertial(mass, transverse, transverse, axial, xyz="0.15 0 0", rpy=inertial_rpy)
    shape = collision(cylinder(radius, length), xyz="0.15 0 0", rpy=shape_rpy)
    return moving(written + shape), transverse, axial


def test_cylinder_formula_for_z_on_a_rod_along_x(lint):
    text, transverse, axial = rod()
    findings = lint(text)
    assert [f.code for f in findings] == ["IN062"]
    finding = findings[0]
    assert (
        finding.message
        == "link `arm`: inertia written in the collision cylinder's axes, not the link's"
    )
    assert "axis of least inertia along z" in finding.detail and "along x" in finding.detail
    assert "the collision cylinder's own axes" in finding.detail
    assert (
        finding.expected["frame"]
        == 'the collision cylinder\'s own axes (<origin rpy="0 1.5708 0">)'
    )
    assert finding.expected["ixx"] == pytest.approx(axial)
    assert finding.expected["iyy"] == pytest.approx(transverse)
    assert finding.expected["izz"] == pytest.approx(transverse)
    np.testing.assert_allclose(
        rpy_matrix(finding.expected["rpy"]), rpy_matrix([0, math.pi / 2, 0]), atol=1e-12
    )
    assert '<inertial><origin rpy="0 1.5708 0"/>' in finding.help


def test_the_suggested_rpy_is_quiet(lint):
    text, _, _ = rod(inertial_rpy=f"0 {math.pi / 2} 0")
    assert lint(text) == []


def test_a_rounded_quarter_turn_names_the_same_axes(lint):
    text, _, axial = rod(shape_rpy="0 1.5708 0")
    findings = lint(text, "IN062")
    assert len(findings) == 1 and findings[0].expected["ixx"] == pytest.approx(axial)
    assert findings[0].expected["ixz"] == 0.0  # snapped to the exact permutation


def test_seed_simple_arm_links_are_written_for_other_axes_and_the_base_is_quiet():
    """The issue's acceptance: link_1 and link_2 explained; base_link correct."""
    result = lint_file(EXAMPLES / "simple_arm/urdf/simple_arm.urdf.xacro", Selection())
    assert result.error is None
    forensic = [f for f in result.findings if f.code == "IN062"]
    assert sorted(f.link for f in forensic) == ["link_1", "link_2"]
    assert not [f for f in result.findings if f.code == "IN020"]
    base = {f.code for f in result.findings if f.link == "base_link"}
    assert not base & {"IN020", "IN060", "IN061", "IN062", "IN063", "IN064"}
    transverse, _, axial = cylinder_moments(1.0, 0.02, 0.3)
    for finding in forensic:
        assert finding.expected["ixx"] == pytest.approx(axial)
        assert finding.expected["izz"] == pytest.approx(transverse)
        assert "written for other axes" in finding.detail
        assert finding.message.endswith(
            ": inertia written in the collision cylinder's axes, not the link's"
        )


def test_the_message_is_one_short_line_and_the_detail_has_the_numbers(lint):
    """The simple arm's rod (issue 21, item 5): whose axes the values are written in, in one
    line; the axis they put the least inertia along, the declared and the link-axes tensors,
    the fit and the hard bound in the detail."""
    result = lint_file(EXAMPLES / "simple_arm/urdf/simple_arm.urdf.xacro", Selection())
    (finding, *_) = [f for f in result.findings if f.code == "IN062" and f.link == "link_1"]
    assert len(finding.message) <= 100
    assert finding.detail == (
        "the declared inertia is written for other axes: the collision cylinder's own axes "
        '(<origin rpy="0 1.5708 0">); '
        "it puts the axis of least inertia along z, the collision cylinder (r = 0.02 m, "
        "l = 0.3 m) has it along x: declared ixx 0.0076, iyy 0.0076, izz 0.0002; in the link "
        "axes it is ixx 0.0002, iyy 0.0076, izz 0.0076, the geometry's within 0.01 %; as written "
        "no mass inside the geometry can have it (IN023)"
    )


def test_axes_of_no_shape_are_named_by_the_axis_they_put_the_least_inertia_along(lint):
    """A rod along z, unturned, its formula written for x: an axis permutation, no shape's."""
    mass, radius, length = 1.0, 0.02, 0.3
    transverse, _, axial = cylinder_moments(mass, radius, length)
    text = moving(
        inertial(mass, axial, transverse, transverse, xyz="0.15 0 0")
        + collision(cylinder(radius, length), xyz="0.15 0 0")
    )
    (finding,) = lint(text, "IN062")
    assert finding.message == (
        "link `arm`: inertia written in other axes: least inertia along x, not z"
    )
    assert "it puts the axis of least inertia along x" in finding.detail


def real_rod():
    """:func:`rod` as a real part: its moments 1.5 and 0.7 times the uniform solid's (a CAD
    link scatters so around its shapes), still written for the cylinder's own axes."""
    mass, radius, length = 1.0, 0.02, 0.3
    transverse, _, axial = cylinder_moments(mass, radius, length)
    written = inertial(mass, 1.5 * transverse, 1.5 * transverse, 0.7 * axial, xyz="0.15 0 0")
    shape = collision(cylinder(radius, length), xyz="0.15 0 0", rpy=f"0 {math.pi / 2} 0")
    return moving(written + shape)


def test_a_real_part_written_for_other_axes_is_a_likely_slip(lint, tmp_path):
    """No exact fit (the part is not the uniform solid of its shape), but turned to the link
    axes it lands where real parts do: named, as likely; its fix unsafe, and fill's
    ``--fix invalid`` leaves it (``--fix all`` recomputes the link)."""
    from inertia_kit.fill.plan import plan_fill
    from inertia_kit.lint.findings import Safety

    findings = lint(real_rod())
    assert [f.code for f in findings] == ["IN062"]
    finding = findings[0]
    assert finding.expected["fit"] == "likely"
    assert "within a factor of" in finding.detail
    assert finding.message == (
        "link `arm`: likely inertia written in the collision cylinder's axes, not the link's"
    )
    assert "likely, not proven" in finding.help
    path = tmp_path / "rod.urdf"
    path.write_text(real_rod())
    result = lint_file(path, Selection(select=("IN062",)))
    assert result.findings[0].fix is not None and result.findings[0].fix.safety is Safety.UNSAFE
    assert [f.link for f in plan_fill(path, fix="invalid").changed_links] == []
    assert [f.link for f in plan_fill(path, fix="all").changed_links] == ["arm"]
