"""
An on-disk cache of :func:`.unions.union` for overlapping primitives, so that linting again a
link whose collision shapes overlap (a capsule built of a cylinder and two spheres, as
franka_ros' self-collision links are) does not tessellate and unite them with manifold3d again
(~50 ms a link), nor import manifold3d.

:func:`cached_union` is ``union`` with a memory: the same results, bit for bit, and the same
errors (never stored).

What is stored
  The :class:`~.unions.UnionResult`, its floats as JSON (``repr`` round-trips every float64).
Key
  Every part's kind, dimensions, exact unit-density mass properties and pose, in order, with
  the density or mass and the segments; and a *code key*: the mesh cache's (package, numpy and
  library versions, the mesh modules) and the size and mtime of the modules that compute a
  union. Parts with a mesh are not cached (their key would be the whole mesh), nor unions whose
  parts' boxes do not meet (``union`` sums them without manifold3d, faster than a read).
Location, concurrency, size
  As the mesh cache (:mod:`.mesh_cache`, :mod:`.mesh_cache_entries`), in ``unions-v1/``.
"""

from __future__ import annotations

import functools
import json
import os
import zlib
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.mesh_cache import cache_location, code_key
from inertia_kit.physics.mesh_cache_entries import MAX_ENTRY_BYTES, write_entry
from inertia_kit.physics.unions import DEFAULT_SEGMENTS, Part, UnionResult, overlapping, union
from inertia_kit.reading import open_regular

#: Version of the entry layout; part of the folder name and of every entry.
FORMAT = 1

# the modules whose code decides a union's numbers (the mesh cache's code key has the rest)
_SOURCES = (
    "unions.py",
    "union_cache.py",
    "manifolds.py",
    "tessellate.py",
    "primitives.py",
    "mass.py",
    "frames.py",
)


def cached_union(
    parts: Iterable[Part],
    *,
    density: float | None = None,
    mass: float | None = None,
    segments: int = DEFAULT_SEGMENTS,
    cache_dir: str | Path | None = None,
) -> UnionResult:
    """
    :func:`~.unions.union`, served from the on-disk cache for primitives that overlap.

    ``cache_dir`` as in :func:`~.mesh_cache.cache_location` (``INERTIA_KIT_NO_CACHE`` turns the
    cache off); the other parameters, the result and the errors as ``union``.
    """
    parts = tuple(parts)
    key = _key(parts, density, mass, segments)
    folder = cache_location(cache_dir) if key is not None else None
    if key is None or folder is None:
        return union(parts, density=density, mass=mass, segments=segments)
    code = _code_key()
    body = json.dumps({"format": FORMAT, "code": code, "key": key}, separators=(",", ":"))
    digest = f"{zlib.crc32(body.encode()):08x}{zlib.adler32(body.encode()):08x}"
    entry = os.path.join(folder, f"unions-v{FORMAT}", f"union-{digest}.json")
    found = _read(entry, code, key)
    if found is not None:
        return found
    result = union(parts, density=density, mass=mass, segments=segments)
    write_entry(str(folder), entry, _encode(code, key, result))
    return result


def _key(
    parts: tuple[Part, ...], density: float | None, mass: float | None, segments: int
) -> dict[str, Any] | None:
    """What decides the union, as JSON values; ``None`` when it is not worth caching."""
    if len(parts) < 2 or not all(isinstance(p, Part) and p.vertices is None for p in parts):
        return None
    try:
        if not overlapping([part.bounds for part in parts]):
            return None
        described = [
            [
                part.kind,
                [float(d) for d in part.dimensions],
                _properties(part.unit),
                [float(v) for v in part.pose.reshape(-1)],
            ]
            for part in parts
        ]
    except (TypeError, ValueError):  # union raises the error itself
        return None
    return {"parts": described, "density": density, "mass": mass, "segments": segments}


def _properties(value: MassProperties) -> list[Any]:
    return [value.mass, value.com.tolist(), value.inertia.tolist()]


@functools.cache
def _code_key() -> str:
    here = Path(__file__).parent
    stamps = []
    for name in _SOURCES:
        try:
            status = os.stat(here / name)
            stamps.append(f"{name} {status.st_size}:{status.st_mtime_ns}")
        except OSError:
            stamps.append(f"{name} unreadable")
    return "; ".join([code_key(), *stamps])


def _encode(code: str, key: dict[str, Any], result: UnionResult) -> bytes | None:
    stored = {
        "mass_properties": _properties(result.mass_properties),
        "volume": result.volume,
        "parts_volume": result.parts_volume,
        "overlap_volume": result.overlap_volume,
        "exact": result.exact,
    }
    try:
        body = json.dumps(
            {"format": FORMAT, "code": code, "key": key, "union": stored}, separators=(",", ":")
        ).encode("ascii")
    except (TypeError, ValueError):
        return None
    return b"%08x " % zlib.crc32(body) + body + b"\n"


def _read(entry: str, code: str, key: dict[str, Any]) -> UnionResult | None:
    """The entry's union, or ``None`` for a missing, unreadable, corrupt or foreign entry."""
    try:
        with open_regular(entry) as stream:  # a pipe planted in a shared cache never blocks
            data = stream.read(MAX_ENTRY_BYTES + 1)
    except (OSError, ValueError):
        return None
    try:
        if len(data) > MAX_ENTRY_BYTES or data[8:9] != b" " or data[-1:] != b"\n":
            return None
        body = data[9:-1]
        if int(data[:8], 16) != zlib.crc32(body):
            return None
        document = json.loads(body)
        if document["format"] != FORMAT or document["code"] != code or document["key"] != key:
            return None
        stored = document["union"]
        mass, com, inertia = stored["mass_properties"]
        return UnionResult(
            MassProperties(float(mass), com, inertia),
            float(stored["volume"]),
            float(stored["parts_volume"]),
            float(stored["overlap_volume"]),
            bool(stored["exact"]),
        )
    except Exception:  # whatever a damaged or foreign file makes json or numpy raise
        return None
