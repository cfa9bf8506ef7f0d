"""IN034 mesh-unreadable: corrupt files and formats that cannot be read."""

from __future__ import annotations

import struct

from kit.urdf import collision, link, mesh, robot

from inertia_kit.lint.findings import Severity


def part(name: str) -> str:
    """A lone link `part` colliding as the mesh file ``name``."""
    return robot(link("part", collision(mesh(name))))


def test_truncated_binary_stl_is_an_error(lint, tmp_path):
    # a header announcing 100 triangles, and only one
    data = b"\0" * 80 + struct.pack("<I", 100) + b"\0" * 50
    (tmp_path / "cut.stl").write_bytes(data)
    findings = lint(part("cut.stl"), "IN034")
    assert len(findings) == 1
    finding = findings[0]
    assert finding.severity == Severity.ERROR and finding.link == "part"
    assert finding.message == "link `part`: collision mesh `cut.stl` cannot be read"
    assert finding.detail.startswith("collision mesh `cut.stl` cannot be read: ")
    assert "re-export" in finding.help


def test_non_finite_obj_is_an_error(lint, tmp_path):
    (tmp_path / "nan.obj").write_text("v nan nan nan\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n")
    findings = lint(part("nan.obj"), "IN034")
    assert len(findings) == 1 and "non-finite" in findings[0].detail


def test_unsupported_format_is_a_warning(lint, tmp_path):
    (tmp_path / "part.vtk").write_text("# vtk DataFile Version 3.0\n")
    findings = lint(part("part.vtk"), "IN034")
    assert len(findings) == 1
    assert findings[0].severity == Severity.WARNING
    assert findings[0].message == (
        "link `part`: collision mesh `part.vtk` is in a format inertia-kit does not read"
    )
    assert "in a format inertia-kit does not read (`.vtk`" in findings[0].detail


def test_readable_mesh_is_quiet(lint, tmp_path):
    (tmp_path / "ok.obj").write_text(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
    )
    assert lint(part("ok.obj"), "IN034") == []


def test_missing_and_empty_meshes_belong_to_other_rules(lint, tmp_path):
    (tmp_path / "empty.stl").write_bytes(b"")
    assert lint(part("empty.stl"), "IN034") == []  # IN026
    assert lint(part("missing.stl"), "IN034") == []  # IN030


def test_the_message_is_one_short_line_and_the_detail_keeps_the_basis(lint, tmp_path):
    """The mesh's file name in the message; its whole URI and the reader's reason in the
    detail."""
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "nan.obj").write_text("v nan nan nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    (finding,) = lint(part("meshes/nan.obj"), "IN034")
    assert finding.message == "link `part`: collision mesh `nan.obj` cannot be read"
    assert len(finding.message) <= 100
    assert finding.detail.startswith("collision mesh `meshes/nan.obj` cannot be read: ")
    assert "non-finite" in finding.detail
