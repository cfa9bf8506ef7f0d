"""read_triangles: every triangle of a mesh file, for a display, read as the analysis reads it."""

from __future__ import annotations

import numpy as np
import pytest
from kit import write
from kit.meshes import box_triangles, obj, write_binary_stl

from inertia_kit.errors import MeshError
from inertia_kit.physics.mesh_formats import read_triangles


@pytest.mark.parametrize("name", ["part.stl", "part.obj"])
def test_a_closed_mesh_gives_all_its_triangles(tmp_path, name):
    triangles = box_triangles((1.0, 2.0, 3.0), low=(-1.0, 0.0, 0.5))
    path = tmp_path / name
    if name.endswith(".stl"):
        write_binary_stl(path, triangles)  # closed: read_surface would not return them
    else:
        write(path, obj(triangles))
    read, unit = read_triangles(path)
    assert unit == 1.0
    assert read.shape == (12, 3, 3)
    np.testing.assert_allclose(read.reshape(-1, 3).min(axis=0), [-1, 0, 0.5])
    np.testing.assert_allclose(read.reshape(-1, 3).max(axis=0), [0, 2, 3.5])


def test_missing_and_unsupported_files_raise_mesh_errors(tmp_path):
    with pytest.raises(MeshError) as missing:
        read_triangles(tmp_path / "gone.stl")
    assert missing.value.kind == "not-found"
    with pytest.raises(MeshError) as unsupported:
        read_triangles(write(tmp_path / "part.step", "ISO-10303-21;"))
    assert unsupported.value.kind == "unreadable"
