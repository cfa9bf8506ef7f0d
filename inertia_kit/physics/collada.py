"""
COLLADA (.dae) read into a triangle soup with numpy and lxml, without trimesh or pycollada: the
triangles ``trimesh.load_scene(path, process=False)`` (trimesh 5.2 on pycollada) gives, placed
by the scene graph as :func:`.mesh_formats._read_scene` places them.

What is read, as pycollada and trimesh read it:

- the scene ``<scene><instance_visual_scene url="#id">`` names (the last ``<visual_scene>`` of
  that id); a file without one is refused (trimesh fails on it: pycollada's ``scene`` is
  ``None``). Its top-level ``<node>`` elements and, below them, every ``<node>``,
  ``<instance_node>`` (a node of ``<library_nodes>``, or a top-level node of the scene) and
  ``<instance_geometry>``; cameras, lights, controllers and ``<extra>`` are skipped.
- a node's transform: its ``<matrix>``, ``<translate>``, ``<rotate>``, ``<scale>`` and
  ``<lookat>`` children multiplied in document order, in float32 as pycollada does (``<skew>``
  is ignored, as pycollada ignores it), and the nodes' transforms multiplied root first in
  float64, then repaired as trimesh's scene graph repairs it (``fix_rigid``: a rotation off
  orthonormal by 1e-13 to 1e-5 is replaced by its SVD's ``U @ Vt``). A mirroring transform
  (negative determinant) reverses each triangle's winding.
- ``<up_axis>`` is **not** applied: pycollada reads it and trimesh never uses it, so a Y_UP
  file keeps its own axes, as trimesh keeps them.
- ``<unit meter>`` is returned as metres per unit, not applied, computed as trimesh computes it
  (``None`` or close to 1: 1.0; else ``unit * meters``). A COLLADA file has one unit.
- a ``<geometry>`` whose ``<mesh>`` holds ``<triangles>`` (the first ``<p>`` only, as
  pycollada), ``<polylist>`` (``<vcount>``; each polygon fanned from its first vertex),
  ``<polygons>`` (one ``<p>`` a polygon, fanned likewise; ``<ph>`` holes ignored, as pycollada
  ignores them), ``<trifans>`` and ``<tristrips>`` (one ``<p>`` a fan or strip, triangulated as
  pycollada: a strip's triangles 0, 2, 4, ... then 1, 3, 5, ..., the odd ones wound 2-1-3);
  ``<lines>`` and ``<linestrips>`` hold no triangle and are skipped. A geometry without a
  ``<mesh>`` (spline, convex mesh) is skipped, as trimesh skips it.
- ``<input offset>`` interleaving (the ``<p>`` stride is the largest offset + 1, over every
  input); the position is the first ``VERTEX`` input, through ``<vertices>`` (its ``POSITION``)
  or naming a ``<source>``; a ``<source>``'s ``<float_array>`` read as float32, as pycollada
  reads it, shaped by its ``<accessor>``'s ``<param>`` count (3 for a position).

Where this reader refuses what trimesh reads (wrongly, for a mass): a geometry pycollada drops
silently when it is corrupt (an index out of range or negative, a ``<p>`` that is not integers,
a source that is not three floats a vertex, an ``<instance_geometry>`` or ``<instance_node>``
naming nothing) makes the file unreadable here, not a part lighter; a NaN coordinate (pycollada
sets it to 0) or one beyond float32 is refused as non-finite; ``<vcount>`` must add up to the
``<p>`` length. Where it reads what trimesh cannot: an accessor ``stride`` or ``offset`` other
than the param count and 0 is honoured (pycollada ignores them); a mesh that also holds
``<linestrips>`` (pycollada drops the whole geometry); a ``<bind_material>`` naming a missing
or broken material (pycollada drops that instance of the geometry).

Where it reads the file more exactly than trimesh: trimesh builds each geometry with
``Trimesh(process=True)`` whatever ``load_scene`` is told, and its vertex merge snaps a vertex
onto an earlier one whose coordinates agree to 8 decimals (of the file unit; and normals to 2,
UVs to 4), moving it by under 1e-8 units. This reader keeps the file's coordinates; the mass
properties differ by the move (1.4e-10 relative on icub ``*_shank.dae``, the only installed
files it touches).

A hostile file: entity declarations are refused before parsing, and the parser resolves no
entity, loads no DTD and never touches the network; nesting is bounded; the scene may place at
most :data:`MAX_INSTANCES` geometries and :data:`MAX_TRIANGLES` triangles. No size is taken
from a ``count`` attribute.
"""

from __future__ import annotations

import math
import re
import warnings

import numpy as np
from numpy.typing import NDArray

from inertia_kit.errors import MeshError
from inertia_kit.physics.decimal_text import plain_decimals, small_integers
from inertia_kit.physics.frames import transformed_points

#: The largest file read (as :data:`.mesh_formats.MAX_MESH_BYTES`).
MAX_BYTES = 256 << 20
#: The most triangles the scene may place (instances included): 1.2 GB of float64 triangles.
MAX_TRIANGLES = 1 << 24
#: The deepest chain of nodes (and instanced nodes) followed.
MAX_DEPTH = 256
#: The most geometry instances the scene may place (a real part places tens; a chain of
#: ``<instance_node>``s multiplies them: 16 of 16 of ... is 16⁶, found while walking, not after).
MAX_INSTANCES = 1 << 16

_NAME = "COLLADA"
_DOCTYPE = re.compile(rb"<!DOCTYPE\b")
_ENTITY = re.compile(rb"<!ENTITY\b")
# trimesh's inch per metre (trimesh.units): a unit converts as (value * this) / this
_INCHES_PER_METRE = 39.37007874015748
_EYE = np.eye(4)
_IDENTITY32 = np.identity(4, dtype=np.float32)
_DIGITS = b"0123456789"
_SPACE = b" \t\n\r"


class _Refused(Exception):
    """A reason the file cannot be read, said in a few words."""


def read_collada(data: bytes, path) -> tuple[NDArray[np.float64], float]:
    """(n, 3, 3) triangles in the file's unit, wound as trimesh winds them, and metres per unit."""
    vertices, faces, unit = read_collada_shared(data, path)
    return vertices[faces], unit


def read_collada_shared(data: bytes, path) -> tuple[NDArray[np.float64], NDArray[np.intp], float]:
    """
    :func:`read_collada`'s triangles as the vertices they share: ``vertices`` (m, 3), placed,
    and ``faces`` (n, 3) with ``vertices[faces]`` the triangles, bit for bit; metres per unit.
    Every instance of a geometry has vertices of its own; a vertex no face uses may be among
    them.
    """
    try:
        document = _Document(_parse(data))
        unit = document.unit()
        parts = document.parts()
    except _Refused as error:
        detail = str(error)
    except (ValueError, TypeError, OverflowError, MemoryError, RecursionError) as error:
        text = str(error).strip().splitlines()[0][:200] if str(error).strip() else ""
        detail = f"{type(error).__name__}: {text}".rstrip(": ")
    else:
        if not parts:
            raise MeshError(
                path, "empty", f"the {_NAME} file holds no triangles; export the part's solid body"
            )
        vertices, faces = _joined(parts)
        finite = np.isfinite(vertices).all(axis=1)
        if not finite.all() and not finite[faces].all():  # an unused vertex may be anything
            raise MeshError(
                path, "unreadable", f"the {_NAME} file holds non-finite vertex coordinates"
            )
        if isinstance(unit, str):
            raise MeshError(path, "unreadable", unit)
        return vertices, faces, unit
    raise MeshError(
        path,
        "unreadable",
        f"cannot read the file as {_NAME} ({detail}); re-export it, or convert it to STL",
    )


def _joined(
    parts: list[tuple[NDArray[np.float64], NDArray[np.int64]]],
) -> tuple[NDArray[np.float64], NDArray[np.intp]]:
    """The parts' vertices one after another, and their faces numbering them so."""
    if len(parts) == 1:
        return parts[0][0], parts[0][1].astype(np.intp, copy=False)
    starts = np.cumsum([0] + [len(vertices) for vertices, _ in parts[:-1]])
    vertices = np.concatenate([vertices for vertices, _ in parts])
    faces = np.concatenate([index + start for (_, index), start in zip(parts, starts, strict=True)])
    return vertices, faces.astype(np.intp, copy=False)


def _parse(data: bytes):
    """The root element, parsed safely."""
    from lxml import etree

    if len(data) > MAX_BYTES:
        raise _Refused(f"larger than {MAX_BYTES >> 20} MB")
    doctype = _DOCTYPE.search(data)
    if doctype is not None and _ENTITY.search(data, doctype.end()) is not None:
        raise _Refused("entity declarations are not allowed: nothing was expanded or fetched")
    parser = etree.XMLParser(
        resolve_entities=False,
        no_network=True,
        load_dtd=False,
        dtd_validation=False,
        # a mesh's <p> and <float_array> are single text nodes of up to the file's size: lxml's
        # 10 MB text bound (huge_tree False) would refuse a large mesh pycollada reads; the file
        # is bounded, entities are refused above and not resolved, depth is bounded below
        huge_tree=True,
        remove_comments=True,
        remove_pis=True,
    )
    try:
        root = etree.fromstring(data, parser)
    except etree.XMLSyntaxError as error:
        raise _Refused(f"XML error: {str(error)[:200]}") from None
    if root is None:
        raise _Refused("no XML element")
    return root


def _ints(
    text: str | None, what: str, stride: int = 1, offset: int = 0
) -> tuple[NDArray[np.int64], int]:
    """
    Non-negative integers, whitespace-separated: every ``stride``-th from ``offset`` (the
    position input of a ``<p>``), and how many the text holds. Every one is read, or checked
    as :func:`_column` says, alike.
    """
    if text is None:
        return np.empty(0, dtype=np.int64), 0
    raw = text.encode("ascii", "replace")
    if raw.translate(None, _DIGITS + _SPACE):
        raise _Refused(f"{what} holds something other than non-negative integers")
    if stride > 1:
        found = _column(raw, stride, offset)
        if found is not None:
            return found
    values = np.fromstring(raw, dtype=np.int64, sep=" ")
    if values.size and values.max() == np.iinfo(np.int64).max:
        raise _Refused(f"{what} holds an integer too large")
    return (values[offset::stride] if stride > 1 else values), values.size


def _column(raw: bytes, stride: int, offset: int) -> tuple[NDArray[np.int64], int] | None:
    """
    :func:`_ints` of ``raw`` (digits and whitespace only) when it is laid out as exporters write
    a ``<p>``: one blank between numbers, none at either end, no number over 8 digits (none of
    the others can be too large); ``None`` otherwise. Only the wanted numbers are read (SWAR,
    :func:`.decimal_text.small_integers`): with a ``NORMAL`` input too, half of them.
    """
    body = np.frombuffer(raw, dtype=np.uint8)
    if not len(body) or body[0] <= 32 or body[-1] <= 32:
        return None
    blanks = np.flatnonzero(body <= 32)
    count = len(blanks) + 1
    if len(blanks):
        # a digit after every blank: one blank between numbers; each of at most 8 digits
        if not ((body[blanks + 1] - np.uint8(48)) < 10).all():
            return None
        widest = max(int(blanks[0]), len(body) - 1 - int(blanks[-1]))
        if len(blanks) > 1:
            widest = max(widest, int((blanks[1:] - blanks[:-1]).max()) - 1)
        if widest > 8:
            return None
    elif len(body) > 8:
        return None
    starts = blanks[offset - 1 :: stride] + 1 if offset else blanks[stride - 1 :: stride] + 1
    if not offset:
        starts = np.concatenate(([0], starts))
    stops = np.append(blanks, len(body))[offset::stride]
    starts = starts[: len(stops)]
    values = small_integers(body, starts, stops)
    if values is None:  # a text under 8 bytes (every number has at most 8 digits)
        return None
    return values, count


def _floats(text: str | None) -> NDArray[np.float32]:
    """
    Whitespace-separated decimal numbers as float32, bit for bit as pycollada reads them
    (``np.fromstring(text, dtype=np.float32, sep=" ")``: each rounded to float64 as ``strtod``
    rounds it, then to float32), without numpy's slow float parser.

    The bytes are split into tokens with numpy; each token of the form
    ``[+-]digits[.digits][e[+-]digits]`` is read as two integers at C speed (the digits without
    the point, and the exponent), and the value is ``mantissa * 10**exponent``: exact, and so
    rounded as ``strtod`` rounds it, for a mantissa under 2**53 and an exponent within 22;
    otherwise within 2**-51 of the decimal's value, which decides the float32 unless the
    decimal lies within 2**-49 of a float32 rounding boundary (a tie of the double rounding):
    those tokens, and mantissas over 18 digits or exponents beyond 300, are read by numpy's
    parser, one by one. A text with anything else (``nan``, ``inf``, a comma) is read by numpy's
    parser whole, and refused unless it reads every token.
    """
    if text is None:
        return np.empty(0, dtype=np.float32)
    raw = text.encode("ascii", "replace")
    exact = plain_decimals(raw, exponents=True)  # the usual text, read exactly: far faster
    if exact is not None:
        return exact.astype(np.float32)
    if raw.translate(None, _FLOAT_BYTES):
        return _floats_numpy(raw)
    buffer = b" " + raw + b"  "
    u = np.frombuffer(buffer, dtype=np.uint8)
    # every byte but a digit, in order (separators, signs, points, exponents): a few a token
    at = np.flatnonzero((u[:-1] < 48) | (u[:-1] > 57))
    kind = u[at]
    before, after = u[at - 1], u[at + 1]
    space = kind <= 32
    opens = space & (after > 32)
    starts = at[opens] + 1
    ends = at[space & (before > 32)]
    count = len(starts)
    if not count:
        return np.empty(0, dtype=np.float32)
    token = np.cumsum(opens, dtype=np.int32) - 1  # the token of each non-digit byte
    digit = (u - 48) < 10
    is_point = kind == 46
    is_exp = (kind | 32) == 101
    is_sign = (kind == 45) | (kind == 43)
    p_at, e_at = np.flatnonzero(is_point), np.flatnonzero(is_exp)
    points, exps = at[p_at], at[e_at]
    point_token, exp_token = token[p_at], token[e_at]
    if is_sign.any():
        signs = at[is_sign]
        lead = before[is_sign] <= 32
        if not (
            (lead | ((before[is_sign] | 32) == 101)).all()
            and (digit[signs + 1] | (lead & (after[is_sign] == 46) & digit[signs + 2])).all()
        ):
            return _floats_numpy(raw)
    # a point: one a token, a digit on a side, after the sign and before the exponent (the
    # next non-digit byte ends its digits); an exponent: one a token, after a digit or point
    # and followed by a digit or a sign
    if (
        (np.diff(point_token) == 0).any()
        or (np.diff(exp_token) == 0).any()
        or not (digit[points - 1] | digit[points + 1]).all()
        or ((kind[p_at - 1] | 32) == 101).any()
        or (is_sign[p_at - 1] & ~(kind[p_at - 2] <= 32)).any()
        or not ((digit[exps - 1] | (before[e_at] == 46)) & (after[e_at] > 32)).all()
    ):
        return _floats_numpy(raw)
    has_point = np.zeros(count, dtype=bool)
    has_point[point_token] = True
    has_exp = np.zeros(count, dtype=bool)
    has_exp[exp_token] = True
    mantissa_end = ends.copy()
    mantissa_end[exp_token] = exps
    places = np.zeros(count, dtype=np.int64)
    places[point_token] = at[p_at + 1] - points - 1
    first = u[starts]
    negative = first == 45
    signed = negative | (first == 43)
    # the digits without point or sign, the exponent a number of its own: "-1.5e+3" -> "-15 3"
    values = np.fromstring(raw.translate(_EXP_TABLE, b".+"), dtype=np.int64, sep=" ")
    if values.size != count + exps.size:
        return _floats_numpy(raw)
    index = np.arange(count)
    if exps.size:
        index += np.cumsum(has_exp) - has_exp
    mantissa = np.abs(values[index])
    exponent = -places
    odd = (mantissa_end - starts - signed - has_point) > 18
    if exps.size:
        written = values[index[has_exp] + 1]
        exponent[has_exp] += np.clip(written, -1000, 1000)
        odd |= np.abs(exponent) > 300
    exact = (mantissa < 1 << 53) & (np.abs(exponent) <= 22)
    with np.errstate(over="ignore", invalid="ignore"):
        magnitude = mantissa / _POW10[np.clip(-exponent, 0, 22)]
        magnitude *= _POW10[np.clip(exponent, 0, 22)]
        result = magnitude.astype(np.float32)
        loose = np.flatnonzero(~exact & ~odd)
        if loose.size:
            near = mantissa[loose].astype(np.float64) * 10.0 ** exponent[loose].astype(np.float64)
            result[loose] = chosen = near.astype(np.float32)
            odd[loose] = ((near * (1 - 2.0**-49)).astype(np.float32) != chosen) | (
                (near * (1 + 2.0**-49)).astype(np.float32) != chosen
            )
    np.negative(result, out=result, where=negative)
    if odd.any():
        which = np.flatnonzero(odd)
        tokens = b" ".join(buffer[starts[i] : ends[i]] for i in which.tolist())
        result[which] = _floats_numpy(tokens)
    return result


_FLOAT_BYTES = b"0123456789.-+eE \t\n\r"
_EXP_TABLE = bytes.maketrans(b"eE", b"  ")
_POW10 = 10.0 ** np.arange(23)


def _floats_numpy(raw: bytes) -> NDArray[np.float32]:
    """numpy's own reading (pycollada's), refused unless it reads every token."""
    count = len(raw.split())
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error", DeprecationWarning)
            values = np.fromstring(raw, dtype=np.float32, sep=" ")
    except (ValueError, DeprecationWarning):
        values = None
    if values is None or values.size != count:
        raise _Refused("a <float_array> holds something other than numbers")
    return values


class _Document:
    """The parts of one COLLADA document the triangles need, read on demand."""

    def __init__(self, root) -> None:
        self.root = root
        # pycollada takes the namespace from the root's tag, whatever it is
        namespace = root.tag.split("}")[0].lstrip("{") if isinstance(root.tag, str) else ""
        self.ns = "{" + namespace + "}"
        self.geometries: dict[str, object] = {}
        for library in root.iterfind(self.tag("library_geometries")):
            for geometry in library.iterfind(self.tag("geometry")):
                self.geometries[geometry.get("id")] = geometry
        self.library_nodes: dict[str, object] = {}
        for library in root.iterfind(self.tag("library_nodes")):
            for node in library.iterfind(self.tag("node")):
                self.library_nodes[node.get("id")] = node
        self.meshes: dict[object, list[tuple[NDArray[np.float64], NDArray[np.int64]]]] = {}
        self.sources: dict[object, NDArray[np.float32]] = {}

    def tag(self, name: str) -> str:
        return self.ns + name

    # --- the unit ------------------------------------------------------------------------------

    def unit(self) -> float | str:
        """Metres per unit, or a message (``str``) refusing the unit."""
        meter = None
        asset = self.root.find(self.tag("asset"))
        unit = asset.find(self.tag("unit")) if asset is not None else None
        if unit is not None:
            try:
                meter = float(unit.get("meter"))
            except (TypeError, ValueError):
                meter = None
        if meter is None or np.isclose(meter, 1.0):
            return 1.0
        factor = _INCHES_PER_METRE * float(f"{meter}") / _INCHES_PER_METRE
        name = f"{meter} * meters"
        if not math.isfinite(factor):
            return f"unknown unit `{name}` in the file; re-export it in metres"
        if not factor > 0:
            return f"unit `{name}` is {factor} m; re-export the file in metres"
        return factor

    # --- the scene -----------------------------------------------------------------------------

    def scene(self):
        instance = self.root.find(f"{self.tag('scene')}/{self.tag('instance_visual_scene')}")
        if instance is None:
            raise _Refused("no <scene> names a <visual_scene>")
        url = instance.get("url") or ""
        found = None
        for library in self.root.iterfind(self.tag("library_visual_scenes")):
            for scene in library.iterfind(self.tag("visual_scene")):
                if url.startswith("#") and scene.get("id") == url[1:]:
                    found = scene
        if found is None:
            raise _Refused(f"the <scene> names `{url[:100]}`, which is no <visual_scene>")
        return found

    def parts(self) -> list[tuple[NDArray[np.float64], NDArray[np.int64]]]:
        """Every geometry instance's primitives, placed: (vertices (m, 3), faces (n, 3))."""
        scene = self.scene()
        top = scene.findall(self.tag("node"))
        self.scene_nodes: dict[str, object] = {}
        for node in top:
            ident = node.get("id")
            if ident and ident not in self.scene_nodes:
                self.scene_nodes[ident] = node
        instances: list[tuple[NDArray[np.float64], object]] = []
        for node in top:
            self._walk(node, _EYE, instances, (), 0)
        total = 0
        meshes = []
        for matrix, geometry in instances:
            matrix = _fix_rigid(matrix)
            mesh = self._mesh(geometry)
            total += sum(len(index) for _, index in mesh)
            if total > MAX_TRIANGLES:
                raise _Refused(f"the scene places more than {MAX_TRIANGLES} triangles")
            meshes.append((matrix, mesh))
        parts = []
        for matrix, mesh in meshes:
            mirrored = np.linalg.det(matrix[:3, :3]) < 0
            for vertices, index in mesh:
                placed = transformed_points(vertices, matrix)
                if mirrored:
                    index = index[:, ::-1]
                parts.append((placed, index))
        return parts

    def _walk(self, node, parent, instances, chain, depth) -> None:
        """The instances below ``node`` (a ``<node>``), its parent's transform ``parent``."""
        if depth > MAX_DEPTH:
            raise _Refused(f"nodes nest deeper than {MAX_DEPTH}")
        matrix = np.dot(parent, self._node_matrix(node))
        for child in node:
            tag = child.tag
            if tag == self.tag("node"):
                self._walk(child, matrix, instances, chain, depth + 1)
            elif tag == self.tag("instance_node"):
                url = child.get("url") or ""
                target = self.scene_nodes.get(url[1:]) if url.startswith("#") else None
                if target is None and url.startswith("#"):
                    target = self.library_nodes.get(url[1:])
                if target is None:
                    raise _Refused(f"<instance_node> names `{url[:100]}`, which is no <node>")
                if any(target is seen for seen in chain):
                    raise _Refused(f"<instance_node> `{url[:100]}` instances itself")
                self._walk(target, matrix, instances, (*chain, target), depth + 1)
            elif tag == self.tag("instance_geometry"):
                url = child.get("url") or ""
                geometry = self.geometries.get(url[1:]) if url.startswith("#") else None
                if geometry is None:
                    raise _Refused(
                        f"<instance_geometry> names `{url[:100]}`, which is no <geometry>"
                    )
                if geometry.find(self.tag("mesh")) is not None:
                    instances.append((matrix, geometry))
                    if len(instances) > MAX_INSTANCES:
                        raise _Refused(f"the scene places more than {MAX_INSTANCES} geometries")

    def _node_matrix(self, node) -> NDArray:
        """A node's transforms multiplied in document order, in float32, as pycollada does."""
        transforms = []
        for child in node:
            tag = child.tag
            if not isinstance(tag, str) or not tag.startswith(self.ns):
                continue
            kind = tag[len(self.ns) :]
            if kind in _TRANSFORMS:
                transforms.append(_transform(kind, child.text))
        if not transforms:
            return _IDENTITY32
        if len(transforms) == 1:
            return transforms[0]
        matrix = np.identity(4, dtype=np.float32)
        for transform in transforms:
            matrix = np.dot(matrix, transform)
        return matrix

    # --- geometry ------------------------------------------------------------------------------

    def _mesh(self, geometry) -> list[tuple[NDArray[np.float64], NDArray[np.int64]]]:
        """A geometry's primitives, each as (vertices (m, 3) float64, triangles (n, 3) int)."""
        cached = self.meshes.get(geometry)
        if cached is not None:
            return cached
        mesh = geometry.find(self.tag("mesh"))
        ident = geometry.get("id")
        sources = {}
        vertices = {}
        for child in mesh:
            if child.tag == self.tag("source"):
                sources[child.get("id")] = child
            elif child.tag == self.tag("vertices"):
                vertices[child.get("id")] = child
        result = []
        for primitive in mesh:
            kind = primitive.tag[len(self.ns) :] if isinstance(primitive.tag, str) else ""
            if kind not in ("triangles", "polylist", "polygons", "trifans", "tristrips"):
                continue
            where = f"<{kind}> of geometry `{ident}`"
            stride, offset, source = self._position_input(primitive, sources, vertices, where)
            positions = self._positions(source, where)
            index = self._corners(primitive, kind, stride, offset, where)
            if index is None or not len(index):
                continue
            if index.size and index.max() >= len(positions):
                raise _Refused(f"{where} names vertex {int(index.max())} of {len(positions)}")
            result.append((positions, index))
        self.meshes[geometry] = result
        return result

    def _position_input(self, primitive, sources, vertices, where):
        """The ``<p>`` stride, the position's offset in it, and the position ``<source>``."""
        offsets = []
        position = None
        for item in primitive.iterfind(self.tag("input")):
            try:
                offset = int(item.get("offset"))
            except (TypeError, ValueError):
                raise _Refused(f"{where} has an <input> without an integer offset") from None
            if offset < 0 or offset > 1024:
                raise _Refused(f"{where} has an <input> offset of {offset}")
            offsets.append(offset)
            if item.get("semantic") != "VERTEX" or position is not None:
                continue
            url = item.get("source") or ""
            ident = url[1:] if url.startswith("#") else None
            if ident in vertices:
                found = None
                for inner in vertices[ident].iterfind(self.tag("input")):
                    if inner.get("semantic") == "POSITION":
                        inner_url = inner.get("source") or ""
                        found = sources.get(inner_url[1:]) if inner_url.startswith("#") else None
                if found is None:
                    raise _Refused(f"{where}: its <vertices> names no POSITION <source>")
                position = (offset, found)
            elif ident in sources:
                position = (offset, sources[ident])
            else:
                raise _Refused(f"{where} names `{url[:100]}`, which is no <vertices>")
        if position is None:
            raise _Refused(f"{where} has no VERTEX input")
        return max(offsets) + 1, position[0], position[1]

    def _positions(self, source, where) -> NDArray[np.float64]:
        """A position ``<source>``: (m, 3) float32 values, as float64."""
        cached = self.sources.get(source)
        if cached is not None:
            return cached
        array = source.find(self.tag("float_array"))
        if array is None:
            raise _Refused(f"{where}: its position <source> holds no <float_array>")
        params = source.findall(
            f"{self.tag('technique_common')}/{self.tag('accessor')}/{self.tag('param')}"
        )
        accessor = source.find(f"{self.tag('technique_common')}/{self.tag('accessor')}")
        if not params or accessor is None:
            raise _Refused(f"{where}: its position <source> has no <accessor>")
        if len(params) != 3:
            raise _Refused(f"{where}: its position <source> has {len(params)} values a vertex")
        try:
            stride = int(accessor.get("stride") or len(params))
            start = int(accessor.get("offset") or 0)
        except ValueError:
            raise _Refused(f"{where}: its position <accessor> is malformed") from None
        values = _floats(array.text)  # pycollada's float32; beyond its range: inf, refused
        if stride == len(params) and start == 0:
            if values.size % 3:
                raise _Refused(f"{where}: its position <float_array> is not whole vertices")
            positions = values.reshape(-1, 3)
        else:
            if stride < len(params) or start < 0:
                raise _Refused(f"{where}: its position <accessor> is malformed")
            count = max((values.size - start - len(params)) // stride + 1, 0)
            rows = start + stride * np.arange(count)[:, None] + np.arange(3)
            positions = values[rows]
        positions = positions.astype(np.float64)
        self.sources[source] = positions
        return positions

    def _corners(self, primitive, kind, stride, offset, where) -> NDArray[np.int64] | None:
        """(n, 3) position index (the input at ``offset`` of ``stride``) of each triangle."""
        p_tag = self.tag("p")
        if kind == "triangles":
            first = primitive.find(p_tag)
            if first is None:
                raise _Refused(f"{where} has no <p>")
            index, size = _ints(first.text, f"the <p> of {where}", stride, offset)
            if size % (3 * stride):
                raise _Refused(f"the <p> of {where} is not whole triangles")
            return index.reshape(-1, 3)
        if kind == "polylist":
            first = primitive.find(p_tag)
            vcount = primitive.find(self.tag("vcount"))
            if first is None or vcount is None:
                raise _Refused(f"{where} has no <p> or <vcount>")
            index, size = _ints(first.text, f"the <p> of {where}", stride, offset)
            counts, _ = _ints(vcount.text, f"the <vcount> of {where}")
            return _fanned(index, size, counts, stride, where)
        rows = [_ints(p.text, f"a <p> of {where}") for p in primitive.iterfind(p_tag)]
        for _, size in rows:
            if size % stride:
                raise _Refused(f"a <p> of {where} is not whole vertices")
        if kind == "polygons":
            if not rows:
                return None
            counts = np.array([size // stride for _, size in rows], dtype=np.int64)
            index = np.concatenate([row for row, _ in rows])
            return _fanned(index[offset::stride], index.size, counts, stride, where)
        parts = []
        for row, _ in rows:
            corners = row[offset::stride]
            n = len(corners)
            if n < 3:
                raise _Refused(f"a <p> of {where} has fewer than 3 vertices")
            if kind == "trifans":
                first = np.repeat(corners[:1], n - 2, axis=0)
                parts.append(np.stack([first, corners[1:-1], corners[2:]], axis=1))
            else:
                even = np.stack([corners[0:-2:2], corners[1:-1:2], corners[2::2][: (n - 1) // 2]])
                odd = np.stack([corners[2:-1:2], corners[1:-2:2], corners[3::2][: (n - 2) // 2]])
                parts.append(even.swapaxes(0, 1))
                parts.append(odd.swapaxes(0, 1))
        if not parts:
            return None
        return np.concatenate(parts)


def _fanned(corners, size, counts, stride, where) -> NDArray[np.int64]:
    """Polygons of ``counts`` vertices (``corners``: their positions, of a ``<p>`` of ``size``
    numbers), fanned from each one's first vertex, as pycollada."""
    if size % stride:
        raise _Refused(f"the <p> of {where} is not whole vertices")
    if int(counts.sum()) != len(corners):
        raise _Refused(
            f"the <vcount> of {where} adds up to {int(counts.sum())} vertices, "
            f"its <p> holds {len(corners)}"
        )
    fans = np.maximum(counts - 2, 0)
    if (fans == 1).all():  # triangles only
        return corners.reshape(-1, 3)
    if (counts == 4).all():  # quads only: (0, 1, 2), (0, 2, 3)
        return corners.reshape(-1, 4)[:, [0, 1, 2, 0, 2, 3]].reshape(-1, 3)
    total = int(fans.sum())
    starts = np.cumsum(counts) - counts
    first = np.repeat(starts, fans)
    step = np.arange(total) - np.repeat(np.cumsum(fans) - fans, fans)
    second = first + step + 1
    return np.stack([corners[first], corners[second], corners[second + 1]], axis=1)


_TRANSFORMS = ("matrix", "translate", "rotate", "scale", "lookat")
_TRANSFORM_SIZES = {"matrix": 16, "translate": 3, "rotate": 4, "scale": 3, "lookat": 9}


def _transform(kind: str, text: str | None) -> NDArray[np.float32]:
    """One transform element's (4, 4) float32 matrix, computed as pycollada computes it."""
    values = _floats(text)
    if values.size != _TRANSFORM_SIZES[kind]:
        raise _Refused(f"a <{kind}> holds {values.size} numbers, not {_TRANSFORM_SIZES[kind]}")
    if kind == "matrix":
        return values.reshape(4, 4)
    if kind == "translate":
        matrix = np.identity(4, dtype=np.float32)
        matrix[:3, 3] = values
        return matrix
    if kind == "scale":
        matrix = np.identity(4, dtype=np.float32)
        matrix[0, 0], matrix[1, 1], matrix[2, 2] = values
        return matrix
    if kind == "rotate":
        x, y, z, angle = values
        with np.errstate(all="ignore"):
            return _rotation(x, y, z, angle * np.pi / 180.0)
    eye, interest, up = values[0:3], values[3:6], values[6:9]
    with np.errstate(all="ignore"):
        front = _unit(np.subtract(eye, interest))
        side = np.multiply(-1, _unit(np.cross(front, up)))
    matrix = np.identity(4, dtype=np.float32)
    matrix[0, 0:3] = side
    matrix[1, 0:3] = up
    matrix[2, 0:3] = front
    matrix[3, 0:3] = eye
    return matrix


def _unit(vector):
    """pycollada's ``toUnitVec``."""
    return vector / np.sqrt(np.vdot(vector, vector))


def _rotation(x, y, z, angle) -> NDArray[np.float32]:
    """pycollada's ``makeRotationMatrix`` (float32 scalars in, float32 arithmetic)."""
    c = np.cos(angle)
    s = np.sin(angle)
    t = 1 - c
    return np.array(
        [
            [t * x * x + c, t * x * y - s * z, t * x * z + s * y, 0],
            [t * x * y + s * z, t * y * y + c, t * y * z - s * x, 0],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c, 0],
            [0, 0, 0, 1],
        ],
        dtype=np.float32,
    )


def _fix_rigid(matrix: NDArray[np.float64]) -> NDArray[np.float64]:
    """
    trimesh's ``fix_rigid`` (``SceneGraph.get`` with ``repair_rigid=1e-5``), which every
    instance's matrix passes through: a rotation part off orthonormal by more than 1e-13 and
    less than 1e-5 (float32 arithmetic makes most rotations so) is replaced by the nearest
    orthonormal matrix, ``U @ Vt`` of its SVD, the translation kept.
    """
    rotation = matrix[:3, :3]
    check = np.abs(np.dot(rotation, rotation.T) - _EYE[:3, :3]).max()
    if not (1e-13 < check < 1e-5):
        return matrix
    u, _, v = np.linalg.svd(rotation)
    repaired = np.eye(4)
    repaired[:3, :3] = np.dot(u, v)
    repaired[:3, 3] = matrix[:3, 3]
    if not np.allclose(repaired, matrix, atol=1e-5):
        raise _Refused("a node's transform is not rigid enough to repair as trimesh repairs it")
    return repaired
