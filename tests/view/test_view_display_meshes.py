"""Shapes as display meshes: primitives and files in their own frames, shared, decimated."""

from __future__ import annotations

import base64

import numpy as np
import pytest
from kit import write
from kit.meshes import box_triangles, write_binary_stl
from kit.urdf import box, cylinder, link, mesh, robot, visual

from inertia_kit.description.loader import load
from inertia_kit.view.display_meshes import KEPT_WHOLE, MeshTable


def _shapes(tmp_path, *body):
    text = robot(link("a", *body))
    return load(write(tmp_path / "r.urdf", text)).links[0].visuals


def _positions(record):
    return np.frombuffer(base64.b64decode(record["positions"]), dtype="<f4").reshape(-1, 3)


def _indices(record):
    return np.frombuffer(base64.b64decode(record["indices"]), dtype="<u4").reshape(-1, 3)


def test_a_box_is_drawn_at_its_size_in_its_origin(tmp_path):
    (shape,) = _shapes(tmp_path, visual(box(0.4, 0.2, 0.1), xyz=(1, 2, 3)))
    table = MeshTable()
    record = table.shape_visual(shape)
    assert record["kind"] == "box"
    np.testing.assert_allclose(np.reshape(record["transform"], (4, 4))[:3, 3], [1, 2, 3])
    data = table.meshes[record["mesh"]].to_json()
    points = _positions(data)
    np.testing.assert_allclose(points.min(axis=0), [-0.2, -0.1, -0.05], rtol=1e-6)
    np.testing.assert_allclose(points.max(axis=0), [0.2, 0.1, 0.05], rtol=1e-6)
    assert data["triangles"] == data["source_triangles"] == len(_indices(data)) == 12


def test_a_cylinder_stands_along_z(tmp_path):
    (shape,) = _shapes(tmp_path, visual(cylinder(0.05, 0.3)))
    table = MeshTable()
    points = table.meshes[table.shape_visual(shape)["mesh"]].positions
    assert np.ptp(points[:, 2]) == pytest.approx(0.3)
    assert np.hypot(points[:, 0], points[:, 1]).max() == pytest.approx(0.05, rel=0.01)


def test_identical_shapes_and_one_file_at_two_scales_are_carried_once(tmp_path):
    stl = write_binary_stl(tmp_path / "part.stl", box_triangles((10.0, 20.0, 30.0)))
    shapes = _shapes(
        tmp_path,
        visual(box(1, 1, 1)),
        visual(box(1, 1, 1), xyz=(0, 0, 1)),
        visual(mesh(stl.name, (0.001, 0.001, 0.001))),
        visual(mesh(stl.name, (0.002, 0.002, 0.002))),
        visual(mesh(stl.name, (0.001, 0.001, 0.001))),
    )
    table = MeshTable()
    records = [table.shape_visual(shape) for shape in shapes]
    assert [r["mesh"] for r in records] == [0, 0, 1, 1, 1]
    assert len(table.meshes) == 2
    # the file's triangles in its own unit, the URDF scale in the shape's transform
    np.testing.assert_allclose(np.ptp(table.meshes[1].positions, axis=0), [10, 20, 30])
    scaled = np.reshape(records[3]["transform"], (4, 4))
    np.testing.assert_allclose(np.diag(scaled), [2e-3, 2e-3, 2e-3, 1])
    assert table.meshes[1].name == "part.stl"
    # shared vertices: a box's 8 corners, not 36 triangle corners
    assert len(table.meshes[1].positions) == 8


def test_a_missing_mesh_is_left_out_without_a_crash(tmp_path):
    shapes = _shapes(tmp_path, visual(mesh("gone.stl")), visual(box(1, 1, 1)))
    table = MeshTable()
    assert table.shape_visual(shapes[0]) is None
    assert table.shape_visual(shapes[1])["mesh"] == 0


def test_an_unreadable_mesh_is_left_out(tmp_path):
    write(tmp_path / "broken.obj", "this is no mesh\n")
    write(tmp_path / "broken.stl", b"\x00" * 90)
    shapes = _shapes(tmp_path, visual(mesh("broken.obj")), visual(mesh("broken.stl")))
    table = MeshTable()
    assert [table.shape_visual(shape) for shape in shapes] == [None, None]
    assert table.meshes == []


def _sphere_table(subdivisions):
    import trimesh

    table = MeshTable()
    for level in subdivisions:
        sphere = trimesh.creation.icosphere(subdivisions=level)
        table._mesh(("sphere", level), lambda s=sphere: _display(s))
    return table


def _display(sphere):
    from inertia_kit.view.display_meshes import DisplayMesh

    faces = np.asarray(sphere.faces, dtype=np.int64)
    return DisplayMesh("sphere", np.asarray(sphere.vertices), faces, len(faces))


def test_over_the_budget_each_mesh_is_decimated_in_proportion():
    table = _sphere_table([5, 4])  # 20480 and 5120 triangles
    before = [m.triangles for m in table.meshes]
    assert table.within_budget(6400)
    after = [m.triangles for m in table.meshes]
    assert sum(after) <= 6400
    # each kept about a quarter of its triangles (6400 / 25600)
    for was, now in zip(before, after, strict=True):
        assert now == pytest.approx(was / 4, rel=0.05)
        assert len(table.meshes[0].positions) < was
    assert [m.source_triangles for m in table.meshes] == before


def test_within_the_budget_nothing_changes():
    table = _sphere_table([2])
    triangles = table.meshes[0].triangles
    assert not table.within_budget(triangles)
    assert table.meshes[0].triangles == triangles


def test_small_meshes_are_kept_whole(tmp_path):
    shapes = _shapes(tmp_path, *(visual(box(i, 1, 1)) for i in range(1, 5)))
    table = MeshTable()
    for shape in shapes:
        table.shape_visual(shape)
    assert not table.within_budget(10)  # 48 triangles over 10: every box is already the least
    assert {m.triangles for m in table.meshes} == {KEPT_WHOLE}
