"""IN032 mesh-not-watertight: open or inconsistently wound meshes where volume matters."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from kit.urdf import collision, inertial, mesh, moving, visual

from inertia_kit.lint.findings import Severity

INERTIAL = inertial(1, 0.00167)


def part(body: str, kind: str = "revolute") -> str:
    return moving(body, name="part", kind=kind)


@pytest.fixture
def meshes(tmp_path):
    box = trimesh.creation.box(extents=(0.1, 0.1, 0.1))
    box.export(tmp_path / "closed.stl")
    open_box = box.copy()
    open_box.update_faces(np.arange(len(box.faces)) < len(box.faces) - 2)  # lid removed
    open_box.export(tmp_path / "open.stl")
    # a closed box with one triangle turned inward
    faces = box.faces.copy()
    faces[0] = faces[0][::-1]
    trimesh.Trimesh(box.vertices, faces, process=False).export(tmp_path / "flipped.stl")
    return tmp_path


def test_closed_collision_mesh_is_quiet(lint, meshes):
    assert lint(part(collision(mesh("closed.stl")) + INERTIAL), "IN032") == []


def test_open_collision_mesh_warns_with_method_and_error_bound(lint, meshes):
    findings = lint(part(collision(mesh("open.stl")) + INERTIAL), "IN032")
    assert len(findings) == 1
    finding = findings[0]
    assert finding.severity == Severity.WARNING and finding.link == "part"
    assert finding.message == (
        "link `part`: collision mesh `open.stl` is open, hull volume 16.7% off"
    )
    assert "collision mesh `open.stl` is not closed (10 triangles)" in finding.detail
    assert "convex hull" in finding.detail
    assert finding.expected["method"] == "convex-hull"
    # the lid's pyramid about the centre is 1/6 of the box
    assert finding.expected["volume_error"] == pytest.approx(1 / 6, rel=1e-6)
    assert "differs from the open surface's by 16.7%" in finding.detail


def test_open_visual_next_to_collision_geometry_is_quiet(lint, meshes):
    body = visual(mesh("open.stl")) + collision(mesh("closed.stl")) + INERTIAL
    assert lint(part(body), "IN032") == []


def test_open_visual_mass_comes_from_warns(lint, meshes):
    findings = lint(part(visual(mesh("open.stl")) + INERTIAL), "IN032")
    assert len(findings) == 1 and "visual mesh `open.stl`" in findings[0].message


def test_open_visual_of_a_massless_fixed_link_is_quiet(lint, meshes):
    assert lint(part(visual(mesh("open.stl")), kind="fixed"), "IN032") == []


def test_tolerance_option(lint, meshes):
    text = part(collision(mesh("open.stl")) + INERTIAL)
    assert lint(text, "IN032", options={"IN032": {"tolerance": 0.2}}) == []


def test_inconsistent_winding_warns(lint, meshes):
    findings = lint(part(collision(mesh("flipped.stl")) + INERTIAL), "IN032")
    assert len(findings) == 1
    assert findings[0].message == (
        "link `part`: collision mesh `flipped.stl` is closed but wound inconsistently"
    )
    assert "computed after repairing the winding" in findings[0].detail
    assert findings[0].expected["method"] == "repaired"


def test_repaired_option(lint, meshes):
    text = part(collision(mesh("flipped.stl")) + INERTIAL)
    assert lint(text, "IN032", options={"IN032": {"repaired": False}}) == []


def test_the_message_is_one_short_line_and_the_detail_keeps_the_basis(lint, meshes):
    """The mesh and the hull's volume error in the message; the triangle count, the method
    and the hull's volume in the detail."""
    (finding,) = lint(part(collision(mesh("open.stl")) + INERTIAL), "IN032")
    assert len(finding.message) <= 100
    assert finding.detail == (
        "collision mesh `open.stl` is not closed (10 triangles): its mass properties are those "
        "of its convex hull, whose volume (0.001 m³) differs from the open surface's by 16.7%"
    )
