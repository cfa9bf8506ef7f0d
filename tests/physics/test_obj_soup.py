"""obj_soup: the triangle soup trimesh 5.2 reads from an OBJ file, without trimesh."""

from __future__ import annotations

import importlib.util
import io
import os
import warnings
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from inertia_kit.physics.mesh_formats import _scene_parts
from inertia_kit.physics.obj_soup import _flat_faces, _layout_indices, obj_soup
from inertia_kit.physics.polyhedra import integrate, reference_point

trimesh = pytest.importorskip("trimesh")

MENAGERIE = Path("/work/ext/menagerie")
#: installed packages holding OBJ meshes (cmeel's example-robot-data lives in cmeel.prefix)
PACKAGES = ("pybullet_data", "rtbdata", "dexmate_urdf", "fourier_robot_descriptions", "cmeel")


def trimesh_soup(data: bytes) -> np.ndarray:
    """trimesh's soup, flattened as mesh_formats does (raises where trimesh fails)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        scene = trimesh.load_scene(file_obj=io.BytesIO(data), file_type="obj", process=False)
    parts, _ = _scene_parts(scene, trimesh.Trimesh)
    return np.concatenate(parts) if parts else np.zeros((0, 3, 3))


def rows(triangles: np.ndarray) -> np.ndarray:
    """The triangles as sorted (n, 9) rows: a multiset with each triangle's vertex order."""
    flat = np.asarray(triangles, dtype=np.float64).reshape(len(triangles), 9)
    return flat[np.lexsort(flat.T[::-1])] if len(flat) else flat


def outcome(read, data: bytes):
    try:
        return read(data)
    except Exception as error:  # trimesh raises anything
        return error


def assert_agrees(data: bytes) -> np.ndarray | None:
    """obj_soup gives trimesh's triangles as a multiset, or both raise; ours is returned."""
    theirs = outcome(trimesh_soup, data)
    ours = outcome(obj_soup, data)
    if isinstance(theirs, Exception):
        assert isinstance(ours, ValueError), (theirs, ours)
        assert "\n" not in str(ours)
        return None
    assert not isinstance(ours, Exception), (ours, theirs)
    assert ours.shape == theirs.shape
    assert ours.dtype == np.float64
    np.testing.assert_array_equal(rows(ours), rows(theirs))
    return ours


V4 = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
V6 = V4 + b"v 1 1 0\nv 1 1 1\n"
CUBE = b"""# a cube of quads, with normals and texture coordinates
mtllib cube.mtl
o cube
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
vt 0 0
vt 1 0
vt 1 1
vn 0 0 -1
vn 0 0 1
g bottom
usemtl red
s off
f 1/1/1 4/2/1 3/3/1 2/1/1
usemtl blue
f 5/1/2 6/2/2 7/3/2 8/1/2
g sides
usemtl red
f 1//1 2//1 6//1 5//1
f 2//1 3//1 7//1 6//1
usemtl blue
f 3 4 8 7
f 4 1 5 8
"""

CASES = {
    "triangles": V4 + b"f 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n",
    "quads": V6 + b"f 1 2 5 3\nf 2 6 5 4\n",
    "cube: materials, groups, v/vt/vn, v//vn": CUBE,
    "pentagon and hexagon: fans": V6 + b"f 1 2 5 6 3\nf 1 2 5 6 3 4\n",
    "only pentagons (vectorised fan)": V6 + b"f 1 2 5 6 3\nf 2 5 6 3 4\n",
    "mixed sizes": V6 + b"f 1 2 3\nf 1 2 5 3\nf 1 2 5 6 3 4\nf 4 5 6\n",
    "negative indices: from the file's end": V4 + b"f -1 -2 -3\nv 5 5 5\nf -4 -3 -2\n",
    "index 0: the first vertex": V4 + b"f 0 2 3\n",
    "index 0 and the last index": b"v 0 0 0\nv 1 0 0\nf 0 1 2\nf 0 -1 -2\nf 2 1 0 -2\n",
    "1 and 2 vertex faces dropped": V4 + b"f 1\nf 1 2\nf 1 2 3\n",
    "only 2 vertex faces": V4 + b"f 1 2\nf 2 3\n",
    "1 and 2 vertex faces, normals of 2 numbers": V4 + b"vn 0 0\nf 1 2\nf 1\n",
    "1 and 2 vertex faces, no normal": V4 + b"vt 0 0\nf 1 2\nf 1\n",
    "empty f line": V4 + b"f\nf 1 2 3 4\n",
    "v/vt": V4 + b"vt 0 0\nvt 1 1\nf 1/1 2/2 3/1\nf 1/2 3/1 4/1\n",
    "v/vt/vn": V4 + b"vn 0 0 1\nvt 0 0\nf 1/1/1 2/1/1 3/1/1 4/1/1\n",
    "same count, other layout: read as the first line": V6 + b"f 1/1 2/2 3/3\nf 1 2 3 4 5 6\n",
    "trailing slash": V4 + b"f 1/ 2/ 3/\n",
    "w and colours": b"v 0 0 0 1\nv 1 0 0 1\nv 0 1 0 1\nf 1 2 3\n",
    "colours": b"v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n",
    "mixed row lengths: cut to the shortest": b"v 0 0 0 1\nv 1 0 0\nv 0 1 0 1 1 1\nf 1 2 3\n",
    "row lengths folding": b"v 0 0 0\nv 1 0\nv 0 1 0 5\nf 1 2 3\n",
    "line continuation": V4 + b"f 1 2 \\\n 3\nv 1 \\\n2 3\nf 4 5 1\n",
    "comments and blank lines": b"# c\n\n" + V4 + b"\n# f 9 9 9\nf 1 2 3\n\n",
    "crlf continuation": V4 + b"# c \\\r\nf 1 2 3\r\nf 1 \\\r\n 2 4\r\n",
    "crlf": (V4 + b"f 1 2 3\nf 1 3 4\n").replace(b"\n", b"\r\n"),
    "tabs": V4.replace(b" ", b"\t", 2) + b"f 1\t2  3\n",
    "leading spaces: not a vertex": V4 + b" v 9 9 9\nf 1 2 3\n",
    "o/g/usemtl/mtllib/s/l lines": b"mtllib a.mtl\no one\n"
    + V4
    + b"g a\nusemtl m\ns 1\nl 1 2\nf 1 2 3\no two\ng b\nusemtl n\nf 2 3 4\n",
    "objects sharing vertices": b"o a\n" + V4 + b"f 1 2 3\no b\nf 1 2 3\nf 2 3 4\n",
    "usemtl in a comment": V4 + b"f 1 2 3\n# usemtl x\nf 1 2 3 4\nf 1 2\n",
    "usemtl in a face line": V4 + b"f 1 2 4 usemtl x\nf 2 3 4\n",
    "faces before vertices": b"f 1 2 3\n" + V4,
    "f\\t in the middle: a face": V4 + b"f 1 2 3\nf\t1 2 4\nf 2 3 4\n",
    "foo in the middle: garbage": V4 + b"f 1 2 3\nfoo\nf 2 3 4\n",
    "foo in mixed faces: dropped": V4 + b"f 1 2 3\nfoo\nf 2 3 4 1\n",
    "f\\t alone after usemtl: skipped": V4 + b"f 1 2 3\nusemtl a\nf\t1 2 4 3\nusemtl b\nf 2 3 4\n",
    "f\\t first after usemtl, then faces": V4 + b"f 1 2 3\nusemtl a\nf\t1 2 4 3\nf 1 2 3\n",
    "f\\t after o: skipped": b"o a\nf\t1 2 3\nusemtl b\nf 2 3 4\n" + V4,
    "f\\t after the last face: ignored": V4 + b"f 1 2 3\nf\t2 3 4\n",
    "exponents": b"v 1e-3 0 0\nv 1E2 0 0\nv 0 1.5e+1 0\nv 2.5-e3 1 1\nf 1 2 3\nf 2 3 4\n",
    "plus signs": V4 + b"f +1 2 3\nf 1 2 3 +4\n",
    "underscores in a fallback index": V4 + b"f 1_0 2 3\nf 1 2 3 4\n",
    "no vertices": b"f 1 2 3\n",
    "no faces": V4,
    "empty": b"",
    "whitespace only": b" \n\t\n",
    "duplicate and degenerate triangles kept": V4 + b"f 1 2 3\nf 1 2 3\nf 1 1 1\n",
    "non-finite coordinates kept": b"v nan 0 0\nv inf 0 0\nv 0 1e308 0\nf 1 2 3\n",
    "utf-8 name": "o ünïcode\n".encode() + V4 + "usemtl é\nf 1 2 3\n".encode(),
    "control characters in a comment": V4 + b"# \x00\x01\x1c\nf 1 2 3\n\x1a",
    "cr only: one line": (V4 + b"f 1 2 3\n").replace(b"\n", b"\r"),
    # trimesh fails on these
    "index past the end": V4 + b"f 1 2 9\n",
    "negative index past the start": V4 + b"f 1 2 -9\n",
    "index past the end in a 2 vertex face": V4 + b"f 1 9\nf 1 2 3\n",
    "comment after a vertex": V4.replace(b"v 0 0 1", b"v 0 0 1 # top") + b"f 1 2 3\n",
    "comment after every vertex": V4.replace(b"\n", b" # c\n") + b"f 1 2 3\n",
    "comment after a face": V4 + b"f 1 2 3 # x\n",
    "comment after a mixed face": V4 + b"f 1 2 3 # x\nf 1 2 3 4\n",
    "float index": V4 + b"f 1.5 2 3\n",
    "empty index in a fallback": V4 + b"f /1 2 3\nf 1 2 3 4\n",
    "bad vt": V4 + b"vt 0 x\nf 1 2 3\n",
    "bad vn": V4 + b"vn 0 0 1 #\nf 1 2 3\n",
    "no face of 3 vertices, with normals": V4 + b"vn 0 0 1\nf 1 2\nf 1\n",
    "word in a fallback": V4 + b"f a b c\nf 1 2 3 4\n",
}


@pytest.mark.parametrize("data", CASES.values(), ids=CASES.keys())
def test_matches_trimesh(data):
    assert_agrees(data)


@pytest.mark.parametrize(
    "data, reason",
    [
        (V4 + b"f 1 2 3\n\xff\n", "UTF-8"),
        (b"v 0 0\nv 1 0\nv 0 1\nf 1 2 3\n", "3 coordinates"),
        (V4 + b"f 1 2 3\\", "continuation"),
        (V4 + b"f 1 2 3\x00\n", "control character 0x00"),
        (V4 + b"v 1 2\x1c3\nf 1 2 3\n", "control character 0x1c"),
        (V4 + "f 1 2 3\u00a0\nf 2 3 4\n".encode(), "ASCII"),
    ],
)
def test_refused(data, reason):
    """Files trimesh reads (or reads oddly) that obj_soup refuses, with a one-line reason."""
    with pytest.raises(ValueError, match=reason) as error:
        obj_soup(data)
    assert "\n" not in str(error.value)


def test_quad_winding():
    """A quad is (0, 1, 2), (2, 3, 0), vertex order as trimesh gives it."""
    triangles = obj_soup(V6 + b"f 1 2 5 3\n")
    vertices = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)
    np.testing.assert_array_equal(triangles, vertices[[[0, 1, 2], [2, 3, 0]]])


def test_refuses_no_vertex_only_with_faces():
    assert obj_soup(b"v 0 0\n").shape == (0, 3, 3)  # no face: nothing to refuse


# --- random small OBJ texts ----------------------------------------------------------------


@st.composite
def obj_texts(draw):
    count = draw(st.integers(1, 8))
    coordinate = st.sampled_from(["0", "1", "-2.5", "0.125", "3e-2", "1.0E1", "7"])
    lines = []
    for _ in range(count):
        extra = draw(st.sampled_from([0, 0, 0, 1, 3]))
        lines.append("v " + " ".join(draw(coordinate) for _ in range(3 + extra)))
    layout = draw(st.sampled_from(["{}", "{}/1", "{}//1", "{}/1/1", "{}/"]))
    mixed_layout = draw(st.booleans())
    for _ in range(draw(st.integers(1, 6))):
        size = draw(st.integers(3, 7))
        indices = []
        for _ in range(size):
            index = draw(st.integers(1, count))
            if draw(st.integers(0, 3)) == 0:
                index = -draw(st.integers(1, count))
            token_layout = (
                draw(st.sampled_from(["{}", "{}/1", "{}//1"])) if mixed_layout else layout
            )
            indices.append(token_layout.format(index))
        lines.append("f " + " ".join(indices))
        if draw(st.integers(0, 4)) == 0:
            lines.append(
                draw(st.sampled_from(["usemtl a", "usemtl b", "o x", "g y", "s 1", "# c"]))
            )
        if draw(st.integers(0, 4)) == 0:
            lines.append("v " + " ".join(draw(coordinate) for _ in range(3)))
    lines.insert(draw(st.integers(0, len(lines))), draw(st.sampled_from(["vt 0 1", "vn 0 0 1"])))
    ending = draw(st.sampled_from(["\n", "\r\n"]))
    return (ending.join(lines) + ending).encode()


@settings(max_examples=300, deadline=None)
@given(obj_texts())
def test_random_texts_match_trimesh(data):
    assert_agrees(data)


NOISY_LINES = [
    "v 0 0 0",
    "v 1 0 0",
    "v 0 1 0",
    "v 0 0 1",
    "v 1 1 1 0.5 0.5 0.5",
    "v 2 2 2 1",
    "v 1\t2 3",
    "f 1 2 3",
    "f 1 2 3 4",
    "f 1 2 3 4 5 6 7",
    "f 1 2",
    "f 1",
    "f",
    "f 0 1 2",
    "f -1 -2 -3",
    "f 1/1 2/2 3/3",
    "f 1//1 2//1 3//1 4//1",
    "f 1/1/1 2/1/1 3/1/1",
    "f 1 2 9",
    "f 1/ 2/ 3/",
    "f 1 2 3 # c",
    "f 1 2 3 usemtl m",
    "f\t1 2 3",
    "f  1   2  3 ",
    "f 1 2 -7",
    "f 2/ 3 4",
    "vt 0 0",
    "vt 0 0 0",
    "vn 0 0 1",
    "vn 1 0",
    "usemtl a",
    "usemtl b",
    "# usemtl c",
    "o x",
    "g y",
    "s off",
    "l 1 2",
    "mtllib m.mtl",
    "# comment",
    "",
    "  ",
    " v 5 5 5",
    "v 1 \\\n2 3",
    "f 1 \\\n2 3",
    "# ends in a backslash \\",
    "p 1",
    "vp 0.5",
]


@settings(max_examples=400, deadline=None)
@given(st.lists(st.sampled_from(NOISY_LINES), max_size=14), st.sampled_from(["\n", "\r\n"]))
def test_random_noisy_texts_match_trimesh(lines, ending):
    """Any mix of ordinary and malformed lines: trimesh's triangles, or both raise."""
    # a last line: a file ending in a backslash is refused (see the module's notes)
    assert_agrees((ending.join([*lines, "# end"]) + ending).encode())


# --- every OBJ file installed ------------------------------------------------------------


def _installed_objs() -> list[Path]:
    roots = []
    for name in PACKAGES:
        spec = importlib.util.find_spec(name)
        if spec is None or not spec.submodule_search_locations:
            continue
        for location in spec.submodule_search_locations:
            root = Path(location)
            roots.append(root.parent / "cmeel.prefix" if name == "cmeel" else root)
    if MENAGERIE.is_dir():
        roots.append(MENAGERIE)
    files = set()
    for root in roots:
        for folder, _, names in os.walk(root):
            files.update(Path(folder) / n for n in names if n.lower().endswith(".obj"))
    return sorted(files)


def _integrals(triangles: np.ndarray, origin: np.ndarray) -> list[np.ndarray]:
    """Volume, centroid and second moment about the centroid (first moment when no volume)."""
    moments = integrate(triangles, origin=origin).moments
    if moments.volume == 0:
        return [np.array([moments.volume]), moments.first, moments.second]
    offset = moments.first / moments.volume
    central = moments.second - moments.volume * np.outer(offset, offset)
    return [np.array([moments.volume]), moments.origin + offset, central]


def installed_differences() -> tuple[int, float, list[str]]:
    """Files checked, the largest relative difference of the integrals, and the disagreements
    (another outcome, or other triangles: the soups must be the same multiset)."""
    files = _installed_objs()
    if not files:
        pytest.skip("no OBJ file installed (pybullet_data, rtbdata, ..., /work/ext/menagerie)")
    worst, failures = 0.0, []
    for file in files:
        data = file.read_bytes()
        theirs, ours = outcome(trimesh_soup, data), outcome(obj_soup, data)
        if isinstance(theirs, Exception) or isinstance(ours, Exception):
            if not (isinstance(theirs, Exception) and isinstance(ours, ValueError)):
                failures.append(f"{file}: trimesh {theirs!r:.80} / ours {ours!r:.80}")
            continue
        if ours.shape != theirs.shape:
            failures.append(f"{file}: {len(theirs)} triangles, ours {len(ours)}")
            continue
        if not np.array_equal(rows(ours), rows(theirs), equal_nan=True):
            failures.append(f"{file}: other triangles than trimesh's")
        if not len(ours) or not np.isfinite(theirs).all():
            continue
        origin = reference_point(theirs)
        for a, b in zip(_integrals(ours, origin), _integrals(theirs, origin), strict=True):
            scale = max(np.abs(a).max(), np.abs(b).max())
            if scale > 0:
                worst = max(worst, float(np.abs(a - b).max() / scale))
    return len(files), worst, failures


@pytest.mark.slow
def test_installed_objs_match_trimesh():
    count, worst, failures = installed_differences()
    assert count > 0
    assert not failures, "\n".join(failures[:20])
    assert worst <= 1e-12, worst


# --- the fast paths: each against the general path and against trimesh ---------------------


@st.composite
def exporter_faces(draw):
    """Face lines as exporters write them, sometimes with one slip the fast path must leave
    to the general path (a double space, a tab, another token shape, a leading zero, ...)."""
    count = draw(st.integers(3, 12))
    layout = draw(st.sampled_from(["{}", "{}/{}", "{}//{}", "{}/{}/{}", "{}/", "{}//"]))
    size = draw(st.integers(3, 5))
    lines = []
    for _ in range(draw(st.integers(1, 8))):
        tokens = []
        for _ in range(size):
            index = draw(st.integers(-count, count + 1))
            tokens.append(layout.format(index, draw(st.integers(1, 99)), 1))
        lines.append("f " + " ".join(tokens))
    slip = draw(
        st.sampled_from(
            ["", "", "", "  ", "\t", " 0", "/", "//", " x", " 123456789012", " 00000000001"]
        )
    )
    if slip:
        at = draw(st.integers(0, len(lines) - 1))
        line = lines[at]
        where = draw(st.integers(2, len(line)))
        lines[at] = line[:where] + slip + line[where:]
    vertices = [f"v {k} {k % 3} {k * k % 5}" for k in range(count)]
    return ("\n".join([*vertices, "vn 0 0 1", "vt 0 0", *lines]) + "\n").encode()


@settings(max_examples=400, deadline=None)
@given(exporter_faces())
def test_exporter_layouts_match_trimesh(data):
    assert_agrees(data)


@settings(max_examples=400, deadline=None)
@given(exporter_faces())
def test_layout_fast_path_reads_as_the_general_path(data):
    """_layout_indices gives _flat_faces' indices wherever it reads the lines at all."""
    face_lines = [line for line in data.split(b"\n") if line.startswith(b"f")]
    joined = b"".join(b" " + line[1:] + b"\n" for line in face_lines)
    body = np.frombuffer(joined, dtype=np.uint8).copy()
    lengths = np.array([len(line) + 1 for line in face_lines])
    offsets = np.cumsum(lengths) - lengths
    lasts = offsets + lengths - 1
    fast = _layout_indices(body, joined, offsets, lasts)
    if fast is None:
        return
    columns = len(joined[: int(lasts[0])].replace(b"/", b" ").split())
    general = _flat_faces(joined, b"/" in joined, offsets, lasts, columns)
    np.testing.assert_array_equal(fast, general)


def test_layout_fast_path_reads_exporter_files():
    """The layouts Blender and trimesh write take the fast path (and give trimesh's soup)."""
    vertices = b"".join(b"v %d 0 %d\n" % (k, k % 2) for k in range(1, 13))
    for face in (b"f 1 2 3\n", b"f 1/1 2/2 3/3\n", b"f 1//1 2//1 3//1\n", b"f 1/2/3 4/5/6 7/8/9\n"):
        lines = face * 3
        body = np.frombuffer(b" " + lines[1:].replace(b"\nf", b"\n "), dtype=np.uint8).copy()
        lengths = np.array([len(face)] * 3)
        offsets = np.cumsum(lengths) - lengths
        assert _layout_indices(body, body.tobytes(), offsets, offsets + lengths - 1) is not None
        assert_agrees(vertices + b"vt 0 0\nvn 0 0 1\n" + lines)
