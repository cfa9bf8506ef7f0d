"""
STL files written here, byte by byte, read back: binary and ASCII, and
every way a file can fail to be one.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import trimesh
from kit.meshes import box_triangles, write_ascii_stl, write_binary_stl
from kit.moments import box_tensor

from inertia_kit.errors import MeshError
from inertia_kit.physics import polyhedra, stl
from inertia_kit.physics.polyhedra import integrate
from inertia_kit.physics.stl import binary_triangle_count, read_stl

DENSITY = 1000.0
SIZE, LOW = (0.5, 0.25, 2.0), (0.25, -0.5, 1.0)  # dyadic: every vertex exact in float32


def sphere(subdivisions=4) -> np.ndarray:
    mesh = trimesh.creation.icosphere(subdivisions=subdivisions, radius=0.3)
    return mesh.triangles * (1.0, 0.7, 0.4) + (0.1, -0.2, 0.3)


def test_binary_box_matches_the_closed_form(tmp_path):
    size = (0.5, 0.25, 2.0)
    integrator = read_stl(write_binary_stl(tmp_path / "box.stl", box_triangles(size, LOW)))
    assert integrator.count == 12
    assert integrator.closed
    properties = integrator.moments.mass_properties(density=DENSITY)
    mass = DENSITY * math.prod(size)
    assert properties.mass == pytest.approx(mass, rel=1e-12)
    np.testing.assert_allclose(properties.com, (0.5, -0.375, 2.0), atol=1e-12)
    expected = box_tensor(mass, size)
    np.testing.assert_allclose(properties.inertia, expected, atol=1e-12 * mass)
    np.testing.assert_array_equal(integrator.bounds, [[0.25, -0.5, 1.0], [0.75, -0.25, 3.0]])


def test_binary_equals_integrating_its_triangles(tmp_path, monkeypatch):
    triangles = sphere(5).astype(np.float32)  # 20480 triangles
    monkeypatch.setattr(polyhedra, "CHUNK", 1000)  # chunks end mid-file
    integrator = read_stl(write_binary_stl(tmp_path / "sphere.stl", triangles))
    assert integrator.count == len(triangles)
    assert integrator.closed
    expected = integrate(triangles)
    np.testing.assert_array_equal(integrator.bounds, expected.bounds)
    mine = integrator.moments.mass_properties(density=DENSITY)
    theirs = expected.moments.mass_properties(density=DENSITY)
    assert mine.mass == pytest.approx(theirs.mass, rel=1e-12)
    np.testing.assert_allclose(mine.com, theirs.com, rtol=0, atol=1e-12)
    np.testing.assert_allclose(mine.inertia, theirs.inertia, rtol=1e-11, atol=0)


def test_binary_matches_trimesh(tmp_path):
    path = write_binary_stl(tmp_path / "sphere.stl", sphere(5))
    mine = read_stl(path).moments.mass_properties(density=DENSITY)
    reference = trimesh.load(path).mass_properties
    assert mine.mass == pytest.approx(DENSITY * reference.volume, rel=1e-9)
    np.testing.assert_allclose(mine.com, reference.center_mass, rtol=0, atol=1e-9 * 0.6)
    inertia = DENSITY * reference.inertia
    np.testing.assert_allclose(mine.inertia, inertia, rtol=0, atol=1e-9 * np.abs(inertia).max())


def test_binary_header_starting_with_solid_is_still_binary(tmp_path):
    path = write_binary_stl(
        tmp_path / "solidworks.stl", box_triangles(SIZE, LOW), header=b"solid part exported"
    )
    assert binary_triangle_count(path) == 12
    integrator = read_stl(path)
    assert integrator.count == 12 and integrator.closed


def test_ascii_equals_binary(tmp_path):
    triangles = sphere(3).astype(np.float32)
    ascii_ = read_stl(write_ascii_stl(tmp_path / "ascii.stl", triangles))
    binary = read_stl(write_binary_stl(tmp_path / "binary.stl", triangles))
    assert binary_triangle_count(tmp_path / "ascii.stl") is None
    assert ascii_.count == binary.count == len(triangles)
    assert ascii_.closed and binary.closed
    a, b = (i.moments.mass_properties(density=DENSITY) for i in (ascii_, binary))
    assert a.mass == pytest.approx(b.mass, rel=1e-12)
    np.testing.assert_allclose(a.com, b.com, rtol=0, atol=1e-12)
    np.testing.assert_allclose(a.inertia, b.inertia, rtol=1e-11, atol=0)


def test_open_surface_is_not_closed(tmp_path):
    integrator = read_stl(write_binary_stl(tmp_path / "open.stl", sphere(3)[1:]))
    assert not integrator.closed


@pytest.mark.parametrize("header", [b"binary STL", b"solid part exported"])
def test_binary_triangles_are_trimesh_s_bit_for_bit(tmp_path, header):
    # read here for an open surface, in place of trimesh: the same order and bits, signed zeros
    # and degenerate triangles kept (trimesh, process=False, merges and drops nothing)
    triangles = sphere(2).astype(np.float32)
    triangles[0, 0] = (-0.0, 0.0, -0.0)
    triangles[1] = triangles[1, 0]  # a triangle of one point
    path = write_binary_stl(tmp_path / "soup.stl", triangles[:-3], header=header)
    mine = stl.binary_triangles(path)
    theirs = trimesh.load(path, process=False).triangles
    assert mine.dtype == np.float64 and mine.shape == theirs.shape
    np.testing.assert_array_equal(mine.view(np.uint64), theirs.view(np.uint64))


def test_binary_triangles_of_an_ascii_stl_is_none(tmp_path):
    assert stl.binary_triangles(write_ascii_stl(tmp_path / "a.stl", sphere(1))) is None


def test_ascii_with_signed_zeros_is_closed(tmp_path):
    triangles = box_triangles((1.0, 2.0, 4.0), (-1.0, 0.0, -2.0))
    text = write_ascii_stl(tmp_path / "zeros.stl", triangles).read_text()
    lines = text.splitlines()
    # every other vertex line writes its zeros as -0.0
    lines = [
        line.replace(" 0.0", " -0.0") if "vertex" in line and i % 2 else line
        for i, line in enumerate(lines)
    ]
    path = tmp_path / "signed.stl"
    path.write_text("\n".join(lines))
    assert "-0.0" in path.read_text()
    integrator = read_stl(path)
    assert integrator.closed
    assert integrator.moments.volume == pytest.approx(8.0, rel=1e-12)


# --- files that are no STL, or no solid -------------------------------------------------


def assert_mesh_error(path: Path, kind: str, match: str) -> MeshError:
    with pytest.raises(MeshError, match=match) as caught:
        read_stl(path)
    error = caught.value
    assert error.kind == kind
    assert error.path == str(path)
    assert str(error).startswith(f"{path}: ")
    return error


def test_truncated_binary(tmp_path):
    path = write_binary_stl(tmp_path / "cut.stl", box_triangles(SIZE, LOW))
    path.write_bytes(path.read_bytes()[:-30])
    assert binary_triangle_count(path) is None
    assert_mesh_error(path, "unreadable", r"not a binary STL \(its header's count of 12 triangles")


def test_truncated_binary_with_solid_header(tmp_path):
    path = write_binary_stl(tmp_path / "cut.stl", box_triangles(SIZE, LOW), header=b"solid part")
    path.write_bytes(path.read_bytes()[:-30])
    assert_mesh_error(path, "unreadable", "needs 684 bytes, the file has 654")


def test_binary_cut_short_while_being_read(tmp_path, monkeypatch):
    # the size was right when the count was read, and is not by the time the records are
    path = write_binary_stl(tmp_path / "shrinking.stl", box_triangles(SIZE, LOW))
    monkeypatch.setattr(stl, "binary_triangle_count", lambda path: 13)
    assert_mesh_error(path, "unreadable", "changed while it was being read|cut short")


def test_not_an_stl(tmp_path):
    path = tmp_path / "picture.stl"
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + bytes(range(256)) * 4)
    assert_mesh_error(path, "unreadable", "not an STL file")
    text = tmp_path / "notes.stl"
    text.write_text("these are not the triangles you are looking for\n")
    assert_mesh_error(text, "unreadable", "not an STL file")


def test_empty_file(tmp_path):
    path = tmp_path / "empty.stl"
    path.write_bytes(b"")
    assert_mesh_error(path, "empty", "empty")


def test_binary_without_triangles(tmp_path):
    assert_mesh_error(
        write_binary_stl(tmp_path / "none.stl", np.zeros((0, 3, 3))), "empty", "no tri"
    )


def test_ascii_without_triangles(tmp_path):
    path = tmp_path / "none.stl"
    path.write_text("solid nothing\nendsolid nothing\n")
    assert_mesh_error(path, "empty", "no triangles")


def test_nan_coordinates(tmp_path):
    triangles = box_triangles(SIZE, LOW)
    triangles[3, 1, 2] = np.nan
    assert_mesh_error(write_binary_stl(tmp_path / "nan.stl", triangles), "unreadable", "non-finite")
    assert_mesh_error(
        write_ascii_stl(tmp_path / "nan_ascii.stl", triangles), "unreadable", "non-fin"
    )


def test_malformed_ascii(tmp_path):
    path = tmp_path / "bad.stl"
    path.write_text("solid bad\nfacet normal 0 0 0\nouter loop\nvertex 1 2 three\nendsolid bad\n")
    assert_mesh_error(path, "unreadable", "malformed vertex")
    short = tmp_path / "short.stl"
    short.write_text(
        "solid s\nfacet normal 0 0 0\nouter loop\nvertex 1 2 3\nvertex 1 2 4\nendsolid"
    )
    assert_mesh_error(short, "unreadable", "not a multiple of 3")
