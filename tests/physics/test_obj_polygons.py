"""
read_mujoco_triangles of an OBJ file against the real MuJoCo: the triangles its OBJ decoder builds
(tinyobjloader's split of quads along the shorter diagonal and ear clipping of larger polygons,
the first object only), compared face by face with the compiled ``mesh_face``, and the mass
properties MuJoCo infers from them to 1e-9.
"""

from __future__ import annotations

import numpy as np
import pytest
from kit import write

from inertia_kit.errors import MeshError
from inertia_kit.physics.mesh_formats import _read_scene, read_mujoco_triangles
from inertia_kit.physics.mujoco_mesh_inertia import soup_mass_properties
from inertia_kit.physics.obj_polygons import obj_triangles

mujoco = pytest.importorskip("mujoco")


@pytest.fixture(autouse=True)
def _in_tmp_path(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # MuJoCo writes MUJOCO_LOG.TXT in the cwd


def _compile(path, inertia="shell", mass='mass="1"'):
    """MuJoCo's model of one static body whose one geom is the OBJ file's mesh."""
    xml = f"""<mujoco><compiler balanceinertia="true" meshdir="{path.parent}"/>
      <asset><mesh name="m" file="{path.name}" inertia="{inertia}"/></asset>
      <worldbody><body><geom type="mesh" mesh="m" {mass}/></body></worldbody></mujoco>"""
    return mujoco.MjModel.from_xml_string(xml)


def _faces_of(path, vertices):
    """Our triangles of ``path`` as indices of ``vertices`` (all distinct, as written)."""
    where = {tuple(v): i for i, v in enumerate(np.asarray(vertices, dtype=np.float64).tolist())}
    assert len(where) == len(vertices)
    triangles, unit = read_mujoco_triangles(path)
    assert unit == 1.0
    return np.array([[where[tuple(p)] for p in t] for t in triangles.tolist()]).reshape(-1, 3)


def _check_against_mujoco(path, vertices):
    """Our faces are MuJoCo's, index for index (it keeps distinct vertices in file order)."""
    model = _compile(path)
    assert model.mesh_vertnum[0] == len(vertices)
    ours = _faces_of(path, vertices)
    np.testing.assert_array_equal(ours, model.mesh_face)
    return ours


def _obj(vertices, *faces, header="", vertex_format="v {} {} {}"):
    lines = [header] if header else []
    lines += [vertex_format.format(*v) for v in vertices]
    lines += list(faces)
    return "\n".join(lines) + "\n"


# an apex off every plane used below: MuJoCo needs a convex hull of the mesh's vertices
APEX = (0.25, 0.5, 3.0)


def _old_faces(path, vertices):
    """What the trimesh reading (before MuJoCo's triangulation) gave, as indices."""
    where = {tuple(v): i for i, v in enumerate(np.asarray(vertices, dtype=np.float64).tolist())}
    triangles, _ = _read_scene(path, ".obj")
    return np.array([[where[tuple(p)] for p in t] for t in triangles.tolist()]).reshape(-1, 3)


@pytest.mark.parametrize(
    ("corners", "expected"),
    [
        # non-planar quads: the diagonal 0-2 the shorter, then 1-3, then a tie (split along 1-3)
        ([(0, 0, 0), (2, 0, 0.3), (1, 1, 0), (0, 1, 0.3)], [[0, 1, 2], [0, 2, 3]]),
        ([(0, 0, 0), (1, 0, 0.3), (3, 1, 0), (0, 1, 0.3)], [[0, 1, 3], [1, 2, 3]]),
        ([(0, 0, 0), (2, 0, 0.3), (2, 1, 0), (0, 1, 0.3)], [[0, 1, 3], [1, 2, 3]]),
        ([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], [[0, 1, 3], [1, 2, 3]]),
    ],
)
def test_a_quad_is_split_along_its_shorter_diagonal(tmp_path, corners, expected):
    vertices = [*corners, APEX]
    path = write(tmp_path / "quad.obj", _obj(vertices, "f 1 2 3 4", "f 5 1 2"))
    faces = _check_against_mujoco(path, vertices)
    assert faces[:2].tolist() == expected


def test_a_quad_the_old_reading_split_the_other_way_changes_the_mass_properties(tmp_path):
    # a tetrahedron-like solid: a non-planar quad, closed by four triangles to an apex; its
    # diagonal 1-3 is the shorter, where a fan from vertex 0 splits along 0-2
    vertices = [(0, 0, 0), (1, 0, 0.4), (3, 2, 0), (0, 1, 0.4), (1, 1, 2)]
    text = _obj(vertices, "f 1 4 3 2", "f 1 2 5", "f 2 3 5", "f 3 4 5", "f 4 1 5")
    path = write(tmp_path / "solid.obj", text)
    ours = _check_against_mujoco(path, vertices)
    assert not np.array_equal(ours, _old_faces(path, vertices))

    solid = write(tmp_path / "weighed.obj", text)
    model = _compile(solid, inertia="legacy", mass="")
    value = soup_mass_properties(read_mujoco_triangles(solid)[0], "legacy")
    old = soup_mass_properties(_read_scene(solid, ".obj")[0], "legacy")
    density = 1000.0  # a geom's default
    np.testing.assert_allclose(value.mass * density, model.body_mass[1], rtol=1e-9)
    np.testing.assert_allclose(
        np.sort(value.principal_moments) * density, np.sort(model.body_inertia[1]), rtol=1e-9
    )
    assert abs(old.mass * density - model.body_mass[1]) > 1e-3 * model.body_mass[1]


@pytest.mark.parametrize(
    "polygon",
    [
        # non-convex pentagon (a notch), planar in z = 0
        [(0, 0, 0), (4, 0, 0), (4, 3, 0), (2, 1, 0), (0, 3, 0)],
        # non-convex hexagon, tilted out of every axis plane
        [(0, 0, 0), (3, 0.3, 0.5), (3.2, 2, 1), (1.5, 0.8, 0.6), (0.2, 2.5, 1.3), (-1, 1, 0.4)],
        # non-planar hexagon, convex and clockwise seen from +z, off the origin (where it is,
        # matters: tinyobjloader's "area" is that of the origin and the ear's first edge)
        [(3, 2, 1), (2, 3, 1.5), (3, 4, 0.7), (5, 4, 1.6), (6, 3, 0.8), (5, 2, 1.4)],
        # a comb: many reflex corners, away from the origin
        [(5, 5, 1), (9, 5, 1), (9, 8, 1), (8, 6, 1), (7, 8, 1), (6, 6, 1), (5, 8, 1)],
    ],
)
def test_a_larger_polygon_is_ear_clipped_as_tinyobjloader_does(tmp_path, polygon):
    vertices = [*polygon, APEX]
    count = len(polygon)
    face = "f " + " ".join(str(i + 1) for i in range(count))
    path = write(tmp_path / "polygon.obj", _obj(vertices, face, f"f {count + 1} 1 2"))
    ours = _check_against_mujoco(path, vertices)
    assert not np.array_equal(ours, _old_faces(path, vertices))


def test_a_self_intersecting_polygon_loses_what_ear_clipping_cannot_cut(tmp_path):
    # a bow tie: tinyobjloader finds no ear in the remaining quad and drops it
    polygon = [(0, 0, 0), (2, 2, 0), (2, 0, 0), (0, 2, 0), (-1, 1, 0.5), (1, 3, 0.2)]
    vertices = [*polygon, APEX]
    path = write(tmp_path / "bowtie.obj", _obj(vertices, "f 1 2 3 4 5 6", "f 7 1 2"))
    ours = _check_against_mujoco(path, vertices)
    assert len(ours) - 1 <= len(polygon) - 2


def test_random_polygons_match_mujoco(tmp_path):
    rng = np.random.default_rng(7)
    for trial in range(40):
        count = int(rng.integers(4, 12))
        if trial % 2:
            points = rng.normal(size=(count, 3))  # non-planar, self-intersecting
        else:
            angles = np.sort(rng.uniform(0, 2 * np.pi, count))[:: rng.choice([-1, 1])]
            radii = rng.uniform(0.3, 1.0, count)
            flat = np.c_[radii * np.cos(angles), radii * np.sin(angles), np.zeros(count)]
            rotation, _ = np.linalg.qr(rng.normal(size=(3, 3)))
            points = flat @ rotation.T + rng.normal(size=3)  # non-convex, in a random plane
        vertices = [tuple(p) for p in np.round(points, 6).tolist()] + [(0.5, 0.25, 7.125)]
        face = "f " + " ".join(str(i + 1) for i in range(count))
        path = write(tmp_path / f"random{trial}.obj", _obj(vertices, face, "f 1 2 3"))
        _check_against_mujoco(path, vertices)


def test_index_forms_negative_indices_colours_and_weights(tmp_path):
    vertices = [(0, 0, 0), (2, 0, 0.3), (2, 1, 0), (0, 1, 0.3), (1, 0.5, 2), (0.5, -1, 0.1)]
    cases = {
        "plain": ("v {} {} {}", "f 1 2 3 4 6", "f 5 1 2"),
        "texture": ("v {} {} {}", "f 1/1 2/1 3/1 4/1 6/1", "f 5/1 1/1 2/1"),
        "normal": ("v {} {} {}", "f 1//1 2//1 3//1 4//1 6//1", "f 5//1 1//1 2//1"),
        "both": ("v {} {} {}", "f 1/1/1 2/1/1 3/1/1 4/1/1 6/1/1", "f 5/1/1 1/1/1 2/1/1"),
        "negative": ("v {} {} {}", "f -6 -5 -4 -3 -1", "f -2 -6 -5"),
        "colours": ("v {} {} {} 0.5 0.25 1", "f 1 2 3 4 6", "f 5 1 2"),
        "weights": ("v {} {} {} 0.5", "f 1 2 3 4 6", "f 5 1 2"),
    }
    headers = {"texture": "vt 0 0", "normal": "vn 0 0 1", "both": "vt 0 0\nvn 0 0 1"}
    results = []
    for name, (vertex_format, *faces) in cases.items():
        header = headers.get(name, "")
        text = _obj(vertices, *faces, header=header, vertex_format=vertex_format)
        path = write(tmp_path / f"{name}.obj", text)
        results.append(_check_against_mujoco(path, vertices))
    for result in results[1:]:
        np.testing.assert_array_equal(result, results[0])


def test_a_relative_index_counts_back_from_the_vertices_read_so_far(tmp_path):
    vertices = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 1), (2, 0, 1)]
    text = "\n".join(
        [
            "v 0 0 0",
            "v 1 0 0",
            "v 0 1 0",
            "f -3 -1 -2",  # 1 3 2
            "v 0 0 1",
            "f -4 -3 -1",  # 1 2 4
            "v 1 1 1",
            "v 2 0 1",
            "f -2 -1 -5 -4",  # 5 6 2 3
        ]
    )
    path = write(tmp_path / "relative.obj", text + "\n")
    faces = _check_against_mujoco(path, vertices)
    assert faces[:2].tolist() == [[0, 2, 1], [0, 1, 3]]


def test_only_the_first_object_or_group_is_read(tmp_path):
    first = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    second = [(5, 0, 0), (6, 0, 0), (5, 1, 0), (5, 0, 1.5)]
    faces_1 = ["f 1 3 2", "f 1 2 4", "f 1 4 3", "f 2 3 4"]
    faces_2 = ["f 5 7 6", "f 5 6 8", "f 5 8 7", "f 6 7 8"]
    vertices = first + second
    v_lines = [f"v {x} {y} {z}" for x, y, z in vertices]
    texts = {
        # objects and groups each make a shape: the first only is MuJoCo's
        "objects": ["o a", *v_lines[:4], *faces_1, "o b", *v_lines[4:], *faces_2],
        "groups": ["g a", *v_lines, *faces_1, "g b", *faces_2],
        # a shape without faces is not kept: the first with faces is
        "empty first": ["o a", *v_lines, "o b", *faces_2, "g c", *faces_1],
        # a material changes nothing
        "material": ["mtllib x.mtl", *v_lines, "usemtl a", *faces_1, "usemtl b", *faces_2],
    }
    expected = {"objects": 4, "groups": 4, "empty first": 4, "material": 8}
    for name, lines in texts.items():
        path = write(tmp_path / f"{name.replace(' ', '_')}.obj", "\n".join(lines) + "\n")
        faces = _check_against_mujoco(path, vertices)
        assert len(faces) == expected[name], name
    assert len(_old_faces(tmp_path / "objects.obj", vertices)) == 8


def test_faces_of_fewer_than_three_vertices_and_unread_quads_are_dropped(tmp_path):
    vertices = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    text = "\n".join(
        [
            *(f"v {x} {y} {z}" for x, y, z in vertices[:3]),
            "f 1 3 2",
            "f 1 2",
            "f 3",
            "f 1 2 3 4",  # vertex 4 is read only after the group ends: tinyobjloader drops it
            "g next",
            "v 0 0 1",
            "f 1 2 4",
        ]
    )
    path = write(tmp_path / "degenerate.obj", text + "\n")
    faces = _check_against_mujoco(path, vertices)
    assert faces.tolist() == [[0, 2, 1]]


@pytest.mark.parametrize(
    ("face", "mujoco_refuses"),
    [
        ("f 0 1 2", True),  # zero index
        ("f -1 -2 -9", True),  # relative index before the first vertex
        ("f 1 2 3 # note", True),  # a comment after the indices
        ("f 1 2 9", True),  # a vertex the file lacks
        ("f 1 2 3 4 9", True),
        ("f 1.5 2 3", False),  # tinyobjloader reads 1: refused here all the same
        ("f a b c", True),
        ("f 1/-2 2/-2 3/-2", True),  # a texture index before the first `vt`
        ("f 1/ -2 3", True),  # ... read across the blank
        ("f 1//1/ 2 3", True),  # three `/`
        ("l 0 1", True),  # a line's zero index
    ],
)
def test_a_malformed_face_is_a_mesh_error(tmp_path, face, mujoco_refuses):
    vertices = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    path = write(tmp_path / "bad.obj", _obj(vertices, "f 1 3 2", face))
    with pytest.raises(MeshError) as error:
        read_mujoco_triangles(path)
    assert error.value.kind == "unreadable"
    if mujoco_refuses:
        with pytest.raises(ValueError):
            _compile(path)


@pytest.mark.parametrize(
    "text",
    [
        "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        "v 0 x 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999\n",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf /1 2 3\n",
    ],
)
def test_malformed_numbers_are_mesh_errors(tmp_path, text):
    with pytest.raises(MeshError) as error:
        read_mujoco_triangles(write(tmp_path / "bad.obj", text))
    assert error.value.kind == "unreadable"


@pytest.mark.parametrize(
    "text",
    [
        "",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\n",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\no b\nf 1 2 3\n",  # the first shape: a line
        "\x00\x01binary\xff\nf 1 2 3\n",
    ],
)
def test_a_file_whose_first_shape_has_no_triangle_is_empty(tmp_path, text):
    path = tmp_path / "empty.obj"
    path.write_bytes(text.encode("latin-1"))
    with pytest.raises(MeshError) as error:
        read_mujoco_triangles(path)
    assert error.value.kind in ("empty", "unreadable")


def test_line_endings_leading_blanks_and_a_byte_order_mark(tmp_path):
    text = b"\xef\xbb\xbfv 9 9 9\r\nv 0 0 0\r  v 1 0 0\n\tv 0 1 0\nv 0 0 1\n f 1 2 3 4\nf 1 2 4\n"
    vertices, faces = obj_triangles(text)
    # the marked first line is no vertex line: 4 vertices
    assert vertices.tolist() == [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
    path = tmp_path / "blanks.obj"
    path.write_bytes(text)
    assert _check_against_mujoco(path, vertices).tolist() == faces.tolist()
    assert faces.tolist() == [[0, 1, 2], [0, 2, 3], [0, 1, 3]]
