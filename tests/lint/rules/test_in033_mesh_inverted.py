"""IN033 mesh-inverted: closed meshes wound inside-out."""

from __future__ import annotations

import pytest
import trimesh
from kit.urdf import collision, link, mesh, robot, visual

from inertia_kit.lint.findings import Severity


def part(name: str, scale: str = "1 1 1") -> str:
    """A lone link `part` whose visual and collision are the mesh file ``name``."""
    return robot(link("part", visual(mesh(name, scale)), collision(mesh(name, scale))))


def test_inside_out_mesh_is_an_error_for_each_shape(lint, tmp_path):
    box = trimesh.creation.box(extents=(0.1, 0.2, 0.3))
    box.invert()
    box.export(tmp_path / "inverted.stl")
    findings = lint(part("inverted.stl"), "IN033")
    assert len(findings) == 2
    assert {f.message.split()[2] for f in findings} == {"visual", "collision"}
    for finding in findings:
        assert finding.severity == Severity.ERROR
        assert finding.message.endswith("mesh `inverted.stl` is inside-out, volume -0.006 m³")
        assert len(finding.message) <= 100
        assert "is wound inside-out: its signed volume is -0.006 m³" in finding.detail
        assert "shell" not in finding.detail
        assert finding.expected["signed_volume"] == pytest.approx(-0.006, rel=1e-6)


def test_outward_mesh_is_quiet(lint, tmp_path):
    trimesh.creation.box(extents=(0.1, 0.2, 0.3)).export(tmp_path / "box.stl")
    assert lint(part("box.stl"), "IN033") == []


def test_mirroring_scale_is_not_an_inversion(lint, tmp_path):
    trimesh.creation.box(extents=(0.1, 0.2, 0.3)).export(tmp_path / "box.stl")
    assert lint(part("box.stl", scale="-1 1 1"), "IN033") == []


def test_small_signed_volume_suggests_an_inverted_shell(lint, tmp_path):
    # an outer shell and a larger inside-out shell overlapping it: the sum is small and negative
    outer = trimesh.creation.box(extents=(0.1, 0.1, 0.1))
    inner = trimesh.creation.box(extents=(0.1, 0.1, 0.1035))
    inner.invert()
    trimesh.util.concatenate([outer, inner]).export(tmp_path / "shells.stl")
    findings = lint(part("shells.stl"), "IN033")
    assert findings and all("one shell of several is inside-out" in f.detail for f in findings)


def test_the_message_is_one_short_line_and_the_detail_keeps_the_basis(lint, tmp_path):
    """The mesh and its signed volume in the message; the shells' explanation in the detail."""
    outer = trimesh.creation.box(extents=(0.1, 0.1, 0.1))
    inner = trimesh.creation.box(extents=(0.1, 0.1, 0.1035))
    inner.invert()
    trimesh.util.concatenate([outer, inner]).export(tmp_path / "shells.stl")
    findings = lint(part("shells.stl"), "IN033")
    assert findings
    for finding in findings:
        assert len(finding.message) <= 100 and "several" not in finding.message
        assert "is inside-out, volume -" in finding.message
        assert "is wound inside-out: its signed volume is -" in finding.detail
        assert "% of its bounding box: probably one shell of several" in finding.detail


def test_a_long_message_leaves_out_the_file_name_of_the_only_mesh_of_its_kind(lint, tmp_path):
    """Fourier's hand links name their meshes after themselves: with both names the message
    would run to 116 characters; the file name stays in the detail."""
    box = trimesh.creation.box(extents=(0.1, 0.2, 0.3))
    box.invert()
    box.export(tmp_path / "L_index_intermediate_link.STL")
    name = "L_index_intermediate_link"
    (finding,) = lint(robot(link(name, collision(mesh(f"{name}.STL")))), "IN033")
    assert finding.message == f"link `{name}`: collision mesh is inside-out, volume -0.006 m³"
    assert finding.detail.startswith(f"collision mesh `{name}.STL` is wound inside-out")
