"""IN020 inertia-geometry-mismatch: expected numbers from closed forms computed here."""

from __future__ import annotations

import math

import pytest
from kit import EXAMPLES
from kit.meshes import box_triangles, write_ascii_stl
from kit.moments import box_moments, cylinder_moments
from kit.urdf import box, collision, cylinder, inertial, mesh, moving, visual

from inertia_kit.lint.findings import Severity
from inertia_kit.lint.runner import Selection, lint_file

BOX = collision(box(0.4, 0.2, 0.1))


def test_uniform_tensor_is_quiet(lint):
    ixx, iyy, izz = box_moments(2.0, (0.4, 0.2, 0.1))
    assert lint(moving(BOX + inertial(2.0, ixx, iyy, izz)), "IN020") == []


def test_within_the_factors_is_quiet(lint):
    ixx, iyy, izz = box_moments(2.0, (0.4, 0.2, 0.1))
    # a hollow-ish part (×2) and a dense core (×0.25) are within the defaults 2.5 and 5
    assert lint(moving(BOX + inertial(2.0, 2 * ixx, 2 * iyy, 2 * izz)), "IN020") == []
    assert lint(moving(BOX + inertial(2.0, ixx / 4, iyy / 4, izz / 4)), "IN020") == []


def test_tensor_three_times_too_large_fires_with_the_expected_value(lint):
    ixx, iyy, izz = box_moments(2.0, (0.4, 0.2, 0.1))
    findings = lint(moving(BOX + inertial(2.0, ixx, 3 * iyy, izz)), "IN020")
    assert [f.code for f in findings] == ["IN020"]
    finding = findings[0]
    assert finding.severity == Severity.WARNING  # within the hard bound (3 × uniform for a box)
    assert finding.link == "arm"
    assert finding.message == "link `arm`: iyy 3 times its collision box's"
    assert "iyy = " in finding.detail and "collision box (0.4 × 0.2 × 0.1 m)" in finding.detail
    assert finding.expected["iyy"] == pytest.approx(iyy)
    assert finding.expected["ixx"] == pytest.approx(ixx)
    assert finding.expected["ratio"] == pytest.approx(3.0)


def test_tensor_far_too_small_fires(lint):
    ixx, iyy, izz = box_moments(2.0, (0.4, 0.2, 0.1))
    findings = lint(moving(BOX + inertial(2.0, ixx / 10, iyy, izz)), "IN020")
    assert len(findings) == 1 and "ixx 1/10 of its collision box's" in findings[0].message
    assert "(1/10 of that)" in findings[0].detail


def test_factor_options(lint):
    ixx, iyy, izz = box_moments(2.0, (0.4, 0.2, 0.1))
    text = moving(BOX + inertial(2.0, 2 * ixx, iyy, izz))
    assert lint(text, "IN020") == []
    assert len(lint(text, "IN020", options={"IN020": {"factor": 1.5}})) == 1
    small = moving(BOX + inertial(2.0, ixx / 3, iyy, izz))
    assert lint(small, "IN020") == []
    assert len(lint(small, "IN020", options={"IN020": {"factor_below": 2.0}})) == 1


def test_rotated_cylinder_with_a_tensor_for_z_fires_in_link_axes(lint):
    """The seed simple arm: a cylinder along x, the tensor written for a cylinder along z."""
    mass, radius, length = 1.0, 0.02, 0.3
    transverse, _, axial = cylinder_moments(mass, radius, length)
    along_x = collision(cylinder(radius, length), xyz=f"{length / 2} 0 0", rpy=f"0 {math.pi / 2} 0")
    body = along_x + inertial(
        mass, transverse, transverse, axial, xyz=f"{length / 2} 0 0", rpy="0 0 0"
    )
    findings = lint(moving(body), "IN020")
    assert len(findings) == 1
    finding = findings[0]
    assert "likely in other axes (IN062)" in finding.message
    assert "other axes" in finding.detail
    # about the link x axis the cylinder has its axial moment m r²/2
    assert finding.expected["ixx"] == pytest.approx(axial)
    assert finding.expected["izz"] == pytest.approx(transverse)
    # the same eigenvalues, rotated with <inertial><origin rpy>, are right
    fixed = body.replace(
        f'<origin xyz="{length / 2} 0 0" rpy="0 0 0"/>',
        f'<origin xyz="{length / 2} 0 0" rpy="0 {math.pi / 2} 0"/>',
    )
    assert lint(moving(fixed), "IN020") == []


def test_tensor_about_the_link_origin_is_recognised_below_the_factor(lint):
    """The mrm pattern: the right tensor shifted to the link origin (×1.91 on ixx, iyy)."""
    mass, radius, length = 157.633, 0.35, 0.4
    transverse, _, axial = cylinder_moments(mass, radius, length)
    shifted = transverse + mass * 0.2**2
    body = collision(cylinder(radius, length), xyz="0 0 0.2") + inertial(
        mass, shifted, shifted, axial, xyz="0 0 0.2"
    )
    findings = lint(moving(body), "IN020")
    assert len(findings) == 1
    assert "likely about another point (IN060)" in findings[0].message
    assert "about the link origin" in findings[0].detail
    assert findings[0].expected["ixx"] == pytest.approx(transverse)
    assert transverse == pytest.approx(6.929, abs=1e-3)


def test_error_when_also_beyond_the_hard_bound(lint):
    # ixx of a cylinder about its own axis can reach m r² at most (a ring at the rim)
    mass, radius, length = 1.0, 0.05, 0.05
    body = collision(cylinder(radius, length)) + inertial(mass, 1.0, 1.0, 1.0)
    findings = lint(moving(body), "IN020")
    assert len(findings) == 1 and findings[0].severity == Severity.ERROR
    assert "IN023" in findings[0].detail


def test_beyond_the_bound_only_within_rounding_or_on_visual_geometry_is_a_warning(lint):
    """A tensor far from a cylinder's and 2.3 % beyond what its mass can have inside it: an
    error only when no rounding of the written numbers explains that, on collision geometry."""
    along_x = "0 1.5707963267948966 0"
    # iyy 2.6 times the uniform 3.02e-05; along the axle (x) ∫x² dm = (iyy + izz - ixx)/2 =
    # 8.6e-06, within the 0.089 × 0.01² = 8.9e-06 the cylinder's 0.02 m allow (IN023)
    far = inertial(0.089, 0.000111842, 8e-05, 4.9e-05)
    rounded = cylinder(0.035, 0.02)
    (finding,) = lint(moving(collision(rounded, rpy=along_x) + far), "IN020")
    assert finding.severity == Severity.WARNING
    assert (
        "; beyond what 0.089 kg inside the link's geometry can have, but 2.3% over is within "
        "what rounding of the written cylinder radius 0.035 m and mass 0.089 kg can explain"
    ) in finding.detail
    (finding,) = lint(moving(visual(rounded, rpy=along_x) + far), "IN020")
    assert finding.severity == Severity.WARNING
    assert "but its only geometry is visual, often a schematic stand-in" in finding.detail
    precise = cylinder("0.0349999", "0.0200001")
    exact = inertial("0.0890001", 0.000111842, 8e-05, 4.9e-05)
    (finding,) = lint(moving(collision(precise, rpy=along_x) + exact), "IN020")
    assert finding.severity == Severity.ERROR
    assert "no 0.089 kg inside the link's geometry can have it (IN023)" in finding.detail


def test_overlapping_collision_shapes_are_a_union(lint):
    """Two boxes overlapping by half count the shared volume once: 0.6 × 0.2 × 0.1 overall."""
    shapes = collision(box(0.4, 0.2, 0.1), xyz="-0.1 0 0") + collision(
        box(0.4, 0.2, 0.1), xyz="0.1 0 0"
    )
    ixx, iyy, izz = box_moments(3.0, (0.6, 0.2, 0.1))
    assert lint(moving(shapes + inertial(3.0, ixx, iyy, izz)), "IN020") == []
    findings = lint(moving(shapes + inertial(3.0, ixx, 3 * iyy, izz)), "IN020")
    assert len(findings) == 1 and findings[0].expected["iyy"] == pytest.approx(iyy, rel=1e-4)
    assert "its 2 collision shapes'" in findings[0].message
    assert "2 collision shapes (box (0.4 × 0.2 × 0.1 m); box" in findings[0].detail


def test_a_tensor_matching_the_visual_geometry_is_quiet(lint):
    """A crude collision sphere around a box-shaped visual: the visual basis clears it."""
    ixx, iyy, izz = box_moments(2.0, (0.4, 0.2, 0.1))
    body = (
        visual(box(0.4, 0.2, 0.1)) + collision(cylinder(0.02, 0.1)) + inertial(2.0, ixx, iyy, izz)
    )
    assert lint(moving(body), "IN020") == []


def test_visual_only_link_uses_the_visual_geometry(lint):
    ixx, iyy, izz = box_moments(2.0, (0.4, 0.2, 0.1))
    body = visual(box(0.4, 0.2, 0.1))
    findings = lint(moving(body + inertial(2.0, ixx, iyy, 4 * izz)), "IN020")
    assert len(findings) == 1 and "its visual box's" in findings[0].message


def test_mesh_with_scale(lint, tmp_path):
    """A 100 mm cube in millimetres, scaled by 0.001: the tensor of a 0.1 m cube."""
    write_ascii_stl(tmp_path / "cube.stl", box_triangles((100, 100, 100)))
    moment, _, _ = box_moments(1.0, (0.1, 0.1, 0.1))
    cube = collision(mesh("cube.stl", scale="0.001 0.001 0.001"))
    good = inertial(1.0, moment, moment, moment, xyz="0.05 0.05 0.05")
    assert lint(moving(cube + good), "IN020") == []
    bad = inertial(1.0, 3 * moment, moment, moment, xyz="0.05 0.05 0.05")
    findings = lint(moving(cube + bad), "IN020")
    assert len(findings) == 1 and findings[0].expected["ixx"] == pytest.approx(moment)


def test_links_without_inertial_or_geometry_are_not_its_business(lint):
    assert lint(moving(BOX), "IN020") == []
    assert lint(moving(inertial(1.0, 1.0, 1.0, 1.0)), "IN020") == []
    broken = moving(BOX + inertial(1.0, 1.0, 1.0, -1.0))  # not positive definite: IN010's
    assert lint(broken, "IN020") == []


def _seed(path: str, packages: tuple[str, ...] = ()) -> list:
    result = lint_file(EXAMPLES / path, Selection(select=("IN020",)), package_paths=packages)
    assert result.error is None
    return result.findings


def test_seed_mrm_links_declare_tensors_about_the_link_origin():
    findings = _seed("mrm_description/urdf/mrm.xacro", (str(EXAMPLES),))
    assert sorted(f.link for f in findings) == [f"link_0{i}" for i in range(1, 6)]
    link_01 = next(f for f in findings if f.link == "link_01")
    transverse, _, _ = cylinder_moments(157.633, 0.35, 0.4)
    assert link_01.expected["ixx"] == pytest.approx(transverse)
    assert round(link_01.expected["ixx"], 3) == 6.929


def test_seed_simple_arm_and_robot1_fire_and_pan_tilt_is_quiet():
    assert sorted(f.link for f in _seed("simple_arm/urdf/simple_arm.urdf.xacro")) == [
        "link_1",
        "link_2",
    ]
    robot1 = _seed("robot1/urdf/robot1_base.xacro")
    assert {f.link for f in robot1} >= {"base_link", "wheel_1", "wheel_2"}
    assert _seed("pan_tilt_description/urdf/pan_tilt.urdf", (str(EXAMPLES),)) == []


def test_the_message_is_one_short_line_and_the_detail_keeps_the_basis():
    """The seed arm's mrm links: the ratio and the slip's rule in the message; the moments, the
    cylinder's dimensions, the slip's wording and the bound in the detail."""
    findings = _seed("mrm_description/urdf/mrm.xacro", (str(EXAMPLES),))
    link_01 = next(f for f in findings if f.link == "link_01")
    assert len(link_01.message) <= 100
    assert link_01.message.startswith("link `link_01`: ") and "(IN060)" in link_01.message
    assert "collision cylinder (r = 0.35 m, l = 0.4 m) with the declared" in link_01.detail
    assert "6.929" in link_01.detail and "about the link origin" in link_01.detail
