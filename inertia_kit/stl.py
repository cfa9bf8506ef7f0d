"""
STL files straight into volume integrals: binary records read in fixed-size chunks into a
reused numpy buffer and integrated as they come, ASCII parsed with one regular expression.
No trimesh, no vertex merging.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np

from inertia_kit.errors import MeshError
from inertia_kit.polyhedra import CHUNK, SurfaceIntegrator, integrate

HEADER_BYTES = 84
RECORD = np.dtype([("normal", "<f4", (3,)), ("vertices", "<f4", (3, 3)), ("attribute", "<u2")])

_ASCII_VERTEX = re.compile(rb"vertex\s+(\S+)\s+(\S+)\s+(\S+)")


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
    count = binary_triangle_count(path)
    integrator = _read_binary(path, count) if count is not None else _read_ascii(path)
    if integrator.count == 0:
        raise MeshError(path, "empty", "the STL file holds no triangles")
    moments = integrator.moments
    if not (np.isfinite(moments.volume) and np.isfinite(moments.second).all()):
        raise MeshError(path, "unreadable", "the STL file holds non-finite vertex coordinates")
    return integrator


def _read_binary(path: str | Path, count: int) -> SurfaceIntegrator:
    buffer = np.empty(min(count, CHUNK), dtype=RECORD)
    with open(path, "rb") as stream:
        stream.seek(HEADER_BYTES)
        first = stream.readinto(buffer) // RECORD.itemsize if count else 0
        head = buffer["vertices"][:first]
        origin = head.reshape(-1, 3).astype(np.float64).mean(axis=0) if first else np.zeros(3)
        if not np.isfinite(origin).all():
            origin = np.zeros(3)
        integrator = SurfaceIntegrator(origin)
        integrator.add(head)
        done = first
        while done < count:
            got = stream.readinto(buffer) // RECORD.itemsize
            if got == 0:
                raise MeshError(path, "unreadable", f"binary STL truncated after {done} of {count} triangles")
            integrator.add(buffer["vertices"][:got])
            done += got
    return integrator


def _read_ascii(path: str | Path) -> SurfaceIntegrator:
    data = Path(path).read_bytes()
    if not data.lstrip()[:5].lower() == b"solid":
        raise MeshError(
            path,
            "unreadable",
            "not an STL file: neither a binary STL (its size does not match the triangle count "
            "in its header) nor an ASCII STL (it does not start with `solid`)",
        )
    try:
        values = np.array(_ASCII_VERTEX.findall(data), dtype=np.float64)
    except ValueError as error:
        raise MeshError(path, "unreadable", f"ASCII STL with a malformed vertex: {error}") from None
    if len(values) % 3:
        raise MeshError(path, "unreadable", f"ASCII STL with {len(values)} vertices, not a multiple of 3")
    if not np.isfinite(values).all():
        raise MeshError(path, "unreadable", "the STL file holds non-finite vertex coordinates")
    return integrate(values.reshape(-1, 3, 3))
