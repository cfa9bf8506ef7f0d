"""
The triangle soup trimesh 5.2 reads from a Wavefront OBJ file, found without trimesh.

``trimesh.load_scene(..., file_type="obj", process=False)`` runs ``load_obj`` of
``trimesh/exchange/obj.py`` (with ``group_material=True``, no object or group splitting), and
:func:`.mesh_formats._scene_parts` flattens its meshes (identity transforms) into one soup.
:func:`obj_soup` gives the same triangles, each with the same vertices in the same order, by
these rules (those of trimesh 5.2, read from its source and checked against it):

- Text: the bytes are decoded as UTF-8, stripped of surrounding whitespace, ``\\r\\n`` becomes
  ``\\n``, and a backslash before a newline joins two lines. Lines end at ``\\n`` only (a lone
  ``\\r`` is a character of the line, and separates numbers as a space does).
- Vertices: every line starting with ``v`` and a space, *anywhere* in the file (a face may name a
  vertex written after it). The numbers are read all at once (``np.fromstring``): any text that is
  not a number (a trailing ``# comment``, ``nan`` aside) makes trimesh fail. Each row has as many
  numbers as the first ``v`` line; when the file's numbers do not fill such rows (some lines hold
  a colour or a ``w``, others not), each row is cut to the shortest line's count. The first three
  numbers are the coordinates. ``vt`` and ``vn`` lines are read the same way, only to fail where
  trimesh fails; they change no triangle.
- Faces: lines starting with ``f`` (at the first column; ``f\\t1 2 3`` and ``foo`` too: the
  text after the ``f``) between the first line starting with ``usemtl``, ``o``, ``f``, ``g`` or
  ``s`` and a space, and the last line starting with ``f`` and a space (see :func:`_dropped` for
  the one such line trimesh skips). ``usemtl`` (anywhere in that stretch, even in a comment)
  starts a new material and cuts its line there; ``o``, ``g``, ``s``, ``l``, ``mtllib`` and
  other lines are ignored. The faces of
  one material are read together: when all their lines have the same count of numbers (slashes
  counted as separators), every line is read with the layout of the *first* line (``v``,
  ``v/vt``, ``v//vn``, ``v/vt/vn``: the vertex index is every ``count / tokens``-th number), and
  a line of 1–2 vertices gives no triangle; otherwise each line is read on its own: its tokens'
  numbers before the first ``/`` (Python ``int``), lines of fewer than 3 tokens dropped.
- Indices: ``k > 0`` is vertex ``k - 1``; ``0`` and negative indices are Python indices into all
  the file's vertices (``-1``: the *last* vertex of the file, not the one before the face;
  ``0``: the first). An index past either end makes trimesh fail.
- Triangles: a triangle as written; a quad ``(0, 1, 2), (2, 3, 0)``; a larger polygon a fan
  ``(0, i + 1, i + 2)``. Nothing is merged or dropped (``process=False``): degenerate triangles
  and repeated vertices stay.
- No ``v`` line, or no face: no triangle.

Where trimesh reads a malformed file silently, this matches it (an index 0, a negative index
counted from the file's end, faces of one count read with another line's layout, a line cut at
``usemtl``, 1–2 vertex faces dropped). Where trimesh fails (an index past either end, text that
is not a number), :func:`obj_soup` raises ``ValueError`` with a one-line reason. It also refuses
these files, which trimesh reads:

- bytes that are not UTF-8 (trimesh guesses an encoding with ``charset_normalizer``, when
  installed, and fails without it);
- in a ``v``, ``vt``, ``vn`` or ``f`` line, a character outside ASCII, or a control character
  but tab, ``\\v``, ``\\f`` and ``\\r`` (a NUL ends numpy's C string; ``\\x1c``-``\\x1f``
  separate Python's words but not numpy's numbers); elsewhere (a comment) they are ignored;
- ``v`` lines of fewer than 3 numbers, with faces (trimesh builds two-dimensional triangles);
- a file ending in a backslash (trimesh then reads its last line without a newline, and may
  drop its last character).

Coordinates are returned as read: NaN or infinite values are the caller's to refuse.
"""

from __future__ import annotations

import itertools

import numpy as np
from numpy.typing import NDArray

from inertia_kit.physics.decimal_text import plain_decimals, small_integers
from inertia_kit.physics.obj_polygons import quoted_line

_SPACE, _NEWLINE, _SLASH = ord(" "), ord("\n"), ord("/")
#: str.isspace() of the ASCII characters: what str.strip and str.split take for whitespace
_ASCII_SPACE = b" \t\n\r\x0b\x0c\x1c\x1d\x1e\x1f"
#: the control characters allowed: \t, \n, \v, \f, \r (a NUL ends numpy's C string; \x1c-\x1f
#: split a Python string but not numpy's numbers; the others split neither)
_ALLOWED_CONTROL = np.zeros(256, dtype=bool)
_ALLOWED_CONTROL[list(b"\t\n\x0b\x0c\r")] = True
#: the bytes str.split and numpy take for whitespace (the other control characters refused)
_WHITESPACE = np.zeros(256, dtype=bool)
_WHITESPACE[list(b" \t\n\r\x0b\x0c")] = True
_DIGIT = np.zeros(256, dtype=bool)
_DIGIT[list(b"0123456789")] = True
_SIGN = np.zeros(256, dtype=bool)
_SIGN[list(b"+-")] = True
#: the line openings that start trimesh's stretch of faces
_FACE_STARTERS = (b"usemtl ", b"o ", b"f ", b"g ", b"s ")


def obj_soup(data: bytes) -> NDArray[np.float64]:
    """
    (n, 3, 3) triangles: exactly the soup trimesh 5.2 gives for this OBJ (every object and group,
    every face), as a multiset of triangles, each with trimesh's vertex order (winding).

    Raises ``ValueError`` (one line) where trimesh fails, and for the files the module's notes
    list; coordinates are returned as read (NaN and infinities included).
    """
    text = _text(data)
    buf = np.frombuffer(text, dtype=np.uint8)
    controls = np.flatnonzero(buf < _SPACE)
    kinds = buf[controls]
    # a NUL or another control character is refused in the lines read (see _bodies)
    controlled = not _ALLOWED_CONTROL[kinds].all()
    newlines = controls[kinds == _NEWLINE]
    starts = np.concatenate(([0], newlines + 1))
    ends = np.append(newlines, len(buf))  # the text ends with a newline: the last line is empty
    # each line's first two bytes (or the text's last newline)
    heads = [buf[np.minimum(starts + k, len(buf) - 1)] for k in range(2)]

    def opening(word: bytes) -> NDArray[np.bool_]:
        mask = (heads[0] == word[0]) & (heads[1] == word[1])
        if len(word) == 3:  # a line of two bytes and more ends with a newline: in the text
            mask[mask] = buf[starts[mask] + 2] == word[2]
        elif len(word) > 3:  # usemtl: few lines
            mask[mask] = [text.startswith(word, s) for s in starts[mask].tolist()]
        return mask

    # vt and vn lines are read only to fail where trimesh fails
    vertices, _, normals = (
        _read_rows(text, buf, starts, ends, opening(name), len(name), controlled)
        for name in (b"v ", b"vt ", b"vn ")
    )
    lines = None if vertices is None else _face_lines(text, starts, ends, heads, opening)
    if lines is None:
        return np.zeros((0, 3, 3))
    face_starts, face_ends, groups = lines
    if vertices.shape[1] < 3:
        raise ValueError(f"`v` lines hold {vertices.shape[1]} numbers, not 3 coordinates")
    vertices = vertices[:, :3]
    count = len(vertices)
    parts = [np.zeros((0, 3), np.int64)]
    lines_read = _bodies(buf, face_starts, face_ends, 1, controlled)
    for group in groups:
        parts.append(_group_faces(*_material(lines_read, group), count, normals == 3))
    faces = np.ascontiguousarray(parts[1] if len(parts) == 2 else np.concatenate(parts))
    # k > 0 is vertex k - 1; 0 and negative ones are Python indices (trimesh's `faces[faces > 0]
    # -= 1`, then numpy indexing), in range (_check_range)
    faces -= 1
    below = faces < 0
    if below.any():
        faces[below] = (faces[below] + 1 + count) % count
    # gathered as 24-byte records: several times faster than rows of a float array
    records = np.ascontiguousarray(vertices).view(np.dtype((np.void, 24)))[:, 0]
    return records[faces].view(np.float64).reshape(-1, 3, 3)


def _text(data: bytes) -> bytes:
    """The text trimesh parses: stripped, ``\\r\\n`` as ``\\n``, continuations joined, between
    newlines."""
    if data.isascii():
        first = (
            len(data) - len(data.lstrip(_ASCII_SPACE))
            if data[:1] and data[0] in _ASCII_SPACE
            else 0
        )
        last = len(data)
        while last > first and data[last - 1] in _ASCII_SPACE and len(data) - last < 4096:
            last -= 1
        if last > first and data[last - 1] in _ASCII_SPACE:  # a long run of blanks: copy
            last = len(data[first:].rstrip(_ASCII_SPACE)) + first
        body = memoryview(data)[first:last]  # not copied until joined
    else:
        try:
            body = data.decode("utf-8").strip().encode("utf-8")
        except UnicodeDecodeError:
            raise ValueError("the file is not UTF-8 text") from None
    if b"\r" in data and b"\r\n" in data:  # (a memoryview has no substring test)
        body = bytes(body).replace(b"\r\n", b"\n")
    text = b"".join((b"\n", body, b"\n"))
    if b"\\" not in data:
        return text
    if text.endswith(b"\\\n"):
        raise ValueError("the file ends in a line continuation (a backslash)")
    return text.replace(b"\\\n", b"")


def _bodies(
    buf: NDArray[np.uint8], starts: NDArray, ends: NDArray, skip: int, controlled: bool
) -> tuple[NDArray[np.uint8], bytes, NDArray[np.intp], NDArray[np.intp]]:
    """
    Lines ``[starts, ends)`` each followed by a newline, concatenated, with their first ``skip``
    bytes (the keyword) blanked, as an array and as bytes; and each line's offset and length
    (newline included) in it. A ValueError for a character outside ASCII, or (``controlled``:
    the file has some) a control character but whitespace: a NUL ends numpy's C string, and
    \\x1c-\\x1f separate Python's words but not numpy's numbers.
    """
    lengths = ends - starts + 1
    offsets = np.cumsum(lengths) - lengths
    if not len(starts):
        return np.zeros(0, np.uint8), b"", offsets, lengths
    if np.array_equal(starts[1:], ends[:-1] + 1):  # one block of lines, as usual
        body = buf[starts[0] : ends[-1] + 1].copy()
    else:  # the lines, and the gaps between them, as runs of kept and dropped bytes
        runs = np.empty(2 * len(starts) - 1, dtype=np.int64)
        runs[0::2] = lengths
        runs[1::2] = starts[1:] - ends[:-1] - 1
        kept = np.zeros(len(runs), dtype=bool)
        kept[0::2] = True
        body = buf[starts[0] : ends[-1] + 1][np.repeat(kept, runs)]
    for k in range(skip):
        body[offsets + k] = _SPACE
    body[offsets + lengths - 1] = _NEWLINE  # a line cut by `usemtl` ends there
    joined = body.tobytes()
    if not joined.isascii():
        at = int(offsets[np.argmax(np.maximum.reduceat(body, offsets) > 127)])
        line = joined[at : at + 200].split(b"\n")[0].strip()
        raise ValueError(f"a line holds a character outside ASCII: {quoted_line(line)}")
    if controlled:
        odd = (body < _SPACE) & ~_ALLOWED_CONTROL[body]
        if odd.any():
            code = int(body[np.argmax(odd)])
            raise ValueError(
                f"a `v`, `vt`, `vn` or `f` line holds the control character {code:#04x}"
            )
    return body, joined, offsets, lengths


def _material(lines_read, group: NDArray[np.intp]):
    """The lines ``group`` (ascending) of :func:`_bodies`' lines, as :func:`_bodies` gives them:
    a slice per run of consecutive lines (a stretch between two ``usemtl``)."""
    body, _, offsets, lengths = lines_read
    if len(group) == len(offsets):
        return lines_read
    breaks = np.flatnonzero(np.diff(group) != 1) + 1
    firsts = group[np.concatenate(([0], breaks))]
    lasts = group[np.append(breaks - 1, len(group) - 1)]
    ends = offsets[lasts] + lengths[lasts]
    pieces = [body[a:b] for a, b in zip(offsets[firsts].tolist(), ends.tolist(), strict=True)]
    body = np.concatenate(pieces)
    lengths = lengths[group]
    return body, body.tobytes(), np.cumsum(lengths) - lengths, lengths


def _read_rows(
    text: bytes,
    buf: NDArray[np.uint8],
    starts: NDArray,
    ends: NDArray,
    mask: NDArray[np.bool_],
    skip: int,
    controlled: bool,
) -> NDArray[np.float64] | int | None:
    """The numbers of the ``v`` lines as trimesh's ``_parse_vertices`` reads them (``None`` for
    none), or a ValueError where it fails; for ``vt`` and ``vn`` lines, the ValueError or the
    count of columns trimesh reads (plain decimals, which cannot fail, are only counted)."""
    if not mask.any():
        return None
    keyword = text[starts[mask][0] : starts[mask][0] + skip - 1].decode()
    _, joined, offsets, _ = _bodies(buf, starts[mask], ends[mask], skip, controlled)
    if b"e" in joined and (b"+e" in joined or b"-e" in joined):
        joined = joined.replace(b"+e", b"e").replace(b"-e", b"e")
    first = joined[: joined.index(b"\n")]
    per_row = len(first.split())
    if skip > 2 and plain_decimals(joined, values=False) == len(offsets) * per_row:
        return per_row
    try:
        numbers = plain_decimals(joined)
        if numbers is None:
            numbers = np.fromstring(joined, dtype=np.float64, sep=" ")
    except ValueError:
        raise ValueError(
            f"a `{keyword}` line holds text that is not a number (trimesh fails)"
        ) from None
    if len(numbers) == len(offsets) * per_row:
        return numbers.reshape(len(offsets), per_row) if skip == 2 else per_row
    # trimesh's fallback: each line (split again at \r, \v, \f) cut to the shortest
    values = joined.decode().split("\n")[:-1]
    split = [part.strip().split() for value in values for part in value[skip:].splitlines()]
    if not split:
        raise ValueError(f"the `{keyword}` lines hold no numbers (trimesh fails)")
    shortest = min(map(len, split))
    try:
        rows = np.array([row[:shortest] for row in split], dtype=np.float64)
    except ValueError as error:  # pragma: no cover - numpy read every number already
        raise ValueError(f"a `{keyword}` line: {error}") from None
    return rows if skip == 2 else rows.shape[1]


def _face_lines(text, starts, ends, heads, opening):
    """
    trimesh's face lines: their starts and ends (a line cut at ``usemtl``), and the indices of
    the lines of each material, in file order; ``None`` when there is none.
    """
    starters = np.zeros(len(starts), dtype=bool)
    for word in _FACE_STARTERS:
        starters |= opening(word)
    low = int(starts[np.argmax(starters)]) - 1 if starters.any() else len(text)
    is_face = opening(b"f ")
    # up to the newline after the last face (without a face, the first newline after the first)
    high = int(ends[np.flatnonzero(is_face)[-1]]) if is_face.any() else text.find(b"\n", 2)
    if low >= high:
        return None
    # materials: `usemtl ` anywhere in the stretch starts one, named by the rest of its line
    splits = []
    at = text.find(b"usemtl ", low, high)
    while at >= 0:
        splits.append(at)
        at = text.find(b"usemtl ", at + 7, high)
    candidate = (heads[0] == ord("f")) & (starts - 1 >= low) & (starts - 1 < high)
    odd = np.flatnonzero(candidate & ~is_face)
    if len(odd):
        candidate[_dropped(text, starts, candidate, odd, low, high, splits)] = False
    chosen = np.flatnonzero(candidate)
    if not len(chosen):
        return None
    face_starts, face_ends = starts[chosen], ends[chosen].copy()

    names = []
    for k, at in enumerate(splits):
        following = splits[k + 1] if k + 1 < len(splits) else high
        line_end = text.find(b"\n", at)
        stop = min(following, line_end if line_end >= 0 else high)
        names.append(text[at + 6 : stop].decode("utf-8").strip())
        if text[at - 1] != ord("\n"):  # in the middle of a line: a face line is cut there
            line = int(np.searchsorted(face_starts, at, side="right")) - 1
            if line >= 0 and face_starts[line] < at <= face_ends[line]:
                face_ends[line] = min(face_ends[line], at)
    material = np.searchsorted(np.asarray(splits, dtype=np.int64), face_starts, side="right") - 1
    ids: dict[str | None, int] = {None: 0}
    split_group = np.array([ids.setdefault(name, len(ids)) for name in names], dtype=np.intp)
    group = np.where(material >= 0, split_group[np.maximum(material, 0)] if names else 0, 0)
    order = np.argsort(group, kind="stable")
    bounds = np.searchsorted(group[order], np.arange(len(ids) + 1))
    groups = [order[a:b] for a, b in itertools.pairwise(bounds) if b > a]
    return face_starts, face_ends, groups


def _dropped(text, starts, candidate, odd, low, high, splits) -> list[int]:
    """
    The lines starting with ``f`` but not ``f `` (``f``, ``f\\t1 2 3``, ``foo``) that trimesh
    skips: it reads a stretch between two ``usemtl`` (the first: from ``low``) only when it
    starts with ``f `` or holds a newline and ``f``; its first line, a ``usemtl``, ``o`` or
    ``g`` line, removed. So such a line, first after that and the stretch's only ``f`` line, is
    skipped; every other is read as a face of what follows the ``f``.
    """
    chunks = np.array([low, *splits], dtype=np.int64)
    face_starts = starts[candidate]
    skipped = []
    for line in odd.tolist():
        at = int(starts[line])
        k = int(np.searchsorted(chunks, at, side="right")) - 1
        begin = int(chunks[k])
        end = int(chunks[k + 1]) if k + 1 < len(chunks) else high
        removed = k > 0 or text.startswith((b"o ", b"usemtl", b"g "), low + 1)
        rest = text.find(b"\n", begin + 1) + 1 if removed else low + 1
        alone = np.count_nonzero((face_starts >= begin) & (face_starts < end)) == 1
        if alone and at == rest:
            skipped.append(line)
    return skipped


def _group_faces(
    body: NDArray[np.uint8],
    joined: bytes,
    offsets: NDArray[np.intp],
    lengths: NDArray[np.intp],
    count: int,
    normals: bool,
) -> NDArray[np.int64]:
    """The triangles (vertex indices as written: 1-based, ``0`` and negative ones Python
    indices) of one material's face lines, ``body`` (as :func:`_bodies` gives them)."""
    lasts = offsets + lengths - 1
    slashed = b"/" in joined
    # only the vertex indices of `v/vt/vn` tokens: faster than reading every number; plain
    # `f a b c` lines are read as fast by np.fromstring (_flat_faces)
    faces = _layout_indices(body, joined, offsets, lasts) if slashed else None
    if faces is not None:
        _check_range(faces, count)
        return _polygons(faces)
    separator = body <= _SPACE  # the control characters left are whitespace
    if slashed:
        separator |= body == _SLASH
    columns = _token_counts(separator, offsets)
    if (columns == columns[0]).all():
        faces = _flat_faces(joined, slashed, offsets, lasts, int(columns[0]))
        _check_range(faces, count)
        return _polygons(faces)
    faces = _mixed_faces(body, offsets, lasts)
    if not len(faces) and normals:
        # trimesh then gives its empty mesh the file's normals, and numpy fails on them
        raise ValueError(
            "a material's faces all have fewer than 3 vertices, in a file with normals "
            "(trimesh fails)"
        )
    _check_range(faces, count)
    return faces


def _polygons(faces: NDArray[np.int64]) -> NDArray[np.int64]:
    """The triangles of polygons of one size (rows of ``faces``): a quad ``(0, 1, 2), (2, 3,
    0)``, a larger polygon a fan ``(0, i + 1, i + 2)``; none for rows of 1-2 vertices."""
    size = faces.shape[1]
    if size == 3:
        return faces
    if size == 4:
        return np.concatenate((faces[:, [0, 1, 2]], faces[:, [2, 3, 0]]))
    if size < 3:
        return np.zeros((0, 3), np.int64)
    fan = np.stack(
        [np.zeros(size - 2, np.intp), np.arange(1, size - 1), np.arange(2, size)], axis=1
    )
    return faces[:, fan].reshape(-1, 3)


#: the bytes of face lines laid out as exporters write them (the keyword blanked)
_LAYOUT_BYTES = b"0123456789/ \n"
#: the longest number :func:`_layout_indices` reads (``np.fromstring`` reads up to 18 digits
#: exactly; a longer one is the general path's)
_LONGEST = 18


def _layout_indices(body, joined: bytes, offsets, lasts) -> NDArray[np.int64] | None:
    """
    The vertex indices :func:`_flat_faces` reads, without reading the other numbers, when
    every face line is laid out alike, as exporters write them: single spaces, only digits
    and slashes, every token of the same shape as the first (``v``, ``v/vt``, ``v//vn``,
    ``v/vt/vn``: its slashes and the empty runs between them, e.g. ``1//2``, alike), starting
    with a digit, no number over 18 digits. Then every line has the same count of numbers,
    and the first line's layout takes each token's first number: the digits before its first
    slash. ``None`` for any other text (the general path reads it).
    """
    lines = len(offsets)
    if not lines or joined.translate(None, _LAYOUT_BYTES):
        return None
    spaces = np.flatnonzero(body == _SPACE)
    per_line = int(np.searchsorted(spaces, lasts[0]))
    # each line: the blanked keyword and its space, then one space before each token
    if per_line < 4 or len(spaces) != per_line * lines:
        return None
    spaces = spaces.reshape(lines, per_line)
    if not (np.array_equal(spaces[:, 0], offsets) and np.array_equal(spaces[:, 1], offsets + 1)):
        return None
    starts = (spaces[:, 1:] + 1).reshape(-1)
    ends = np.empty((lines, per_line - 1), dtype=spaces.dtype)
    ends[:, :-1] = spaces[:, 2:]
    ends[:, -1] = lasts
    ends = ends.reshape(-1)
    del spaces
    if not ((body[starts] - np.uint8(48)) < 10).all():  # a double space, a slash first
        return None
    if b"/" in joined:
        slashes = np.flatnonzero(body == _SLASH)
        shape = int(np.searchsorted(slashes, ends[0]))  # the slashes of a token
        if not shape or len(slashes) != shape * len(starts):
            return None
        slashes = slashes.reshape(len(starts), shape)
        # each token holds `shape` slashes (the runs interleave with the tokens)
        if not ((slashes[:, 0] > starts).all() and (slashes[:, -1] < ends).all()):
            return None
        # and the same runs, each empty where the first token's is: every line has the same
        # count of numbers, the first token's layout
        for k in range(shape + 1):
            left = starts - 1 if k == 0 else slashes[:, k - 1]
            right = slashes[:, k] if k < shape else ends
            run = right - left - 1
            empty = run[0] == 0
            if (run.any() if empty else not (run > 0).all()) or run.max() > _LONGEST:
                return None
        stops = np.ascontiguousarray(slashes[:, 0])
        del slashes
    else:
        stops = ends
        if (stops - starts).max() > _LONGEST:
            return None
    values = small_integers(body, starts, stops)
    if values is None:
        return None
    return values.reshape(lines, per_line - 1)


def _token_counts(separator: NDArray[np.bool_], offsets) -> NDArray[np.intp]:
    """Tokens of each line (``str.split``), between separators; every line opens with one."""
    opens = np.flatnonzero(separator[:-1] & ~separator[1:])
    bounds = np.append(offsets, len(separator))
    first = int(np.searchsorted(opens, bounds[1]))  # the first line's
    if first and len(opens) == first * len(offsets):  # as many in every line, as usual?
        table = opens.reshape(len(offsets), first)
        if (table[:, 0] >= offsets).all() and (table[:, -1] < bounds[1:]).all():
            return np.full(len(offsets), first)
    return np.diff(np.searchsorted(opens, bounds))


def _flat_faces(joined: bytes, slashed: bool, offsets, lasts, columns: int) -> NDArray[np.int64]:
    """trimesh's ``_parse_faces_vectorized``: every line laid out as the first."""
    try:
        numbers = joined.replace(b"/", b" ") if slashed else joined
        array = np.fromstring(numbers, dtype=np.int64, sep=" ")
        array = array.reshape((-1, columns))
    except ValueError as error:
        raise ValueError(f"cannot read the `f` lines' indices (trimesh fails: {error})") from None
    sample = joined[int(offsets[0]) : int(lasts[0])]
    tokens = len(sample.split())
    if tokens == columns:
        return array
    return array[:, np.arange(tokens) * int(columns / tokens)]


def _mixed_faces(body, offsets, lasts) -> NDArray[np.int64]:
    """trimesh's ``_parse_faces_fallback``: each line on its own, its polygon as a fan (a quad
    ``(0, 1, 2), (2, 3, 0)``), lines of fewer than 3 tokens dropped."""
    sizes = _token_counts(body <= _SPACE, offsets)
    kept = sizes >= 3
    if not kept.any():
        return np.zeros((0, 3), np.int64)
    body = body.copy()
    body[~np.repeat(kept, lasts - offsets + 1)] = _SPACE
    indices = _first_numbers(body, int(sizes[kept].sum()))
    sizes = sizes[kept]
    # triangle j of a polygon of k vertices: (0, j + 1, j + 2); a quad's second (2, 3, 0)
    triangles = sizes - 2
    first = np.cumsum(sizes) - sizes
    owner = np.repeat(np.arange(len(sizes)), triangles)
    j = np.arange(len(owner)) - np.repeat(np.cumsum(triangles) - triangles, triangles)
    local = np.stack([np.zeros_like(j), j + 1, j + 2], axis=1)
    local[(sizes[owner] == 4) & (j == 1)] = (2, 3, 0)
    faces = indices[first[owner, None] + local]
    return faces


def _first_numbers(body: NDArray[np.uint8], expected: int) -> NDArray[np.int64]:
    """``int(token.split("/")[0])`` of every token of ``body`` (lines to drop blanked)."""
    whitespace = _WHITESPACE[body]
    opens = ~whitespace
    opens[1:] &= whitespace[:-1]
    # blank each token from its first slash on
    slash = body == _SLASH
    if slash.any():
        token = np.cumsum(opens, dtype=np.int32)
        slashes = np.cumsum(slash, dtype=np.int32)
        before = (slashes - slash)[opens]  # slashes before each token
        tail = (slashes - before[np.maximum(token - 1, 0)] > 0) & ~whitespace
        body = np.where(tail, np.uint8(_SPACE), body)
        whitespace = _WHITESPACE[body]
    digit, sign = _DIGIT[body], _SIGN[body]
    simple = (digit | sign | whitespace).all()
    if simple and sign.any():  # a sign opens a token and a digit follows it
        at = np.flatnonzero(sign)
        simple = bool(opens[at].all() and _DIGIT[np.append(body, 0)[at + 1]].all())
    if simple:
        closes = np.flatnonzero(~whitespace[:-1] & whitespace[1:])
        simple = len(closes) == expected and (
            not expected or (closes + 1 - np.flatnonzero(opens)).max() <= 18
        )
    if simple:
        values = np.fromstring(body.tobytes(), dtype=np.int64, sep=" ")
        if len(values) == expected:
            return values
    # a token Python's int reads otherwise (an underscore, an empty index before a slash)
    values = []
    for token in body.tobytes().split():
        try:
            values.append(int(token))
        except ValueError:
            raise ValueError(
                f"an `f` line holds an index that is not an integer: {quoted_line(token)}"
            ) from None
    if len(values) != expected:
        raise ValueError("an `f` line holds an empty vertex index (trimesh fails)")
    try:
        return np.array(values, dtype=np.int64)
    except OverflowError:
        raise ValueError("an `f` line holds an index too large (trimesh fails)") from None


def _check_range(faces: NDArray[np.int64], count: int) -> None:
    """A ValueError for an index (as written) past the vertices (trimesh's IndexError)."""
    if not len(faces):
        return
    high, low = int(faces.max()), int(faces.min())
    if high > count or low < -count or not count:
        shown = high if high > count else low
        raise ValueError(f"an `f` line names vertex {shown}, but the file has {count} vertices")
