"""
Mass properties of mesh files against closed forms and invariants.

Every file is written here, in ``tmp_path``: trimesh's exporters, or STL, OBJ and DAE text by
hand where a test needs exact coordinates or a particular layout.
"""

from __future__ import annotations

import dataclasses
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import trimesh
from kit import REPO
from kit.meshes import square_triangles, write_ascii_stl, write_binary_stl
from kit.physics import from_second_moment

from inertia_kit.errors import MeshError
from inertia_kit.physics import primitives
from inertia_kit.physics.frames import transform
from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.meshes import MeshMassProperties, MeshSolid, mesh, mesh_solid

ROOT = REPO
DENSITY = 700.0

# dyadic sizes and offsets: every vertex is exact in float32 and in 8 decimals, so every
# format stores the box exactly
SIZE = (0.5, 0.25, 2.0)
OFFSET = (0.25, -0.5, 1.0)


def box_mesh(size=SIZE, matrix=None) -> trimesh.Trimesh:
    return trimesh.creation.box(extents=size, transform=matrix)


def box_reference(size=SIZE, matrix=None, density=DENSITY) -> MassProperties:
    reference = primitives.box(size, density=density)
    return reference if matrix is None else reference.transformed(matrix)


def offset() -> np.ndarray:
    return transform(OFFSET, (0.0, 0.0, 0.0))


def linear_image(value: MassProperties, matrix) -> MassProperties:
    """The same body after every point x goes to A x at unchanged density (A may mirror)."""
    a = np.asarray(matrix, dtype=np.float64)
    jacobian = abs(np.linalg.det(a))
    return from_second_moment(
        jacobian * value.mass, a @ value.com, jacobian * a @ value.second_moment @ a.T
    )


def export(mesh_or_scene, path: Path, file_type: str | None = None) -> Path:
    data = mesh_or_scene.export(file_type=file_type or path.suffix[1:])
    path.write_bytes(data if isinstance(data, bytes) else data.encode())
    return path


def with_faces(source: trimesh.Trimesh, faces) -> trimesh.Trimesh:
    return trimesh.Trimesh(source.vertices.copy(), np.asarray(faces), process=False)


# --- every format, against the box formula --------------------------------------------------

FORMATS = {
    "stl-binary": ("box.stl", "stl"),
    "stl-ascii": ("box.stl", "stl_ascii"),
    "obj": ("box.obj", "obj"),
    "dae": ("box.dae", "dae"),
    "ply": ("box.ply", "ply"),
    "glb": ("box.glb", "glb"),
}


@pytest.mark.parametrize("name", FORMATS)
def test_offset_box_is_exact_in_every_format(tmp_path: Path, name: str) -> None:
    filename, file_type = FORMATS[name]
    path = export(box_mesh(matrix=offset()), tmp_path / filename, file_type)

    result = mesh(path, density=DENSITY)

    assert isinstance(result, MeshMassProperties)
    assert result.mass_properties.isclose(box_reference(matrix=offset()), rtol=1e-9)
    assert result.volume == pytest.approx(math.prod(SIZE), rel=1e-12)
    assert (result.method, result.closed, result.inverted) == ("exact", True, False)
    assert (result.triangle_count, result.unit_scale, result.volume_error) == (12, 1.0, 0.0)
    half = np.array(SIZE) / 2
    np.testing.assert_allclose(result.bounds, [np.add(OFFSET, -half), np.add(OFFSET, half)])
    assert result.path == str(path)
    assert result.scale == (1.0, 1.0, 1.0)


def test_gltf_with_external_buffers(tmp_path: Path) -> None:
    files = trimesh.Scene(box_mesh(matrix=offset())).export(file_type="gltf")
    for name, data in files.items():
        (tmp_path / name).write_bytes(data)

    result = mesh(tmp_path / "model.gltf", density=DENSITY)

    assert (result.method, result.unit_scale) == ("exact", 1.0)
    assert result.mass_properties.isclose(box_reference(matrix=offset()), rtol=1e-9)


def test_rotated_offset_box(tmp_path: Path) -> None:
    matrix = transform((1.5, -2.0, 0.7), (0.3, -0.7, 1.1))
    path = write_ascii_stl(tmp_path / "rotated.stl", box_mesh(matrix=matrix).triangles)

    result = mesh(path, density=DENSITY)

    assert result.method == "exact"
    assert result.mass_properties.isclose(box_reference(matrix=matrix), rtol=1e-9)


def test_scene_graph_transforms_are_applied(tmp_path: Path) -> None:
    rotated = transform((1.5, -2.0, 0.7), (0.3, -0.7, 1.1))
    scene = trimesh.Scene()
    scene.add_geometry(box_mesh(), transform=rotated)
    path = export(scene, tmp_path / "rotated.glb")

    result = mesh(path, density=DENSITY)

    assert result.method == "exact"
    assert result.mass_properties.isclose(box_reference(matrix=rotated), rtol=1e-9)


def test_mirroring_scene_node_is_not_an_inversion(tmp_path: Path) -> None:
    mirror = np.diag([-1.0, 1.0, 1.0, 1.0]) @ offset()
    scene = trimesh.Scene()
    scene.add_geometry(box_mesh(), transform=mirror)
    path = export(scene, tmp_path / "mirrored.glb")

    result = mesh(path, density=DENSITY)

    assert (result.method, result.inverted) == ("exact", False)
    expected = linear_image(box_reference(), mirror[:3, :3]).placed(mirror[:3, 3])
    assert result.mass_properties.isclose(expected, rtol=1e-9)


# --- a curved surface -------------------------------------------------------------------------


def check_sphere(result: MeshMassProperties, sphere: trimesh.Trimesh, centre, radius) -> None:
    """Between the inscribed and the circumscribed ball: the tessellation error's bounds."""
    normals = sphere.face_normals
    inner = float(np.min(np.einsum("ij,ij->i", sphere.triangles[:, 0] - centre, normals)))
    assert 0.9 * radius < inner < radius
    ball = 4 / 3 * math.pi
    assert ball * inner**3 <= result.volume <= ball * radius**3
    moments = result.mass_properties.principal_moments
    assert np.all(8 / 15 * math.pi * DENSITY * inner**5 <= moments)
    assert np.all(moments <= 8 / 15 * math.pi * DENSITY * radius**5)
    # icosahedral symmetry leaves only an isotropic tensor
    assert np.ptp(moments) <= 1e-9 * moments.max()
    np.testing.assert_allclose(result.mass_properties.com, centre, rtol=0, atol=1e-12 * radius)


def test_icosphere_within_tessellation_error(tmp_path: Path) -> None:
    centre, radius = np.array([0.1, -0.2, 0.3]), 0.3
    sphere = trimesh.creation.icosphere(subdivisions=3, radius=radius)
    sphere.apply_translation(centre)
    path = write_ascii_stl(tmp_path / "sphere.stl", sphere.triangles)

    result = mesh(path, density=DENSITY)

    assert result.method == "exact"
    check_sphere(result, sphere, centre, radius)
    # and closer to the ball than the coarsest bound: an icosphere of level 3 is within 1 %
    assert result.volume == pytest.approx(4 / 3 * math.pi * radius**3, rel=1e-2)


# --- scale and units ----------------------------------------------------------------------------


def test_millimetre_mesh_with_scale_equals_metre_mesh(tmp_path: Path) -> None:
    millimetres = transform((10.0, 20.0, -30.0), (0.0, 0.0, 0.0))
    path = export(box_mesh((100.0, 50.0, 200.0), millimetres), tmp_path / "part_mm.stl")

    result = mesh(path, (0.001, 0.001, 0.001), density=DENSITY)

    metres = box_reference((0.1, 0.05, 0.2), transform((0.01, 0.02, -0.03), (0, 0, 0)))
    assert result.mass_properties.isclose(metres, rtol=1e-9)
    assert result.volume == pytest.approx(0.1 * 0.05 * 0.2, rel=1e-12)
    np.testing.assert_allclose(result.bounds, [[-0.04, -0.005, -0.13], [0.06, 0.045, 0.07]])
    assert result.scale == (0.001, 0.001, 0.001)
    assert result.unit_scale == 1.0


def test_non_uniform_mirroring_scale(tmp_path: Path) -> None:
    matrix = transform((0.3, -0.2, 0.5), (0.4, 0.2, -0.9))
    box = box_mesh(matrix=matrix)
    path = write_ascii_stl(tmp_path / "part.stl", box.triangles)
    scale = (-1.0, 2.0, 0.5)

    result = mesh(path, scale, density=DENSITY)

    assert (result.method, result.inverted) == ("exact", False)
    assert result.volume == pytest.approx(math.prod(SIZE), rel=1e-12)
    expected = linear_image(box_reference(matrix=matrix), np.diag(scale))
    assert result.mass_properties.isclose(expected, rtol=1e-9)
    corners = box.vertices * scale
    np.testing.assert_allclose(result.bounds, [corners.min(axis=0), corners.max(axis=0)])

    # the same as a file mirrored by hand: vertices mirrored, winding reversed
    mirrored = write_ascii_stl(tmp_path / "mirrored.stl", (box.triangles * scale)[:, ::-1])
    assert mesh(mirrored, density=DENSITY).mass_properties.isclose(expected, rtol=1e-9)


def test_dae_unit_is_applied(tmp_path: Path) -> None:
    text = box_mesh((100.0, 50.0, 200.0)).export(file_type="dae").decode()
    assert "<unit" not in text
    text = text.replace("<asset>", '<asset>\n    <unit meter="0.001" name="millimeter"/>', 1)
    path = tmp_path / "part_mm.dae"
    path.write_text(text)

    result = mesh(path, density=DENSITY)

    assert result.unit_scale == 0.001
    assert result.mass_properties.isclose(box_reference((0.1, 0.05, 0.2)), rtol=1e-9)
    np.testing.assert_allclose(result.bounds, [[-0.05, -0.025, -0.1], [0.05, 0.025, 0.1]])


# --- surfaces that are not simply closed -------------------------------------------------------


@pytest.mark.parametrize("suffix", [".stl", ".obj"])
def test_inverted_mesh_is_reported_and_flipped(tmp_path: Path, suffix: str) -> None:
    box = box_mesh(matrix=offset())
    path = export(with_faces(box, box.faces[:, ::-1]), tmp_path / f"inverted{suffix}")

    result = mesh(path, density=DENSITY)

    assert (result.method, result.closed, result.inverted) == ("exact", True, True)
    assert result.volume > 0
    assert result.mass_properties.isclose(box_reference(matrix=offset()), rtol=1e-9)
    assert "inside-out" in result.summary


def tetrahedron_reference(corners, density=DENSITY) -> MassProperties:
    """Closed form: ``∫ x xᵀ dV = V/20 (Σ vᵢ vᵢᵀ + s sᵀ)`` about a vertex-free origin, s = Σ vᵢ."""
    v = np.asarray(corners, dtype=np.float64)
    centroid = v.mean(axis=0)
    d = v - centroid
    volume = abs(np.linalg.det(d[1:] - d[0])) / 6
    s = d.sum(axis=0)
    second = volume / 20 * (d.T @ d + np.outer(s, s))
    return from_second_moment(density * volume, centroid, density * second)


def test_open_tetrahedron_uses_convex_hull(tmp_path: Path) -> None:
    corners = np.array([[0.1, 0.2, 0.3], [1.3, 0.1, 0.2], [0.4, 2.2, 0.1], [0.2, 0.5, 3.1]])
    faces = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])
    closed = trimesh.Trimesh(corners, faces, process=False)
    assert closed.volume > 0
    path = write_ascii_stl(tmp_path / "open.stl", closed.triangles[:3])

    result = mesh(path, density=DENSITY)

    assert (result.method, result.closed, result.inverted) == ("convex-hull", False, False)
    assert result.triangle_count == 3
    assert result.mass_properties.isclose(tetrahedron_reference(corners), rtol=1e-9)
    # from the centroid, each face of a tetrahedron subtends a quarter of its volume
    assert result.volume_error == pytest.approx(1 / 4, rel=1e-9)


def test_open_mesh_uses_convex_hull(tmp_path: Path) -> None:
    box = box_mesh(matrix=offset())
    # drop the two triangles of the +z face
    top = box.face_normals[:, 2] > 0.5
    assert top.sum() == 2
    path = export(with_faces(box, box.faces[~top]), tmp_path / "open.stl")

    result = mesh(path, density=DENSITY)

    assert (result.method, result.closed, result.inverted) == ("convex-hull", False, False)
    assert result.triangle_count == 10
    # the hull of a box's corners is the box
    assert result.mass_properties.isclose(box_reference(matrix=offset()), rtol=1e-9)
    # the open surface spans, from the centroid, the box less the pyramid on its missing face:
    # every face of a box subtends a sixth of its volume
    assert result.volume_error == pytest.approx(1 / 6, rel=1e-9)
    assert "convex hull" in result.summary


def sphere_mesh() -> trimesh.Trimesh:
    return trimesh.creation.icosphere(subdivisions=2, radius=0.2)


@pytest.mark.parametrize("shape", ["icosphere", "box"])
def test_inconsistent_winding_is_repaired(tmp_path: Path, shape: str) -> None:
    solid = sphere_mesh() if shape == "icosphere" else box_mesh(matrix=offset())
    faces = solid.faces.copy()
    faces[::5] = faces[::5, ::-1]
    consistent = mesh_solid(export(solid, tmp_path / "consistent.stl"))
    path = export(with_faces(solid, faces), tmp_path / "inconsistent.stl")

    result = mesh_solid(path)

    assert (result.method, result.closed, result.inverted) == ("repaired", True, False)
    assert result.volume == pytest.approx(consistent.volume, rel=1e-12)
    reference = consistent.mass_properties(density=DENSITY)
    assert result.mass_properties(density=DENSITY).isclose(reference, rtol=1e-9)
    if shape == "icosphere":
        check_sphere(mesh(path, density=DENSITY), solid, np.zeros(3), 0.2)
    assert "wound inconsistently" in result.summary


def test_inconsistent_winding_is_repaired_in_obj(tmp_path: Path) -> None:
    solid = sphere_mesh()
    faces = solid.faces.copy()
    faces[1::3] = faces[1::3, ::-1]
    path = export(with_faces(solid, faces), tmp_path / "inconsistent.obj")

    result = mesh(path, density=DENSITY)

    assert result.method == "repaired"
    check_sphere(result, solid, np.zeros(3), 0.2)


def test_float_noise_is_merged_and_exact(tmp_path: Path) -> None:
    box = box_mesh(matrix=offset())
    noise = np.random.default_rng(7).uniform(-1e-13, 1e-13, box.triangles.shape)
    path = write_ascii_stl(tmp_path / "noisy.stl", box.triangles + noise)

    result = mesh(path, density=DENSITY)

    assert (result.method, result.closed) == ("exact", True)
    assert result.mass_properties.isclose(box_reference(matrix=offset()), rtol=1e-9)


# --- OBJ with several objects -------------------------------------------------------------------

CUBE_QUADS = ((1, 3, 4, 2), (5, 6, 8, 7), (1, 2, 6, 5), (3, 7, 8, 4), (1, 5, 7, 3), (2, 4, 8, 6))


def obj_cube(name: str, low, size: float, first: int) -> list[str]:
    """A cube as an OBJ object of six quads, counter-clockwise seen from outside."""
    lines = [f"o {name}"]
    for x in (0, 1):
        for y in (0, 1):
            for z in (0, 1):
                corner = np.add(low, np.multiply((x, y, z), size))
                lines.append("v " + " ".join(repr(float(c)) for c in corner))
    lines += ["f " + " ".join(str(first + i - 1) for i in quad) for quad in CUBE_QUADS]
    return lines


@pytest.mark.parametrize("layout", ["objects", "materials"])
def test_obj_with_two_objects_counts_both(tmp_path: Path, layout: str) -> None:
    first_cube = obj_cube("first", (0, 0, 0), 1.0, 1)
    second_cube = obj_cube("second", (3.0, 0.5, -2.0), 0.5, 9)
    if layout == "objects":
        lines = ["# two separate cubes", *first_cube, *second_cube]
    else:
        # one object in two groups and materials: trimesh splits it into two geometries
        lines = ["mtllib absent.mtl", "usemtl red", *first_cube]
        lines += ["g second", "usemtl blue", *second_cube[1:]]
    path = tmp_path / "two.obj"
    path.write_text("\n".join(lines) + "\n")

    result = mesh(path, density=DENSITY)

    first = box_reference((1.0, 1.0, 1.0), transform((0.5, 0.5, 0.5), (0, 0, 0)))
    second = box_reference((0.5, 0.5, 0.5), transform((3.25, 0.75, -1.75), (0, 0, 0)))
    assert (result.method, result.triangle_count) == ("exact", 24)
    assert result.volume == pytest.approx(1.0 + 0.125, rel=1e-12)
    assert result.mass_properties.isclose(first + second, rtol=1e-9)
    np.testing.assert_allclose(result.bounds, [[0, 0, -2.0], [3.5, 1.0, 1.0]])


# --- the density-free solid ---------------------------------------------------------------------


def test_mesh_solid_and_mesh_agree(tmp_path: Path) -> None:
    path = export(box_mesh(matrix=offset()), tmp_path / "box.stl")

    solid = mesh_solid(path)
    by_mass = mesh(path, mass=3.5)

    assert isinstance(solid, MeshSolid)
    assert solid.mass_properties(density=DENSITY) == mesh(path, density=DENSITY).mass_properties
    assert by_mass.mass_properties.mass == 3.5
    expected = box_reference(matrix=offset()).with_mass(3.5)
    assert by_mass.mass_properties.isclose(expected, rtol=1e-9)
    np.testing.assert_allclose(solid.centroid, OFFSET, atol=1e-15)
    with pytest.raises(dataclasses.FrozenInstanceError):
        solid.method = "repaired"  # type: ignore[misc]
    with pytest.raises(ValueError):
        solid.bounds[0, 0] = 1.0


@pytest.mark.parametrize(
    "kwargs", [{}, {"density": 1.0, "mass": 1.0}, {"density": -1.0}, {"mass": 0.0}]
)
def test_density_or_mass_is_required(tmp_path: Path, kwargs) -> None:
    path = export(box_mesh(), tmp_path / "box.stl")
    with pytest.raises(ValueError, match=r"density|mass"):
        mesh(path, **kwargs)


@pytest.mark.parametrize("scale", [(1.0, 0.0, 1.0), (1.0, 1.0), (1.0, math.nan, 1.0)])
def test_bad_scale_is_a_value_error(tmp_path: Path, scale) -> None:
    path = export(box_mesh(), tmp_path / "box.stl")
    with pytest.raises(ValueError, match="scale"):
        mesh_solid(path, scale)


# --- errors --------------------------------------------------------------------------------------


def write(name: str, data: bytes | str | None):
    def make(tmp_path: Path) -> Path:
        path = tmp_path / name
        if data is not None:
            path.write_bytes(data if isinstance(data, bytes) else data.encode())
        return path

    return make


BAD_FILES = {
    "missing": (write("missing.stl", None), "not-found"),
    "directory": (lambda tmp_path: tmp_path, "not-found"),
    "unsupported": (write("part.step", "ISO-10303-21;\n"), "unreadable"),
    "garbage-stl": (write("part.stl", b"\x00\x01 not an stl at all"), "unreadable"),
    "garbage-ply": (write("part.ply", b"\x00\x01 not a ply"), "unreadable"),
    "garbage-glb": (write("part.glb", b"\x00\x01 not a glb file at all"), "unreadable"),
    "garbage-dae": (write("part.dae", "<COLLADA><unclosed"), "unreadable"),
    "empty-binary-stl": (write("empty.stl", bytes(80) + (0).to_bytes(4, "little")), "empty"),
    "empty-obj": (write("empty.obj", "# nothing here\n"), "empty"),
    "points-only-obj": (write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"), "empty"),
    # squares and cubes of 1e200 overflow the integrals: an internal error before
    "huge-coordinates-obj": (
        write(
            "huge.obj",
            "v 1e200 0 0\nv 0 1e200 0\nv 0 0 1e200\nv 0 0 0\nf 1 2 3\nf 1 4 2\nf 2 4 3\nf 3 4 1\n",
        ),
        "unreadable",
    ),
    "closed-flat-sheet": (
        lambda tmp_path: write_ascii_stl(
            tmp_path / "sheet.stl",
            np.concatenate([square_triangles(), square_triangles()[:, ::-1]]),
        ),
        "empty",
    ),
    "open-flat-sheet": (
        lambda tmp_path: write_ascii_stl(tmp_path / "sheet.stl", square_triangles()),
        "empty",
    ),
}


@pytest.mark.parametrize("case", BAD_FILES)
def test_bad_files_raise_mesh_error(tmp_path: Path, case: str) -> None:
    make, kind = BAD_FILES[case]
    path = make(tmp_path)

    with pytest.raises(MeshError) as caught:
        mesh(path, density=DENSITY)

    error = caught.value
    assert error.kind == kind
    assert error.path == str(path)
    assert str(error).startswith(f"{path}: ")
    assert error.__cause__ is None
    assert "Traceback" not in error.message
    # every message says what to do
    assert any(word in error.message for word in ("check", "export", "convert", "re-export")), (
        error.message
    )


# --- the fast path ------------------------------------------------------------------------------


def _weighed_afresh(path: Path, *modules: str) -> list[str]:
    """The method ``mesh(path)`` takes in a fresh interpreter, and whether each of ``modules``
    was imported there (``True`` / ``False``)."""
    code = (
        "import sys\n"
        "from inertia_kit.physics.meshes import mesh\n"
        f"result = mesh({str(path)!r}, density=1000.0)\n"
        f"print(result.method, *(name in sys.modules for name in {modules!r}))\n"
    )
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True
    )
    return done.stdout.split()


def test_closed_stl_does_not_import_trimesh(tmp_path: Path) -> None:
    path = export(box_mesh(matrix=offset()), tmp_path / "box.stl")
    assert _weighed_afresh(path, "trimesh", "manifold3d") == ["exact", "False", "False"]


@pytest.mark.parametrize(("name", "method"), [("welded", "exact"), ("open", "convex-hull")])
def test_open_binary_stl_does_not_import_trimesh(tmp_path: Path, name, method) -> None:
    # a binary STL is a triangle soup: closed only once its corners are welded; an open one is
    # bounded by its hull. Neither needs trimesh to read the triangles.
    triangles = box_mesh().triangles.astype(np.float32)
    # one corner a float32 step off: not closed as written, welded shut
    triangles[0, 0, 0] = np.nextafter(triangles[0, 0, 0], np.float32(np.inf))
    if name == "open":
        triangles = triangles[1:]
    path = write_binary_stl(tmp_path / f"{name}.stl", triangles)
    assert _weighed_afresh(path, "trimesh") == [method, "False"]
