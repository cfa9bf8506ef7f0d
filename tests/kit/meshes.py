"""
Mesh files written from triangles ((n, 3, 3) arrays, wound counter-clockwise seen from outside),
byte by byte, without the code under test or trimesh's exporters: binary and ASCII STL, OBJ, and
COLLADA with a textured material.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from kit import write

# the corners of the unit cube, bit i of the index set along x, y, z (x the high bit), and its six
# faces as corner quads wound counter-clockwise seen from outside
_CORNERS = np.array([[i >> 2 & 1, i >> 1 & 1, i & 1] for i in range(8)], dtype=np.float64)
_QUADS = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
_FACES = np.array([(a, b, c) for a, b, c, d in _QUADS] + [(a, c, d) for a, b, c, d in _QUADS])

# a binary STL: an 80-byte header (not starting with "solid"), the count, one record a triangle
HEADER = b"binary STL written by a test"
_RECORD = np.dtype([("normal", "<f4", 3), ("vertices", "<f4", (3, 3)), ("attribute", "<u2")])


def box_triangles(size, low=(0.0, 0.0, 0.0)) -> np.ndarray:
    """The 12 triangles (float64) of an axis-aligned box of ``size``, lowest corner ``low``."""
    corners = np.asarray(low, dtype=np.float64) + np.asarray(size, dtype=np.float64) * _CORNERS
    return corners[_FACES]


def square_triangles() -> np.ndarray:
    """The unit square in the plane z = 0 as two triangles: a surface that encloses nothing."""
    corners = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float64)
    return corners[[[0, 1, 2], [0, 2, 3]]]


def binary_stl(triangles, header: bytes = HEADER) -> bytes:
    """
    The 80-byte header (padded with spaces), the uint32 count and one 50-byte record a triangle,
    its normal zero and its attribute word set, as readers must skip it.
    """
    records = np.zeros(len(triangles), dtype=_RECORD)
    # coordinates beyond float32 are written as infinity, as a float32 writer stores them: some
    # tests write such files on purpose (extreme numbers), so the overflow is not a warning
    with np.errstate(over="ignore"):
        records["vertices"] = triangles
    records["attribute"] = 0x1234
    count = np.uint32(len(triangles)).astype("<u4").tobytes()
    return header.ljust(80, b" ")[:80] + count + records.tobytes()


def ascii_stl(triangles) -> str:
    """ASCII STL with every coordinate written in full (``repr``), so nothing is rounded."""
    lines = ["solid test"]
    for triangle in np.asarray(triangles, dtype=np.float64).tolist():
        lines += [" facet normal 0 0 0", "  outer loop"]
        lines += [f"   vertex {x!r} {y!r} {z!r}" for x, y, z in triangle]
        lines += ["  endloop", " endfacet"]
    return "\n".join([*lines, "endsolid test", ""])


def obj(triangles) -> str:
    """Wavefront OBJ: each distinct vertex once (``repr``), then one face a triangle."""
    flat = np.asarray(triangles, dtype=np.float64).reshape(-1, 3)
    vertices, index = np.unique(flat, axis=0, return_inverse=True)
    faces = index.reshape(-1, 3) + 1
    return "".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in vertices.tolist()) + "".join(
        f"f {a} {b} {c}\n" for a, b, c in faces.tolist()
    )


def textured_collada(triangles, image: str = "skin.png") -> str:
    """
    COLLADA 1.4.1 whose one material is textured with the file ``image`` (an ``<image>`` whose
    ``<init_from>`` names it) as its diffuse and emission colours and, in an ``<extra>``, as a
    bump map, the way Blender and 3ds Max export one. trimesh reads the triangles and tries to
    load each texture for its renderer; the mass needs none of them.
    """
    flat = np.asarray(triangles, dtype=np.float64).reshape(-1, 3)
    positions = " ".join(repr(v) for v in flat.ravel().tolist())
    indices = " ".join(str(i) for i in range(len(flat)))
    texture = '<texture texture="skin-sampler" texcoord="UVMap"/>'
    return f"""<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="1" name="meter"/><up_axis>Z_UP</up_axis></asset>
  <library_images><image id="skin"><init_from>{image}</init_from></image></library_images>
  <library_effects>
    <effect id="skin-effect">
      <profile_COMMON>
        <newparam sid="skin-surface">
          <surface type="2D"><init_from>skin</init_from></surface>
        </newparam>
        <newparam sid="skin-sampler"><sampler2D><source>skin-surface</source></sampler2D></newparam>
        <technique sid="common">
          <phong><emission>{texture}</emission><diffuse>{texture}</diffuse></phong>
          <extra><technique profile="FCOLLADA"><bump>{texture}</bump></technique></extra>
        </technique>
      </profile_COMMON>
    </effect>
  </library_effects>
  <library_materials>
    <material id="skin-material"><instance_effect url="#skin-effect"/></material>
  </library_materials>
  <library_geometries>
    <geometry id="part"><mesh>
      <source id="part-positions">
        <float_array id="part-array" count="{flat.size}">{positions}</float_array>
        <technique_common><accessor source="#part-array" count="{len(flat)}" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common>
      </source>
      <vertices id="part-vertices"><input semantic="POSITION" source="#part-positions"/></vertices>
      <triangles material="skin" count="{len(flat) // 3}">
        <input semantic="VERTEX" source="#part-vertices" offset="0"/><p>{indices}</p>
      </triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes><visual_scene id="scene"><node id="part-node">
    <instance_geometry url="#part"><bind_material><technique_common>
      <instance_material symbol="skin" target="#skin-material"/>
    </technique_common></bind_material></instance_geometry>
  </node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
"""


def png_1x1() -> bytes:
    """A valid PNG of one green pixel, for a texture that exists."""
    import struct
    import zlib

    def chunk(kind: bytes, data: bytes) -> bytes:
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", 1, 1, 8, 2, 0, 0, 0)
    pixels = zlib.compress(b"\x00\x00\xff\x00")
    return (
        b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", pixels) + chunk(b"IEND", b"")
    )


def write_textured_collada(path: Path, triangles, *, image: bool) -> Path:
    """:func:`textured_collada` at ``path``, its texture ``skin.png`` beside it when ``image``."""
    if image:
        write(path.parent / "skin.png", png_1x1())
    return write(path, textured_collada(triangles))


def without_pillow(folder: Path) -> Path:
    """
    ``folder``, holding a package ``PIL`` whose import fails as it does when Pillow is not
    installed: first on PYTHONPATH, it hides Pillow from a subprocess (trimesh then logs
    "No module named 'PIL'" for every texture it tries to load).
    """
    refusal = "raise ImportError(\"No module named 'PIL'\", name='PIL')\n"
    write(folder / "PIL" / "__init__.py", refusal)
    return folder


def write_binary_stl(path: Path, triangles, header: bytes = HEADER) -> Path:
    return write(path, binary_stl(triangles, header))


def write_ascii_stl(path: Path, triangles) -> Path:
    return write(path, ascii_stl(triangles))


def write_box_stl(path: Path, size) -> Path:
    """A closed box of ``size``, centred on the origin, as a binary STL file."""
    return write_binary_stl(path, box_triangles(size, low=np.multiply(size, -0.5)))


def torus_triangles(major: float, minor: float, rings: int, sides: int) -> np.ndarray:
    """
    A closed torus about z (radii ``major`` and ``minor``) as ``2 · rings · sides`` triangles
    (float64), wound counter-clockwise seen from outside: a large mesh with no poles.
    """
    u = 2 * np.pi * np.arange(rings) / rings
    v = 2 * np.pi * np.arange(sides) / sides
    uu, vv = np.meshgrid(u, v, indexing="ij")
    radius = major + minor * np.cos(vv)
    points = np.stack([radius * np.cos(uu), radius * np.sin(uu), minor * np.sin(vv)], axis=-1)
    i, j = np.meshgrid(np.arange(rings), np.arange(sides), indexing="ij")
    a, b = points[i, j], points[(i + 1) % rings, j]
    c, d = points[(i + 1) % rings, (j + 1) % sides], points[i, (j + 1) % sides]
    first = np.stack([a, b, c], axis=-2).reshape(-1, 3, 3)
    second = np.stack([a, c, d], axis=-2).reshape(-1, 3, 3)
    return np.concatenate([first, second])
