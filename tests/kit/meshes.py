"""
Mesh files written from triangles ((n, 3, 3) arrays, wound counter-clockwise seen from outside),
byte by byte, without the code under test or trimesh's exporters: binary and ASCII STL, OBJ.
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


def write_binary_stl(path: Path, triangles, header: bytes = HEADER) -> Path:
    return write(path, binary_stl(triangles, header))


def write_ascii_stl(path: Path, triangles) -> Path:
    return write(path, ascii_stl(triangles))


def write_box_stl(path: Path, size) -> Path:
    """A closed box of ``size``, centred on the origin, as a binary STL file."""
    return write_binary_stl(path, box_triangles(size, low=np.multiply(size, -0.5)))
