"""
The triangles MuJoCo builds from a Wavefront OBJ file, found without MuJoCo.

MuJoCo 4.0.0 reads an OBJ mesh with its OBJ decoder (``plugin/obj_decoder/obj_decoder.cc`` in
google-deepmind/mujoco), which parses the file with tinyobjloader (``ObjReader::ParseFromString``
with its default configuration: triangulation on, tinyobjloader's own triangulation, ``float``
coordinates) and keeps the faces of the *first shape* only. The rules below are those of
``tiny_obj_loader.h`` (``LoadObj``, ``parseTriple``, ``fixIndex``, ``exportGroupsToShape``,
``pnpoly``) as MuJoCo 4.0.0 runs them (its library holds the messages of tinyobjloader
v2.0.0rc11 and later, whose triangulation is unchanged since March 2021, commit 7ba4b65):

- A line ends at ``\\n``, ``\\r\\n`` or ``\\r`` (and is read up to a NUL). After its leading
  spaces and tabs, ``v``, ``f``, ``g``, ``o``, ``l`` or ``p`` followed by a space or a tab makes
  it a vertex, face, group, object, line or points line; every other line is ignored (a
  ``usemtl`` changes nothing here, since MuJoCo gives tinyobjloader no material file).
- A face's vertex index is the integer before the first ``/`` of each of its tokens (``7``,
  ``7/2``, ``7//3``, ``7/2/3``): 1-based, or negative, counted back from the vertices read so
  far; zero, or a negative index reaching before the first vertex, and tinyobjloader refuses
  the whole file. It refuses it too for a texture or normal index reaching before the first
  ``vt`` or ``vn``, for a token of more than two ``/`` and for an unresolvable ``l`` or ``p``
  index (:func:`_check_other_indices`).
- A ``g`` or ``o`` line ends a shape, which tinyobjloader keeps when it has a triangle (``g``),
  a triangle, line or point (``o``), or any face, line or point (the end of the file). MuJoCo
  uses the first shape kept: an OBJ file of several objects gives the first object's faces
  (all the file's vertices stay in the mesh, unused).
- A face of fewer than 3 vertices is dropped; a triangle is kept as written; a quad is split,
  in ``float`` arithmetic, along its shorter diagonal: ``(0, 1, 2), (0, 2, 3)`` when
  ``|v2 - v0|² < |v3 - v1|²``, else ``(0, 1, 3), (1, 2, 3)``; a quad naming a vertex not yet
  read when its shape ends is dropped.
- A larger polygon is cut by tinyobjloader's ear clipping (:func:`ear_clip`), which may leave
  vertices out when it finds no ear (of a self-intersecting polygon, say).

Vertices are returned as written (float64); the triangulation computes, as tinyobjloader does,
with their float32 values. Where tinyobjloader reads a malformed number or index leniently (a
``v`` line of fewer than 3 numbers, ``f 1.5 2 3``), this refuses the file instead.
"""

from __future__ import annotations

import itertools
import re

import numpy as np
from numpy.typing import NDArray

#: the largest polygon triangulated (ear clipping takes time quadratic in its vertices)
MAX_POLYGON_VERTICES = 10_000
#: the polygon vertices ear-clipped in one lock step
_CHUNK = 1 << 21

_F32 = np.float32
_HALF = _F32(0.5)
_ZERO = _F32(0.0)
#: std::numeric_limits<float>::epsilon()
_EPSILON = np.finfo(np.float32).eps

# line kinds
_OTHER, _VERTEX, _FACE, _GROUP, _OBJECT, _PRIMITIVE = range(6)
_LETTERS = {b"v": _VERTEX, b"f": _FACE, b"g": _GROUP, b"o": _OBJECT, b"l": _PRIMITIVE}
_LETTERS[b"p"] = _PRIMITIVE


def obj_triangles(data: bytes) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """
    The mesh MuJoCo's OBJ decoder builds from an OBJ file's bytes.

    Returns
    -------
    vertices : (n, 3) float64
      Every ``v`` line's coordinates, as written.
    faces : (m, 3) int64
      Vertex indices (0-based) of each triangle, in the order and winding MuJoCo gives them;
      none when the first shape has no triangle.

    Raises
    ------
    ValueError
      For a file MuJoCo refuses (a zero or unresolvable face index; a triangle naming a vertex
      the file lacks) or whose numbers this does not read (see the module's notes).
    """
    lines = _lines(data)
    kinds = _kinds(lines)
    is_vertex = kinds == _VERTEX
    vertices = _vertices(list(itertools.compress(lines, is_vertex)))
    count = len(vertices)

    is_face = kinds == _FACE
    face_lines = list(itertools.compress(lines, is_face))
    sizes, indices = _face_indices(face_lines)
    _check_other_indices(lines, kinds, face_lines)
    # vertices read before each line, and at the end of each shape (a g or o line, or the end)
    read = np.cumsum(is_vertex)
    boundary = (kinds == _GROUP) | (kinds == _OBJECT)
    shape = np.cumsum(boundary)
    ends = np.flatnonzero(boundary)
    ended = np.append(read[ends], count)
    end_kinds = [*kinds[ends].tolist(), None]
    face_shape = shape[is_face]
    indices = _resolve(indices, np.repeat(read[is_face], sizes), face_lines, sizes)

    starts = np.cumsum(sizes) - sizes
    # tinyobjloader's coordinates (one unused row when there are none: nothing is read there)
    coordinates = vertices.astype(np.float32) if count else np.zeros((1, 3), np.float32)
    chosen = _first_shape(
        sizes, starts, indices, coordinates, face_shape, ended, end_kinds, kinds, shape
    )
    if chosen is None:
        return vertices, np.zeros((0, 3), np.int64)
    mine = np.flatnonzero(face_shape == chosen)
    faces = _triangulate(sizes[mine], starts[mine], indices, coordinates, int(ended[chosen]))
    if len(faces) and faces.max() >= count:
        raise ValueError(
            f"a face names vertex {int(faces.max()) + 1}, but the file has {count} vertices"
        )
    return vertices, faces


def _lines(data: bytes) -> list[bytes]:
    """The lines as tinyobjloader reads them: up to a NUL, without leading spaces and tabs."""
    lines = data.splitlines()  # bytes: \n, \r\n and \r only, as tinyobjloader's safeGetline
    if b"\0" in data:
        lines = [line.partition(b"\0")[0] for line in lines]
    if data[:1] in (b" ", b"\t") or any(
        mark in data for mark in (b"\n ", b"\n\t", b"\r ", b"\r\t")
    ):
        lines = [line.lstrip(b" \t") for line in lines]
    return lines


def _kinds(lines: list[bytes]) -> NDArray[np.int8]:
    """Each line's kind, from its first two characters."""
    heads = np.array([line[:2] for line in lines], dtype="S2").view(np.uint8).reshape(-1, 2)
    spaced = (heads[:, 1] == ord(" ")) | (heads[:, 1] == ord("\t"))
    kinds = np.full(len(lines), _OTHER, dtype=np.int8)
    for letter, kind in _LETTERS.items():
        kinds[spaced & (heads[:, 0] == letter[0])] = kind
    return kinds


def _vertices(lines: list[bytes]) -> NDArray[np.float64]:
    """The first three numbers of each ``v`` line (a colour or weight after them is ignored)."""
    numbers = np.fromiter(map(len, map(bytes.split, lines)), np.intp, len(lines)) - 1
    if len(lines) and numbers.min() < 3:
        line = lines[int(np.argmin(numbers))]
        raise ValueError(f"a `v` line has fewer than 3 coordinates: {quoted_line(line)}")
    try:
        if np.all(numbers == 3):
            tokens = b" ".join(line[2:] for line in lines).split()
            return np.array(tokens, dtype=np.float64).reshape(-1, 3)
        return np.array([line.split()[1:4] for line in lines], dtype=np.float64).reshape(-1, 3)
    except ValueError as error:
        raise ValueError(f"a `v` line holds a coordinate that is not a number ({error})") from None


def _face_indices(lines: list[bytes]) -> tuple[NDArray[np.intp], NDArray[np.int64]]:
    """Each ``f`` line's number of vertices, and every vertex index as written, flat."""
    sizes = np.fromiter(map(len, map(bytes.split, lines)), np.intp, len(lines)) - 1
    body = b" ".join(line[2:] for line in lines)
    tokens = body.split()
    if b"/" in body:
        extra = _THIRD_SLASH.search(body)
        if extra:  # tinyobjloader reads what follows the triple as an index, and fails
            start = max(body.rfind(b" ", 0, extra.start()), body.rfind(b"\t", 0, extra.start()))
            token = body[start + 1 :].split(maxsplit=1)[0]
            raise ValueError(f"an `f` line's index has more than two `/`: {quoted_line(token)}")
        tokens = [token.partition(b"/")[0] for token in tokens]
    try:
        indices = np.array(tokens, dtype=np.int64)
    except (ValueError, OverflowError) as error:
        raise ValueError(f"an `f` line holds an index that is not an integer ({error})") from None
    return sizes, indices


# a texture or normal index that may be negative: tinyobjloader refuses one before the first
_NEGATIVE_AFTER_SLASH = re.compile(rb"/\s*-")
_THIRD_SLASH = re.compile(rb"/[^\s/]*/[^\s/]*/")
_ATOI = re.compile(rb"\s*([+-]?\d*)")
_TOKEN_END = re.compile(rb"[^/ \t\r]*")
_BLANKS = re.compile(rb"[ \t\r]*")


def _check_other_indices(lines: list[bytes], kinds: NDArray[np.int8], faces: list[bytes]) -> None:
    """
    A ValueError where tinyobjloader refuses the file for an index other than a face's vertex:
    a negative texture or normal index reaching before the first one (``f 1/-2 2/-2 3/-2``
    with one ``vt``, or ``f 1/ -2 3``, whose ``-2`` is read as a texture index), or a line or
    points index it cannot resolve. The lines that may hold one are read as ``parseTriple``
    reads them, one by one (they are rare).
    """
    suspects = np.flatnonzero(kinds == _PRIMITIVE).tolist()
    if _NEGATIVE_AFTER_SLASH.search(b"\n".join(faces)):
        suspects += [
            k
            for k in np.flatnonzero(kinds == _FACE).tolist()
            if _NEGATIVE_AFTER_SLASH.search(lines[k])
        ]
    if not suspects:
        return
    read = {}
    for name in (b"vt", b"vn"):
        marks = [line[:2] == name and line[2:3] in (b" ", b"\t") for line in lines]
        read[name] = np.cumsum(marks) - marks
    vertices = np.cumsum(kinds == _VERTEX)
    for k in sorted(suspects):
        line = lines[k]
        body = line[2:].lstrip(b" \t") if kinds[k] == _FACE else line[2:]
        counts = (int(vertices[k]), int(read[b"vt"][k]), int(read[b"vn"][k]))
        if _refused(body, counts):
            raise ValueError(f"tinyobjloader cannot resolve an index of {quoted_line(line)}")


def _refused(body: bytes, counts: tuple[int, int, int]) -> bool:
    """Whether tinyobjloader's ``parseTriple`` fails on a line's indices (``atoi`` semantics)."""

    def atoi(at: int) -> int:
        digits = _ATOI.match(body, at).group(1)
        return int(digits) if digits.strip(b"+-") else 0

    def fails(value: int, count: int) -> bool:  # a texture or normal index: zero is allowed
        return value < 0 and count + value < 0

    at, end = 0, len(body)
    while at < end:
        value = atoi(at)
        if value == 0 or fails(value, counts[0]):
            return True
        at = _TOKEN_END.match(body, at).end()
        if at < end and body[at] == ord("/"):
            at += 1
            normal_only = at < end and body[at] == ord("/")
            at += normal_only
            if fails(atoi(at), counts[2 if normal_only else 1]):
                return True
            at = _TOKEN_END.match(body, at).end()
            if not normal_only and at < end and body[at] == ord("/"):
                at += 1
                if fails(atoi(at), counts[2]):
                    return True
                at = _TOKEN_END.match(body, at).end()
        at = _BLANKS.match(body, at).end()
    return False


def _resolve(
    indices: NDArray[np.int64],
    read: NDArray[np.int64],
    lines: list[bytes],
    sizes: NDArray[np.intp],
) -> NDArray[np.int64]:
    """0-based vertex indices (tinyobjloader's ``fixIndex``); a ValueError where it fails."""
    resolved = np.where(indices > 0, indices - 1, read + indices)
    bad = (indices == 0) | (resolved < 0)
    if bad.any():
        token = int(np.argmax(bad))
        line = lines[int(np.searchsorted(np.cumsum(sizes), token, side="right"))]
        what = "vertex 0" if indices[token] == 0 else "a vertex before the first (relative index)"
        raise ValueError(f"an `f` line names {what}: {quoted_line(line)}")
    return resolved


def _first_shape(
    sizes: NDArray[np.intp],
    starts: NDArray[np.intp],
    indices: NDArray[np.int64],
    coordinates: NDArray[np.float32],
    face_shape: NDArray[np.intp],
    ended: NDArray[np.int64],
    end_kinds: list[int | None],
    kinds: NDArray[np.int8],
    shape: NDArray[np.intp],
) -> int | None:
    """The first shape tinyobjloader keeps (which MuJoCo uses), or ``None``."""
    shapes = len(ended)
    faces = np.bincount(face_shape, minlength=shapes)
    others = np.bincount(shape[kinds == _PRIMITIVE], minlength=shapes)
    triangles = np.bincount(face_shape[sizes == 3], minlength=shapes)
    quad, _ = _read_quads(sizes, starts, indices, lambda quads: ended[face_shape[quads], None])
    triangles += np.bincount(face_shape[quad], minlength=shapes)
    polygons = np.bincount(face_shape[sizes > 4], minlength=shapes)
    for index, (kind, face_count, other_count, triangle_count, polygon_count) in enumerate(
        zip(
            end_kinds,
            faces.tolist(),
            others.tolist(),
            triangles.tolist(),
            polygons.tolist(),
            strict=True,
        )
    ):
        if not (face_count or other_count):
            continue
        kept = triangle_count > 0
        if not kept and polygon_count:
            mine = np.flatnonzero((face_shape == index) & (sizes > 4))
            cut, _ = ear_clip(indices, starts[mine], sizes[mine], coordinates, ended[index])
            kept = len(cut) > 0
        if kept or (kind != _GROUP and other_count) or kind is None:
            return index
    return None


def _triangulate(
    sizes: NDArray[np.intp],
    starts: NDArray[np.intp],
    indices: NDArray[np.int64],
    coordinates: NDArray[np.float32],
    read: int,
) -> NDArray[np.int64]:
    """The triangles of one shape's faces, in order; ``read``: its vertices when it ends."""
    order = np.arange(len(sizes))
    parts, owners = [], []

    triangle = sizes == 3
    parts.append(indices[starts[triangle, None] + np.arange(3)])
    owners.append(order[triangle])

    quad, corners = _read_quads(sizes, starts, indices, lambda _: read)
    points = coordinates[corners]
    shorter = _squared(points[:, 2] - points[:, 0]) < _squared(points[:, 3] - points[:, 1])
    split = np.where(
        shorter[:, None, None],
        np.array([[0, 1, 2], [0, 2, 3]]),
        np.array([[0, 1, 3], [1, 2, 3]]),
    )
    parts.append(np.take_along_axis(corners[:, None, :], split, axis=2).reshape(-1, 3))
    owners.append(np.repeat(quad, 2))

    polygon = np.flatnonzero(sizes > 4)
    if len(polygon):
        cut, owner = ear_clip(indices, starts[polygon], sizes[polygon], coordinates, read)
        parts.append(cut)
        owners.append(polygon[owner])

    faces = np.concatenate(parts).astype(np.int64, copy=False)
    return faces[np.argsort(np.concatenate(owners), kind="stable")]


def _read_quads(sizes, starts, indices, read) -> tuple[NDArray[np.intp], NDArray[np.int64]]:
    """The quads whose corners had all been read when their shape ended (tinyobjloader drops
    the others), and their corners; ``read(quads)``: the vertices read by then, per quad."""
    quad = np.flatnonzero(sizes == 4)
    corners = indices[starts[quad, None] + np.arange(4)]
    valid = (corners < read(quad)).all(axis=1)
    return quad[valid], corners[valid]


def _squared(edges: NDArray[np.float32]) -> NDArray[np.float32]:
    """``x*x + y*y + z*z`` in float, summed left to right as tinyobjloader writes it."""
    return edges[:, 0] * edges[:, 0] + edges[:, 1] * edges[:, 1] + edges[:, 2] * edges[:, 2]


def ear_clip(
    indices: NDArray[np.int64],
    starts: NDArray[np.intp],
    sizes: NDArray[np.intp],
    coordinates: NDArray[np.float32],
    read: int,
) -> tuple[NDArray[np.int64], NDArray[np.intp]]:
    """
    tinyobjloader's ear clipping of polygons of more than 4 vertices, in float arithmetic.

    It projects a polygon on the plane of two axes: ``y, z`` when the first corner whose cross
    product has a component above float epsilon has its largest along ``x``, ``x, y`` when along
    ``z``, else ``x, z`` (``y, z`` when no corner has one). From vertex 0 on, it takes three
    consecutive vertices as an ear when ``cross · area >= 0`` (``cross``: the corner's cross
    product; ``area``: half the cross product of the first two vertices' *positions*, as
    tinyobjloader has it) and no other remaining vertex lies inside them (``pnpoly``), cuts it
    (removing the middle vertex) and tries again from the same place; otherwise it moves one
    vertex on. It stops when 3 vertices remain (the last triangle) or after a full turn without
    an ear (the rest is dropped). A vertex not read yet when the shape ends counts as ``(0, 0)``
    in an ear and is skipped as an "other vertex".

    The polygons are cut together, in lock step (sizes grouped by powers of two).

    Parameters
    ----------
    indices : (n,) int
      Vertex indices, 0-based: polygon ``i``'s are ``indices[starts[i] : starts[i] + sizes[i]]``.
    starts, sizes : (m,) int
      Where each polygon's indices start, and how many (at least 5).
    coordinates : (n, 3) float32
      The file's vertices, as tinyobjloader holds them.
    read : int
      The vertices read when the polygons' shape ends.

    Returns
    -------
    triangles : (t, 3) int64
      Vertex indices, each polygon's in the order cut, polygon after polygon, each wound as its
      polygon.
    owners : (t,) int
      The polygon (0 to m - 1) of each triangle.
    """
    parts, owners = [], []
    if sizes.max(initial=0) > MAX_POLYGON_VERTICES:
        raise ValueError(
            f"a face has {int(sizes.max())} vertices (more than {MAX_POLYGON_VERTICES}); split it"
        )
    bucket = np.ceil(np.log2(np.maximum(sizes, 2))).astype(int)
    with np.errstate(all="ignore"):
        for width in np.unique(bucket).tolist():
            group = np.flatnonzero(bucket == width)
            # in chunks of a few million vertices: each step copies its arrays
            for rows in np.array_split(group, -(-len(group) * 2**width // _CHUNK)):
                size = sizes[rows]
                columns = np.minimum(np.arange(size.max()), size[:, None] - 1)
                polygons = indices[starts[rows, None] + columns]
                cut, owner = _ear_clip_group(polygons, size, coordinates, read)
                parts.append(cut)
                owners.append(rows[owner])
    triangles = np.concatenate([np.zeros((0, 3), np.int64), *parts]).astype(np.int64)
    owner = np.concatenate([np.zeros(0, np.intp), *owners])
    order = np.argsort(owner, kind="stable")
    return triangles[order], owner[order]


def _ear_clip_group(
    polygons: NDArray[np.int64],
    sizes: NDArray[np.intp],
    coordinates: NDArray[np.float32],
    read: int,
) -> tuple[NDArray[np.int64], NDArray[np.intp]]:
    """:func:`ear_clip` of polygons of similar sizes, each step one iteration of every one."""
    count, width = polygons.shape
    columns = np.arange(width)
    used = columns < sizes[:, None]
    known = used & (polygons < read)
    points = coordinates[np.where(known, polygons, 0)]
    first, second = _axes(points, known, sizes)
    xs = np.where(known, np.take_along_axis(points, first[:, None, None], 2)[..., 0], _ZERO)
    ys = np.where(known, np.take_along_axis(points, second[:, None, None], 2)[..., 0], _ZERO)
    xs, ys = xs.astype(np.float32), ys.astype(np.float32)

    # remaining: positions in the polygon of the vertices not cut off yet, in order
    remaining = np.tile(columns, (count, 1))
    size = sizes.copy()
    guess = np.zeros(count, np.intp)
    iterations, previous = sizes.copy(), sizes.copy()
    triangles, owners, steps = [], [], []
    active = np.arange(count)
    step = 0
    others = np.arange(max(width - 3, 0))
    while True:
        active = active[(size[active] > 3) & (iterations[active] > 0)]
        if not len(active):
            break
        s, g = size[active], guess[active]
        g = np.where(g >= s, g - s, g)
        iterations[active] = np.where(previous[active] != s, s, iterations[active] - 1)
        previous[active] = s
        live = remaining[active]
        ear = (g[:, None] + np.arange(3)) % s[:, None]
        corner = np.take_along_axis(live, ear, 1)
        vx = np.take_along_axis(xs[active], corner, 1)
        vy = np.take_along_axis(ys[active], corner, 1)
        cross = (vx[:, 1] - vx[:, 0]) * (vy[:, 2] - vy[:, 1]) - (vy[:, 1] - vy[:, 0]) * (
            vx[:, 2] - vx[:, 1]
        )
        area = (vx[:, 0] * vy[:, 1] - vy[:, 0] * vx[:, 1]) * _HALF
        internal = cross * area < _ZERO
        other = np.take_along_axis(live, (g[:, None] + 3 + others) % s[:, None], 1)
        valid = (others < (s - 3)[:, None]) & np.take_along_axis(known[active], other, 1)
        tx = np.take_along_axis(xs[active], other, 1)
        ty = np.take_along_axis(ys[active], other, 1)
        overlap = (_inside(vx, vy, tx, ty) & valid).any(axis=1)
        ears = ~internal & ~overlap

        done = active[ears]
        triangles.append(np.take_along_axis(polygons[done], corner[ears], 1))
        owners.append(done)
        steps.append(np.full(len(done), step))
        # cut the ear's middle vertex off: the positions after it move one place down
        middle = ear[ears, 1]
        shift = np.where(columns >= middle[:, None], np.minimum(columns + 1, width - 1), columns)
        remaining[done] = np.take_along_axis(live[ears], shift, 1)
        size[done] -= 1
        guess[active] = np.where(ears, g, g + 1)
        step += 1
    last = np.flatnonzero(size == 3)
    triangles.append(np.take_along_axis(polygons[last], remaining[last, :3], 1))
    owners.append(last)
    steps.append(np.full(len(last), step))
    owner, order = np.concatenate(owners), np.concatenate(steps)
    sequence = np.lexsort((order, owner))
    return np.concatenate(triangles)[sequence], owner[sequence]


def _axes(
    points: NDArray[np.float32], known: NDArray[np.bool_], sizes: NDArray[np.intp]
) -> tuple[NDArray[np.intp], NDArray[np.intp]]:
    """The two axes tinyobjloader projects each polygon on (see :func:`ear_clip`)."""
    width = known.shape[1]
    columns = np.arange(width)
    following = [(columns + k) % sizes[:, None] for k in (1, 2)]
    p0 = points
    p1, p2 = (np.take_along_axis(points, f[:, :, None], 1) for f in following)
    ok = (columns < sizes[:, None]) & known
    for f in following:
        ok &= np.take_along_axis(known, f, 1)
    e0, e1 = p1 - p0, p2 - p1
    cx = np.abs(e0[..., 1] * e1[..., 2] - e0[..., 2] * e1[..., 1])
    cy = np.abs(e0[..., 2] * e1[..., 0] - e0[..., 0] * e1[..., 2])
    cz = np.abs(e0[..., 0] * e1[..., 1] - e0[..., 1] * e1[..., 0])
    corner = ok & ((cx > _EPSILON) | (cy > _EPSILON) | (cz > _EPSILON))
    at = np.argmax(corner, axis=1)[:, None]
    cx, cy, cz = (np.take_along_axis(c, at, 1)[:, 0] for c in (cx, cy, cz))
    along_x = (cx > cy) & (cx > cz) | ~corner.any(axis=1)
    along_z = (cz > cx) & (cz > cy)
    first = np.where(along_x, 1, 0)
    second = np.where(along_x, 2, np.where(along_z, 1, 2))
    return first, second


def _inside(
    vx: NDArray[np.float32], vy: NDArray[np.float32], tx: NDArray[np.float32], ty: NDArray
) -> NDArray[np.bool_]:
    """tinyobjloader's ``pnpoly`` of triangles ``(a, 3)``, each for test points ``(a, j)``."""
    inside = np.zeros(tx.shape, dtype=bool)
    j = 2
    for i in range(3):
        xi, yi, xj, yj = vx[:, i, None], vy[:, i, None], vx[:, j, None], vy[:, j, None]
        crosses = (yi > ty) != (yj > ty)
        inside ^= crosses & (tx < (xj - xi) * (ty - yi) / (yj - yi) + xi)
        j = i
    return inside


def quoted_line(line: bytes) -> str:
    """A line for a message: decoded, at most 80 characters."""
    text = line.decode("utf-8", "replace")
    return f"`{text[:80]}{'…' if len(text) > 80 else ''}`"
