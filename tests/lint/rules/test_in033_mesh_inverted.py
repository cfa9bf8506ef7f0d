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
        assert "is wound inside-out: its signed volume is -0.006 m³" in finding.message
        assert "shell" not in finding.message
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
    assert findings and all("one shell of several is inside-out" in f.message for f in findings)
