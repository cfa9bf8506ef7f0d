"""
The numpy COLLADA reader (:mod:`inertia_kit.physics.collada`) against trimesh 5.2 + pycollada
(:func:`inertia_kit.physics.mesh_formats._read_scene`): hand-written files for each feature, every
installed robot's ``.dae`` file, and hostile files.
"""

from __future__ import annotations

import importlib.util
import os
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from inertia_kit.errors import MeshError
from inertia_kit.physics.collada import (
    _column,
    _floats,
    _ints,
    read_collada,
    read_collada_shared,
)
from inertia_kit.physics.mesh_formats import _read_scene
from inertia_kit.physics.polyhedra import integrate

NS = "http://www.collada.org/2005/11/COLLADASchema"
XYZ = '<param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>'
CUBE = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1]
# the cube's six faces as quads, counter-clockwise seen from outside
QUADS = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]
TRIS = [i for q in QUADS for i in (q[0], q[1], q[2], q[0], q[2], q[3])]


def source(ident: str, values, params: str = XYZ, stride: int | None = None, extra: str = ""):
    text = " ".join(repr(float(v)) for v in values)
    stride_text = f' stride="{stride}"' if stride else ""
    return (
        f'<source id="{ident}"><float_array id="{ident}-a" count="{len(values)}">{text}'
        f'</float_array><technique_common><accessor source="#{ident}-a"{stride_text}{extra}>'
        f"{params}</accessor></technique_common></source>"
    )


def document(
    geometries: str,
    nodes: str,
    *,
    unit: str = '<unit meter="1" name="meter"/>',
    library_nodes: str = "",
    scene: str = '<scene><instance_visual_scene url="#scene"/></scene>',
    head: str = '<?xml version="1.0" encoding="utf-8"?>\n',
) -> str:
    library = f"<library_nodes>{library_nodes}</library_nodes>" if library_nodes else ""
    return (
        f'{head}<COLLADA xmlns="{NS}" version="1.4.1"><asset>{unit}<up_axis>Z_UP</up_axis>'
        f"</asset><library_geometries>{geometries}</library_geometries>{library}"
        f'<library_visual_scenes><visual_scene id="scene">{nodes}</visual_scene>'
        f"</library_visual_scenes>{scene}</COLLADA>"
    )


def cube_geometry(ident: str = "cube", primitive: str | None = None) -> str:
    if primitive is None:
        primitive = triangles(TRIS)
    return (
        f'<geometry id="{ident}"><mesh>{source(ident + "-pos", CUBE)}'
        f'<vertices id="{ident}-v"><input semantic="POSITION" source="#{ident}-pos"/>'
        f"</vertices>{primitive.replace('#V', f'#{ident}-v')}</mesh></geometry>"
    )


def triangles(index, inputs: str = '<input semantic="VERTEX" source="#V" offset="0"/>') -> str:
    text = " ".join(map(str, index))
    return f'<triangles count="{len(index) // 3}">{inputs}<p>{text}</p></triangles>'


def node(body: str, ident: str = "n") -> str:
    return f'<node id="{ident}">{body}</node>'


def instance(url: str = "cube") -> str:
    return f'<instance_geometry url="#{url}"/>'


def write(tmp_path: Path, text: str | bytes, name: str = "part.dae") -> Path:
    path = tmp_path / name
    path.write_bytes(text.encode() if isinstance(text, str) else text)
    return path


def moments(triangles):
    integrator = integrate(triangles)
    m = integrator.moments
    volume = m.volume
    centroid = m.first / volume if volume else np.zeros(3)
    second = m.second
    return volume, centroid, second


def assert_same_mass(ours, theirs, rtol=1e-12) -> float:
    """Volume, centroid and inertia about the centroid agree to ``rtol`` of the largest."""
    worst = 0.0
    va, ca, _ = moments(ours)
    vb, cb, _ = moments(theirs)
    ia, ib = _central(ours), _central(theirs)
    for a, b in ((va, vb), (ca, cb), (ia, ib)):
        a, b = np.atleast_1d(a), np.atleast_1d(b)
        scale = max(np.abs(b).max(), np.abs(a).max(), 1e-300)
        worst = max(worst, float(np.abs(a - b).max() / scale))
    assert worst <= rtol, worst
    return worst


def _central(triangles):
    m = integrate(triangles).moments
    if not m.volume:
        return np.zeros((3, 3))
    return np.asarray(m.about(m.first / m.volume).second)


def sorted_rows(triangles):
    flat = np.asarray(triangles).reshape(len(triangles), 9)
    return flat[np.lexsort(flat.T[::-1])]


def compare(path: Path) -> tuple[np.ndarray, float]:
    """Ours and trimesh's: the same triangles (as a multiset, each wound alike) and unit."""
    ours, unit = read_collada(path.read_bytes(), path)
    theirs, their_unit = _read_scene(path, ".dae")
    assert unit == their_unit
    assert ours.dtype == np.float64 and ours.shape == theirs.shape
    np.testing.assert_array_equal(sorted_rows(ours), sorted_rows(theirs))
    return ours, unit


# --- features, each against trimesh --------------------------------------------------------------


def test_triangles_and_unit(tmp_path):
    path = write(
        tmp_path,
        document(cube_geometry(), node(instance()), unit='<unit meter="0.0254" name="inch"/>'),
    )
    triangles, unit = compare(path)
    assert len(triangles) == 12 and unit == pytest.approx(0.0254, rel=1e-15)
    assert moments(triangles)[0] == pytest.approx(1.0)


@pytest.mark.parametrize("meter", ["1.0000000001", "0.001", "banana", None])
def test_units(tmp_path, meter):
    unit = "" if meter is None else f'<unit meter="{meter}" name="u"/>'
    compare(write(tmp_path, document(cube_geometry(), node(instance()), unit=unit)))


def test_up_axis_is_not_applied(tmp_path):
    text = document(cube_geometry(), node(instance())).replace("Z_UP", "Y_UP")
    triangles, _ = compare(write(tmp_path, text))
    assert triangles.reshape(-1, 3).max(axis=0).tolist() == [1, 1, 1]


TRANSFORMS = [
    "<matrix>0 -1 0 0.5 1 0 0 2 0 0 1 -3 0 0 0 1</matrix>",
    "<translate>1 2 3</translate>",
    "<rotate>0.267 0.535 0.802 33</rotate>",
    "<scale>2 3 0.5</scale>",
    "<scale>-1 1 1</scale>",
    "<translate>1 0 0</translate><rotate>0 0 1 90</rotate><scale>1 2 3</scale>"
    "<matrix>1 0 0 0.1 0 1 0 0.2 0 0 1 0.3 0 0 0 1</matrix>",
    "<lookat>2 0 0 0 0 0 0 0 1</lookat>",
    "<skew>45 0 1 0 1 0 0</skew>",
]


@pytest.mark.parametrize("transform", TRANSFORMS)
def test_node_transforms(tmp_path, transform):
    nested = node(
        "<translate>0.5 0 0</translate><rotate>1 0 0 30</rotate>"
        + node(transform + instance(), "inner"),
        "outer",
    )
    compare(write(tmp_path, document(cube_geometry(), nested)))


def test_mirroring_reverses_winding(tmp_path):
    triangles, _ = compare(
        write(tmp_path, document(cube_geometry(), node("<scale>-1 1 1</scale>" + instance())))
    )
    assert moments(triangles)[0] == pytest.approx(1.0)


def test_instances_of_nodes_and_geometries(tmp_path):
    library = node(node("<translate>0 0 5</translate>" + instance(), "deep"), "lib")
    nodes = (
        node("<translate>3 0 0</translate>" + instance() + instance(), "a")
        + node('<scale>2 2 2</scale><instance_node url="#lib"/>', "b")
        + node('<translate>0 9 0</translate><instance_node url="#a"/>', "c")
        + node('<instance_light url="#nothing"/><instance_camera url="#x"/><extra/>', "d")
    )
    triangles, _ = compare(write(tmp_path, document(cube_geometry(), nodes, library_nodes=library)))
    assert len(triangles) == 12 * 5


def test_polylist_fans(tmp_path):
    counts = [len(q) for q in QUADS]
    # a pentagon and a triangle too: one face split, as fan order shows
    poly = (
        '<polylist count="6"><input semantic="VERTEX" source="#V" offset="0"/>'
        f"<vcount>{' '.join(map(str, counts))}</vcount>"
        f"<p>{' '.join(str(i) for q in QUADS for i in q)}</p></polylist>"
    )
    triangles, _ = compare(
        write(tmp_path, document(cube_geometry(primitive=poly), node(instance())))
    )
    assert len(triangles) == 12


def test_interleaved_inputs_and_shared_sources(tmp_path):
    normals = source("nrm", [0, 0, 1, 0, 1, 0, 1, 0, 0])
    uv = source("uv", [0, 0, 1, 1], '<param name="S"/><param name="T"/>')
    index = []
    for i, corner in enumerate(TRIS):
        index += [i % 3, corner, i % 2, 7]  # NORMAL at 0, VERTEX at 1, TEXCOORD at 2, 3 unknown
    inputs = (
        '<input semantic="NORMAL" source="#nrm" offset="0"/>'
        '<input semantic="VERTEX" source="#V" offset="1"/>'
        '<input semantic="TEXCOORD" source="#uv" offset="2" set="0"/>'
    )
    prim = triangles(index, inputs).replace(
        "<p>", '<input semantic="COLOR" source="#uv" offset="3"/><p>'
    )
    prim = prim.replace(" 7", " 0")
    geometry = cube_geometry(primitive=prim).replace("<vertices", normals + uv + "<vertices")
    compare(write(tmp_path, document(geometry, node(instance()))))


def test_vertex_input_naming_a_source(tmp_path):
    prim = triangles(TRIS, '<input semantic="VERTEX" source="#cube-pos" offset="0"/>')
    compare(write(tmp_path, document(cube_geometry(primitive=prim), node(instance()))))


def test_polygons(tmp_path):
    body = "".join(f"<p>{' '.join(map(str, q))}</p>" for q in QUADS[:5])
    body += f"<ph><p>{' '.join(map(str, QUADS[5]))}</p><h>0 1 2</h></ph>"
    prim = f'<polygons count="6"><input semantic="VERTEX" source="#V" offset="0"/>{body}</polygons>'
    compare(write(tmp_path, document(cube_geometry(primitive=prim), node(instance()))))


def test_trifans_and_odd_tristrips(tmp_path):
    fans = "".join(f"<p>{' '.join(map(str, q))}</p>" for q in QUADS[:3])
    strips = "".join(f"<p>{q[1]} {q[2]} {q[0]} {q[3]} {q[3]}</p>" for q in QUADS[3:])
    prim = (
        f'<trifans count="3"><input semantic="VERTEX" source="#V" offset="0"/>{fans}</trifans>'
        '<tristrips count="3"><input semantic="VERTEX" source="#V" offset="0"/>'
        f"{strips}</tristrips>"
    )
    compare(write(tmp_path, document(cube_geometry(primitive=prim), node(instance()))))


def test_even_tristrips(tmp_path):
    # pycollada 0.9 triangulates a strip of any length (0, 2, 4, ... then 1, 3, 5, ... wound 2-1-3)
    strips = "".join(f"<p>{q[1]} {q[2]} {q[0]} {q[3]}</p>" for q in QUADS)
    prim = (
        '<tristrips count="6"><input semantic="VERTEX" source="#V" offset="0"/>'
        f"{strips}</tristrips>"
    )
    triangles, _ = compare(
        write(tmp_path, document(cube_geometry(primitive=prim), node(instance())))
    )
    assert moments(triangles)[0] == pytest.approx(1.0)


def test_lines_skipped_and_non_mesh_geometry(tmp_path):
    lines = '<lines count="1"><input semantic="VERTEX" source="#V" offset="0"/><p>0 1</p></lines>'
    spline = '<geometry id="curve"><spline><source id="s"/></spline></geometry>'
    geometry = cube_geometry(primitive=triangles(TRIS) + lines) + spline
    compare(write(tmp_path, document(geometry, node(instance() + instance("curve")))))


def test_lines_only_is_empty(tmp_path):
    lines = '<lines count="1"><input semantic="VERTEX" source="#V" offset="0"/><p>0 1</p></lines>'
    path = write(tmp_path, document(cube_geometry(primitive=lines), node(instance())))
    with pytest.raises(MeshError) as theirs:
        _read_scene(path, ".dae")
    with pytest.raises(MeshError) as ours:
        read_collada(path.read_bytes(), path)
    assert ours.value.kind == theirs.value.kind == "empty"


def test_no_visual_scene_is_refused_as_trimesh_refuses_it(tmp_path):
    path = write(tmp_path, document(cube_geometry(), node(instance()), scene=""))
    with pytest.raises(MeshError) as theirs:
        _read_scene(path, ".dae")
    with pytest.raises(MeshError, match="no <scene>") as ours:
        read_collada(path.read_bytes(), path)
    assert ours.value.kind == theirs.value.kind == "unreadable"


def test_accessor_stride_read_where_pycollada_ignores_it(tmp_path):
    padded = [v for i in range(0, 24, 3) for v in (*CUBE[i : i + 3], 9.0)]
    geometry = cube_geometry().replace(
        source("cube-pos", CUBE), source("cube-pos", padded, stride=4)
    )
    path = write(tmp_path, document(geometry, node(instance())))
    ours, _ = read_collada(path.read_bytes(), path)
    assert moments(ours)[0] == pytest.approx(1.0)


def test_float_forms(tmp_path):
    values = ["-0.0", "1e0", "+1.", ".5e1", "1.0000000000000002", "0.30000000000000004"]
    geometry = cube_geometry().replace(">0.0 0.0 0.0 1.0", ">" + " ".join(values[:3]) + " 1.0")
    compare(write(tmp_path, document(geometry, node(instance()))))


# --- every installed robot's COLLADA file -------------------------------------------------------

PACKAGES = ["pybullet_data", "rtbdata", "dexmate_urdf", "fourier_robot_descriptions", "cmeel"]


def _installed() -> list[tuple[str, Path | None]]:
    roots = []
    for name in PACKAGES:
        spec = importlib.util.find_spec(name)
        if spec is None or not spec.submodule_search_locations:
            roots.append((name, None))
            continue
        for location in spec.submodule_search_locations:
            folder = Path(location)
            if name == "cmeel":
                folder = folder.parent / "cmeel.prefix" / "share" / "example-robot-data"
            roots.append((name, folder))
    if Path("/work/ext").is_dir():
        roots.append(("/work/ext", Path("/work/ext")))
    return roots


def _dae_files() -> list:
    params = []
    for name, folder in _installed():
        if folder is None or not folder.is_dir():
            params.append(pytest.param(None, id=name, marks=pytest.mark.skip(f"{name} absent")))
            continue
        for root, _, files in os.walk(folder):
            for file in sorted(files):
                if file.lower().endswith(".dae"):
                    path = Path(root) / file
                    params.append(pytest.param(path, id=str(path.relative_to(folder.parent))))
    return params


def _unmerged_trimesh(path: Path, tmp_path: Path, monkeypatch, strip_materials: bool = False):
    """
    trimesh's reading without its vertex merge (``Trimesh.process`` snaps vertices that agree
    to 8 decimals onto one another), and optionally of a copy without ``<bind_material>``
    (pycollada drops a geometry instance whose material is broken): the file's own triangles.
    """
    import trimesh
    from lxml import etree

    if strip_materials:
        root = etree.fromstring(path.read_bytes(), etree.XMLParser(huge_tree=True))
        for bind in list(root.iter("{*}bind_material")):
            bind.getparent().remove(bind)
        path = write(tmp_path, etree.tostring(root), "stripped.dae")
    with monkeypatch.context() as patch:
        patch.setattr(trimesh.Trimesh, "merge_vertices", lambda self, *a, **k: None)
        return _read_scene(path, ".dae")


#: how far trimesh's vertex merge (a vertex moved by under 1e-8 file units) may move a mass
MERGE_RTOL = 1e-7


@pytest.mark.slow
@pytest.mark.parametrize("path", _dae_files())
def test_installed_files_agree_with_trimesh(path, tmp_path, monkeypatch):
    try:
        theirs, their_unit = _read_scene(path, ".dae")
    except MeshError as refused:
        try:
            ours, unit = read_collada(path.read_bytes(), path)
        except MeshError as ours_refused:
            assert ours_refused.kind == refused.kind
            return
        # read where trimesh finds nothing: only where pycollada dropped every instance for a
        # broken material, and then the triangles are those of the file without its materials
        assert refused.kind == "empty" and b"<bind_material" in path.read_bytes()
        exact, _ = _unmerged_trimesh(path, tmp_path, monkeypatch, strip_materials=True)
        assert ours.shape == exact.shape
        assert_same_mass(ours, exact)
        return
    ours, unit = read_collada(path.read_bytes(), path)
    assert unit == their_unit
    assert ours.shape == theirs.shape
    if assert_same_mass(ours, theirs, rtol=MERGE_RTOL) > 1e-12:
        assert_same_mass(ours, _unmerged_trimesh(path, tmp_path, monkeypatch)[0])


# --- hostile files ------------------------------------------------------------------------------

LAUGHS = (
    '<?xml version="1.0"?><!DOCTYPE COLLADA [<!ENTITY a "aaaaaaaaaa">'
    + "".join(f'<!ENTITY {chr(98 + i)} "{("&" + chr(97 + i) + ";") * 10}">' for i in range(9))
    + "]>\n"
)


@pytest.mark.parametrize(
    "text, message",
    [
        (document(cube_geometry(), node(instance()) + "<extra>&j;</extra>", head=LAUGHS), "entity"),
        (
            document(
                cube_geometry(),
                node(instance()) + "<extra>&x;</extra>",
                head='<?xml version="1.0"?><!DOCTYPE c [<!ENTITY x SYSTEM "file:///etc/passwd">]>',
            ),
            "entity",
        ),
        (document(cube_geometry(), node(instance()))[:900], "XML"),
        (document(cube_geometry(primitive=triangles([0, 1, 8])), node(instance())), "vertex 8"),
        (document(cube_geometry(primitive=triangles([0, 1, -1])), node(instance())), "integers"),
        (document(cube_geometry(primitive=triangles([0, 1])), node(instance())), "whole"),
        (document(cube_geometry(primitive=triangles([0, 1.5, 2])), node(instance())), "integers"),
        (
            document(
                cube_geometry(
                    primitive='<polylist count="99"><input semantic="VERTEX" source="#V" '
                    'offset="0"/><vcount>4 9</vcount><p>0 1 2 3</p></polylist>'
                ),
                node(instance()),
            ),
            "vcount",
        ),
        (document(cube_geometry(), node(instance("nothing"))), "no <geometry>"),
        (document(cube_geometry(), node('<instance_node url="#n"/>')), "no <node>|itself"),
        (document(cube_geometry(), node("<matrix>1 2 3</matrix>" + instance())), "matrix"),
        (
            document(cube_geometry(), node(instance())).replace("1.0 1.0 0.0", "nan 1.0 0.0", 1),
            "non-finite",
        ),
        (
            document(cube_geometry(), node(instance())).replace("1.0 1.0 0.0", "1e308 1.0 0.0", 1),
            "non-finite",
        ),
        (
            document(cube_geometry(), node(instance())).replace("1.0 1.0 0.0", "1e39 1 0", 1),
            "non-finite",
        ),
        (
            document(cube_geometry(), node(instance())).replace("0.0 1.0 1.0", "0.0 1.0 x", 1),
            "numbers",
        ),
        ("\x00\x01 not xml", "XML"),
        (document(cube_geometry(), "<node>" * 300 + instance() + "</node>" * 300), "deep"),
    ],
    ids=[
        "billion-laughs",
        "external-entity",
        "truncated",
        "index-out-of-range",
        "negative-index",
        "partial-triangle",
        "float-index",
        "vcount-lies",
        "missing-geometry",
        "node-cycle",
        "short-matrix",
        "nan",
        "1e308",
        "float32-overflow",
        "garbage-float",
        "not-xml",
        "deep",
    ],
)
def test_hostile_files_are_refused(tmp_path, text, message):
    path = write(tmp_path, text)
    with pytest.raises(MeshError, match=message) as refused:
        read_collada(path.read_bytes(), path)
    assert refused.value.kind == "unreadable"
    assert "Traceback" not in refused.value.message


def test_a_count_that_lies_allocates_nothing(tmp_path):
    text = document(cube_geometry(), node(instance())).replace(
        'count="24"', 'count="999999999999999"'
    )
    text = text.replace('count="12"', 'count="999999999999999"')
    compare(write(tmp_path, text))


def test_an_instance_explosion_is_refused(tmp_path):
    library = node(instance() * 16, "l0") + "".join(
        node(f'<instance_node url="#l{i}"/>' * 16, f"l{i + 1}") for i in range(5)
    )
    path = write(
        tmp_path,
        document(cube_geometry(), node('<instance_node url="#l5"/>'), library_nodes=library),
    )
    with pytest.raises(MeshError, match="more than"):
        read_collada(path.read_bytes(), path)


def test_no_triangles_is_empty(tmp_path):
    path = write(tmp_path, document(cube_geometry(primitive=triangles([])), node(instance())))
    with pytest.raises(MeshError) as refused:
        read_collada(path.read_bytes(), path)
    assert refused.value.kind == "empty"


# --- the fast paths: against the general path and trimesh ------------------------------------


def test_normal_input_and_quads_as_exporters_write_them(tmp_path):
    """Blender's and SolidWorks' layout (VERTEX and NORMAL at offsets 0 and 1; 7 significant
    digits, exponents among them) for <triangles>, and a <polylist> of quads."""
    corners = [float(f"{v * 1.234567:.7g}") for v in CUBE]
    corners[1] = 1.234567e-05
    normals = source("cube-n", [0.0, 0.0, 1.0])
    quads = " ".join(f"{i} 0" for q in QUADS for i in q)
    tris = " ".join(f"{i} 0" for i in TRIS)
    inputs = (
        '<input semantic="VERTEX" source="#V" offset="0"/>'
        '<input semantic="NORMAL" source="#cube-n" offset="1"/>'
    )
    for primitive in (
        f"<triangles count='12'>{inputs}<p>{tris}</p></triangles>",
        f"<polylist count='6'>{inputs}<vcount>{' 4' * 6}</vcount><p>{quads}</p></polylist>",
    ):
        geometry = cube_geometry(primitive=primitive).replace("<vertices", normals + "<vertices")
        geometry = geometry.replace(
            " ".join(repr(float(v)) for v in CUBE), " ".join(map(repr, corners))
        )
        ours, _ = compare(write(tmp_path, document(geometry, node(instance()))))
        assert len(ours) == 12


@settings(max_examples=500, deadline=None)
@given(
    st.lists(st.integers(0, 10**9), min_size=1, max_size=40),
    st.sampled_from([" ", "  ", "\n", " \t", "\r\n"]),
    st.sampled_from(["", " ", "\n "]),
    st.integers(1, 4),
    st.data(),
)
def test_p_column_read_as_every_number_is(numbers, separator, edge, stride, data):
    """_ints of one input of a <p>: the numbers the whole reading gives, and their count."""
    offset = data.draw(st.integers(0, stride - 1))
    text = edge + separator.join(map(str, numbers)) + edge
    column, size = _ints(text, "p", stride, offset)
    every, total = _ints(text, "p")
    assert size == total == len(numbers)
    np.testing.assert_array_equal(column, every[offset::stride])
    # the fast path: single spaces, numbers of at most 8 digits, a text of 8 bytes at least
    laid_out = separator == " " and not edge and max(numbers) < 10**8 and len(text) >= 8
    if laid_out and stride > 1:
        assert _column(text.encode(), stride, offset) is not None  # the fast path read it


@settings(max_examples=500, deadline=None)
@given(
    st.lists(
        st.floats(-1e6, 1e6, allow_nan=False).map(lambda v: f"{v:.7g}")
        | st.sampled_from(
            ["-0", "+.5", "1.", "1e-30", "1E+3", "-1.5e22", "1.2e-5", "0.30000000000000004"]
        ),
        min_size=1,
        max_size=20,
    )
)
def test_floats_bit_for_bit_as_pycollada(values):
    text = " ".join(values)
    expected = np.fromstring(text, dtype=np.float32, sep=" ")
    assert _floats(text).tobytes() == expected.tobytes()


def test_shared_vertices_make_the_triangles_of_every_instance(tmp_path):
    """Two instances of one geometry, one moved: each has vertices of its own, the faces
    number them in order, and vertices[faces] are read_collada's triangles."""
    moved = '<node id="m"><translate>2 0 0</translate>' + instance() + "</node>"
    path = write(tmp_path, document(cube_geometry(), node(instance()) + moved))
    vertices, faces, _ = read_collada_shared(path.read_bytes(), path)
    triangles, _ = read_collada(path.read_bytes(), path)
    assert (vertices.shape, faces.shape) == ((16, 3), (24, 3))
    assert faces[:12].max() == 7 and faces[12:].min() == 8
    np.testing.assert_array_equal(vertices[faces], triangles)


def test_an_unused_vertex_may_be_anything(tmp_path):
    """Only what a face uses must be finite: an unused NaN vertex reads as before."""
    positions = CUBE + [float("nan")] * 3
    text = document(cube_geometry(), node(instance())).replace(
        source("cube-pos", CUBE), source("cube-pos", positions)
    )
    path = write(tmp_path, text)
    vertices, faces, _ = read_collada_shared(path.read_bytes(), path)
    assert len(vertices) == 9 and np.isnan(vertices[8]).all() and faces.max() == 7
