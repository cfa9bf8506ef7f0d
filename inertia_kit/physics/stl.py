"""
STL files straight into volume integrals: binary records memory-mapped a window at a time (or
read into a reused buffer a chunk at a time) and integrated as they come, ASCII parsed with one
regular expression. No trimesh, no vertex merging, and memory bounded by a window whatever the
file's size.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from inertia_kit.errors import MeshError
from inertia_kit.physics import polyhedra
from inertia_kit.physics.polyhedra import SurfaceIntegrator, integrate

HEADER_BYTES = 84
#: An ASCII STL (parsed whole) larger than this is not read.
MAX_ASCII_BYTES = 256 << 20
RECORD = np.dtype([("normal", "<f4", (3,)), ("vertices", "<f4", (3, 3)), ("attribute", "<u2")])

_ASCII_VERTEX = re.compile(rb"vertex\s+(\S+)\s+(\S+)\s+(\S+)")
# bytes no ASCII STL holds: control characters other than whitespace
_BINARY_BYTES = re.compile(rb"[\x00-\x08\x0e-\x1f]")


def binary_triangle_count(path: str | Path) -> int | None:
    """The triangle count of a binary STL, or ``None`` if the file is not one (by its size)."""
    size = os.path.getsize(path)
    if size < HEADER_BYTES:
        return None
    with open(path, "rb") as stream:
        stream.seek(80)
        count = int(np.frombuffer(stream.read(4), dtype="<u4")[0])
    return count if size == HEADER_BYTES + count * RECORD.itemsize else None


def read_stl(path: str | Path) -> SurfaceIntegrator:
    """
    Integrate an STL file (binary or ASCII).

    Returns
    -------
    integrator : SurfaceIntegrator
      Its ``moments``, ``closed``, ``bounds`` and ``count`` describe the file's triangles in
      the file's own units.

    Raises
    ------
    MeshError
      ``unreadable`` for a file that is neither a well-formed binary nor an ASCII STL, or holds
      non-finite coordinates; ``empty`` for a file with no triangles.
    """
    if os.path.getsize(path) == 0:
        raise MeshError(path, "empty", "the STL file is empty (0 bytes)")
    count = binary_triangle_count(path)
    integrator = _read_binary(path, count) if count is not None else _read_ascii(path)
    if integrator.count == 0:
        raise MeshError(path, "empty", "the STL file holds no triangles")
    moments = integrator.moments
    if not (np.isfinite(moments.volume) and np.isfinite(moments.second).all()):
        raise MeshError(path, "unreadable", "the STL file holds non-finite vertex coordinates")
    return integrator


def binary_triangles(path: str | Path) -> NDArray[np.float64] | None:
    """
    The triangles (n, 3, 3) of a binary STL, in file order and its unit, as trimesh reads them
    (``process=False``: the records' float32 vertices as float64, nothing merged or dropped);
    ``None`` for a file that is not one (an ASCII STL).

    For a surface that is not closed, which :func:`read_stl` integrates without holding it:
    its closure is judged on the triangles, read here without importing trimesh.
    """
    count = binary_triangle_count(path)
    if count is None:
        return None
    size = count * RECORD.itemsize
    with open(path, "rb") as stream:
        stream.seek(HEADER_BYTES)
        data = stream.read(size)
    if len(data) < size:
        raise MeshError(
            path,
            "unreadable",
            f"binary STL cut short: it ended before its {count} triangles",
        )
    return np.frombuffer(data, dtype=RECORD)["vertices"].astype(np.float64)


def _read_binary(path: str | Path, count: int) -> SurfaceIntegrator:
    """
    Integrate ``count`` records a chunk at a time, without holding them all.

    ``readinto`` a reused buffer, not a memory map: a map is ~5 % faster, but a file truncated
    by another process while mapped kills the process with SIGBUS, and bad input must never
    crash us.
    """
    with open(path, "rb", buffering=0) as stream:
        return _stream_binary(path, stream, count)


def _stream_binary(path: str | Path, stream, count: int) -> SurfaceIntegrator:
    """Integrate the records as ``readinto`` brings them into a reused buffer of a chunk."""
    buffer = np.empty(min(count, polyhedra.CHUNK), dtype=RECORD)
    raw = memoryview(buffer.view(np.uint8))
    vertices = buffer["vertices"]
    integrator = SurfaceIntegrator((0.0, 0.0, 0.0)) if count == 0 else None
    done = 0
    stream.seek(HEADER_BYTES)
    while done < count:
        size = min(len(buffer), count - done)
        if _fill(stream, raw[: size * RECORD.itemsize]) < size * RECORD.itemsize:
            raise MeshError(
                path,
                "unreadable",
                f"binary STL cut short: it ended after {done} of its {count} triangles",
            )
        if integrator is None:
            integrator = SurfaceIntegrator(_origin(vertices[:size]))
        integrator.add(vertices[:size])
        done += size
    assert integrator is not None
    return integrator


def _origin(vertices: NDArray) -> NDArray[np.float64] | tuple[float, float, float]:
    """A reference point near the surface: the mean vertex (of the first chunk)."""
    mean = vertices.reshape(-1, 3).mean(axis=0, dtype=np.float64)
    return mean if np.isfinite(mean).all() else (0.0, 0.0, 0.0)


def _fill(stream, view: memoryview) -> int:
    """Read into all of ``view`` unless the file ends first; the number of bytes read."""
    total = 0
    while total < len(view):
        got = stream.readinto(view[total:])
        if not got:
            break
        total += got
    return total


def _read_ascii(path: str | Path) -> SurfaceIntegrator:
    if os.path.getsize(path) > MAX_ASCII_BYTES:
        raise MeshError(
            path,
            "unreadable",
            f"not a binary STL (its size does not match its triangle count), and larger than "
            f"the {MAX_ASCII_BYTES >> 20} MB an ASCII STL is read up to",
        )
    data = Path(path).read_bytes()
    if data.lstrip()[:5].lower() != b"solid" or _BINARY_BYTES.search(data):
        size = len(data)
        if size >= HEADER_BYTES:
            count = int(np.frombuffer(data[80:84], dtype="<u4")[0])
            binary = (
                f"its header's count of {count} triangles needs "
                f"{HEADER_BYTES + count * RECORD.itemsize} bytes, the file has {size}"
            )
        else:
            binary = (
                f"it has only {size} bytes, less than a binary STL's {HEADER_BYTES}-byte header"
            )
        raise MeshError(
            path,
            "unreadable",
            f"not an STL file: not a binary STL ({binary}) nor an ASCII STL (which starts with "
            "`solid` and holds text only)",
        )
    try:
        values = np.array(_ASCII_VERTEX.findall(data), dtype=np.float64)
    except ValueError as error:
        raise MeshError(path, "unreadable", f"ASCII STL with a malformed vertex: {error}") from None
    if len(values) % 3:
        raise MeshError(
            path, "unreadable", f"ASCII STL with {len(values)} vertices, not a multiple of 3"
        )
    if not np.isfinite(values).all():
        raise MeshError(path, "unreadable", "the STL file holds non-finite vertex coordinates")
    return integrate(values.reshape(-1, 3, 3))
