"""IN026 degenerate-geometry: zero or negative sizes, meshes that enclose no volume."""

from __future__ import annotations

from kit import moving

from inertia_kit.lint.findings import Severity

INERTIAL = (
    '<inertial><mass value="1"/>'
    '<inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>'
)


def arm(body: str) -> str:
    return moving(body, name="arm")


def collision(geometry: str) -> str:
    return f"<collision><geometry>{geometry}</geometry></collision>"


def visual(geometry: str) -> str:
    return f"<visual><geometry>{geometry}</geometry></visual>"


def test_positive_sizes_are_quiet(lint):
    assert lint(arm(collision('<box size="0.1 0.1 0.1"/>') + INERTIAL), "IN026") == []


def test_zero_and_negative_sizes_are_errors(lint):
    for geometry in (
        '<box size="0.1 0 0.1"/>',
        '<cylinder radius="-0.05" length="0.2"/>',
        '<sphere radius="0"/>',
        '<capsule radius="0.05" length="-0.1"/>',
    ):
        findings = lint(arm(collision(geometry) + INERTIAL), "IN026")
        assert len(findings) == 1, geometry
        assert findings[0].severity == Severity.ERROR
        assert "zero or negative" in findings[0].message


def test_zero_mesh_scale_is_degenerate(lint, tmp_path):
    (tmp_path / "part.stl").write_text("solid s\nendsolid s\n")
    findings = lint(arm(collision('<mesh filename="part.stl" scale="1 0 1"/>') + INERTIAL), "IN026")
    assert len(findings) == 1 and "zero factor" in findings[0].message


def flat_stl(path):
    # a single square in the plane z = 0: no volume
    path.write_text(
        "solid flat\n"
        "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\n"
        "endloop\nendfacet\n"
        "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\nvertex 0 1 0\n"
        "endloop\nendfacet\nendsolid flat\n"
    )


def test_empty_collision_mesh_is_an_error(lint, tmp_path):
    flat_stl(tmp_path / "flat.stl")
    findings = lint(arm(collision('<mesh filename="flat.stl"/>') + INERTIAL), "IN026")
    assert len(findings) == 1 and findings[0].severity == Severity.ERROR


def test_flat_visual_mesh_is_fine_when_the_link_collides_with_something_else(lint, tmp_path):
    flat_stl(tmp_path / "flat.stl")
    body = visual('<mesh filename="flat.stl"/>') + collision('<box size="1 1 0.01"/>') + INERTIAL
    assert lint(arm(body), "IN026") == []
    # ... but not when the visual is all the geometry the link's mass has
    findings = lint(arm(visual('<mesh filename="flat.stl"/>') + INERTIAL), "IN026")
    assert len(findings) == 1 and findings[0].severity == Severity.ERROR


def test_zero_size_visual_of_a_colliding_link_is_a_warning(lint):
    body = visual('<sphere radius="0"/>') + collision('<sphere radius="0.03"/>') + INERTIAL
    findings = lint(arm(body), "IN026")
    assert len(findings) == 1 and findings[0].severity == Severity.WARNING


def test_other_problems_belong_to_other_rules(lint):
    assert lint(arm(collision('<mesh filename="missing.stl"/>') + INERTIAL), "IN026") == []
    assert lint(arm(collision('<box size="0.1 abc 0.1"/>') + INERTIAL), "IN026") == []
