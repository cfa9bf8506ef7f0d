"""IN026 degenerate-geometry: zero or negative sizes, meshes that enclose no volume."""

from __future__ import annotations

import pytest
from kit.meshes import square_triangles, write_ascii_stl
from kit.urdf import box, collision, cylinder, inertial, mesh, moving, sphere, visual

from inertia_kit.lint.findings import Severity

INERTIAL = inertial(1, 0.001)


def test_positive_sizes_are_quiet(lint):
    assert lint(moving(collision(box(0.1, 0.1, 0.1)) + INERTIAL), "IN026") == []


def test_zero_and_negative_sizes_are_errors(lint):
    for geometry in (
        box(0.1, 0, 0.1),
        cylinder(-0.05, 0.2),
        sphere(0),
        '<capsule radius="0.05" length="-0.1"/>',
    ):
        findings = lint(moving(collision(geometry) + INERTIAL), "IN026")
        assert len(findings) == 1, geometry
        assert findings[0].severity == Severity.ERROR
        assert "zero or negative" in findings[0].detail


def test_zero_mesh_scale_is_degenerate(lint, tmp_path):
    (tmp_path / "part.stl").write_text("solid s\nendsolid s\n")
    findings = lint(moving(collision(mesh("part.stl", scale="1 0 1")) + INERTIAL), "IN026")
    assert len(findings) == 1 and "zero factor" in findings[0].detail
    assert findings[0].message == "link `arm`: its collision mesh `part.stl` is degenerate"


def test_empty_collision_mesh_is_an_error(lint, tmp_path):
    write_ascii_stl(tmp_path / "flat.stl", square_triangles())
    findings = lint(moving(collision(mesh("flat.stl")) + INERTIAL), "IN026")
    assert len(findings) == 1 and findings[0].severity == Severity.ERROR


def test_flat_visual_mesh_is_fine_when_the_link_collides_with_something_else(lint, tmp_path):
    write_ascii_stl(tmp_path / "flat.stl", square_triangles())
    body = visual(mesh("flat.stl")) + collision(box(1, 1, 0.01)) + INERTIAL
    assert lint(moving(body), "IN026") == []
    # ... but not when the visual is all the geometry the link's mass has
    findings = lint(moving(visual(mesh("flat.stl")) + INERTIAL), "IN026")
    assert len(findings) == 1 and findings[0].severity == Severity.ERROR


def test_zero_size_visual_of_a_colliding_link_is_a_warning(lint):
    body = visual(sphere(0)) + collision(sphere(0.03)) + INERTIAL
    findings = lint(moving(body), "IN026")
    assert len(findings) == 1 and findings[0].severity == Severity.WARNING


def test_other_problems_belong_to_other_rules(lint):
    assert lint(moving(collision(mesh("missing.stl")) + INERTIAL), "IN026") == []
    assert lint(moving(collision(box(0.1, "abc", 0.1)) + INERTIAL), "IN026") == []


def test_thinner_than_an_atom_is_degenerate(lint):
    """Below 1e-10 m (physics/numbers.py): no solid; Drake's 1e-7 m contact spheres pass."""
    findings = lint(moving(collision(cylinder(0.1, "1e-11")) + INERTIAL), "IN026")
    (finding,) = findings
    assert "a dimension of 1e-11 m is below 1e-10 m, the size of an atom" in finding.detail
    for geometry in (sphere("1e-7"), box("1e-10", 1, 1)):
        assert lint(moving(collision(geometry) + INERTIAL), "IN026") == [], geometry


def test_a_mesh_thinner_than_an_atom_is_empty(lint, tmp_path):
    from kit.meshes import box_triangles, write_binary_stl

    write_binary_stl(tmp_path / "speck.stl", box_triangles([1, 1, 1]))
    for scale in ("1e-11 1 1", "1 1e-11 1e-9"):
        body = collision(mesh("speck.stl", scale=scale)) + INERTIAL
        (finding,) = lint(moving(body), "IN026")
        assert "it is 1e-11 m thin, thinner than an atom (1e-10 m): no solid" in finding.detail


def test_a_mesh_whose_moments_overflow_is_degenerate(lint, tmp_path):
    """Float32 STL coordinates of 1e38 are usable, scaled by 1e30 their moments overflow."""
    from kit.meshes import box_triangles, write_binary_stl

    write_binary_stl(tmp_path / "huge.stl", box_triangles([1e38, 1e38, 1e38]))
    (finding,) = lint(
        moving(collision(mesh("huge.stl", scale="1e30 1e30 1e30")) + INERTIAL), "IN026"
    )
    assert "its volume or moments overflow double precision" in finding.detail


@pytest.mark.parametrize(
    "shape",
    [box(0, 0, 0), box(0.1, 0, 0.1), cylinder(0, 0.1), cylinder(0.1, 0)],
    ids=["box", "flat-box", "cylinder-radius", "cylinder-length"],
)
def test_a_zero_visual_drake_refuses_is_an_error(lint, shape):
    # Drake 1.51 refuses the model at Box()/Cylinder() with a dimension ≤ 0, visual or not
    body = visual(shape) + collision(sphere(0.03)) + INERTIAL
    (finding,) = lint(moving(body), "IN026")
    assert finding.severity == Severity.ERROR


def test_a_zero_size_virtual_link_stays_an_error_on_a_heavy_body(lint):
    # Upkie's virtual links: a 1 g frame with a `<box size="0 0 0"/>` visual welded to a body:
    # a negligible share of its mass, but Drake refuses the model at that box
    frame = '<link name="imu"><visual><geometry><box size="0 0 0"/></geometry></visual>'
    frame += inertial(0.001, 0) + "</link>"
    weld = '<joint name="imu_fix" type="fixed"><parent link="arm"/><child link="imu"/></joint>'
    findings = lint(moving(INERTIAL + collision(box(0.1, 0.1, 0.1)), weld + frame), "IN026")
    assert [(f.link, f.severity) for f in findings] == [("imu", Severity.ERROR)]
    assert "it adds" not in findings[0].message + (findings[0].detail or "")


def test_the_message_is_one_short_line_and_the_detail_has_the_basis(lint):
    (finding,) = lint(moving(collision(box(0.1, 0, 0.1)) + INERTIAL), "IN026")
    assert finding.message == "link `arm`: its collision box (0.1 × 0 × 0.1 m) is degenerate"
    assert len(finding.message) <= 100
    assert finding.detail == (
        "its collision box (0.1 × 0 × 0.1 m): a dimension is zero or negative"
    )
