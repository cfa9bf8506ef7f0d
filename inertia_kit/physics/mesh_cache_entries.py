"""
The mesh cache's entries: how one is encoded, written, read back and checked, and how the
folder is kept to a bounded size. :mod:`.mesh_cache` decides which entry a mesh has.

Format
  One file per mesh and code key: ``<cache>/meshes-v1/<name>-<64-bit hash>.json``, holding one
  line ``<crc32 hex> <json>``. JSON because Python's float ``repr`` round-trips every float64
  exactly (and ``-0.0``, ``inf``, ``nan``), ``json`` is already imported by the CLI, an entry
  (~1 KB) is checked and parsed in ~25 µs, and a person can read it; an ``.npz`` of the same
  arrays takes ~600 µs to load (a zip archive). The CRC catches truncation and bit rot; the key
  inside the entry is compared in full.
Concurrency and failures
  An entry is written to a temporary file in the same folder and renamed over the old one
  (``os.replace``), so readers see a whole entry or none, and concurrent writers of the same
  entry each install a whole, identical file. A corrupt, truncated, foreign or unreadable entry
  is ignored, recomputed and overwritten; an unwritable location only means nothing is stored.
  No ``fsync``: a crash can at worst leave an entry that fails its CRC, which is recomputed.
Size
  At most :data:`MAX_ENTRIES` entries (a few KB each on disk, so some 40 MB at worst): a process
  that writes an entry then deletes the least recently used ones beyond the cap, and temporary
  files abandoned by crashed writers. Hits refresh an entry's mtime at most once a day.
"""

from __future__ import annotations

import contextlib
import functools
import json
import os
import time
import zlib
from collections.abc import Mapping
from dataclasses import fields
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from inertia_kit.physics.meshes import MeshSolid
from inertia_kit.physics.volume_moments import VolumeMoments
from inertia_kit.reading import open_regular

#: Version of the entry layout; part of the folder name and of every entry.
FORMAT = 1
#: Entries kept at most; pruning brings the count down to 90 % of it.
MAX_ENTRIES = 10_000
#: An entry larger than this is not one of ours.
MAX_ENTRY_BYTES = 1 << 16

# MeshSolid fields rebuilt from the scale; every other field is stored as it is
_SCALED = frozenset({"path", "scale", "moments", "bounds"})
_SCALARS: dict[str, type] = {
    "bool": bool,
    "int": int,
    "float": float,
    "str": str,
    "float64": np.float64,
    "int64": np.int64,
    "bool_": np.bool_,
}
_SCALAR_TAGS = {kind: tag for tag, kind in _SCALARS.items()}
_DAY_SECONDS = 86_400.0
_STALE_TEMP_SECONDS = 3_600.0
_pruned: set[str] = set()  # folders pruned by this process


class UnscaledSolid:
    """A mesh's solid before its unit and ``scale``: what an entry holds."""

    # a plain class: a dataclass costs ~1 ms of start-up to create
    __slots__ = ("bounds", "moments", "other")

    def __init__(self, moments: VolumeMoments, bounds: NDArray[np.float64], other: dict[str, Any]):
        self.moments = moments  # in the file's unit
        self.bounds = bounds  # (2, 3), in the file's unit
        self.other = other  # every other MeshSolid field but path, scale, moments and bounds

    @classmethod
    def of(cls, solid: MeshSolid) -> UnscaledSolid | None:
        """From a solid computed at a ``scale`` that, with its unit, makes factors of exactly 1."""
        other = {f.name: getattr(solid, f.name) for f in fields(solid) if f.name not in _SCALED}
        if not all(type(value) in _SCALAR_TAGS for value in other.values()):
            return None  # a field of a kind this format does not know: do not cache
        return cls(solid.moments, solid.bounds, other)

    def to_json(self) -> dict[str, Any]:
        m = self.moments
        arrays = {"first": m.first, "second": m.second, "origin": m.origin, "bounds": self.bounds}
        if not all(np.asarray(a).dtype == np.float64 for a in arrays.values()):
            raise TypeError("not float64")
        return {
            "volume": _scalar(m.volume),
            **{name: np.asarray(a).ravel().tolist() for name, a in arrays.items()},
            "other": {name: _scalar(value) for name, value in self.other.items()},
        }

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> UnscaledSolid:
        moments = VolumeMoments(
            _unscalar(data["volume"]),
            _array(data["first"], (3,)),
            _array(data["second"], (3, 3)),
            _array(data["origin"], (3,)),
        )
        other = {name: _unscalar(value) for name, value in data["other"].items()}
        if set(other) != _stored_fields():
            raise ValueError(f"fields {sorted(other)}, expected {sorted(_stored_fields())}")
        if not isinstance(other["unit_scale"], float) or not other["unit_scale"] > 0:
            raise ValueError("unit_scale")
        return cls(moments, _array(data["bounds"], (2, 3)), other)


@functools.cache
def _stored_fields() -> frozenset[str]:
    return frozenset(f.name for f in fields(MeshSolid)) - _SCALED


def _scalar(value: Any) -> list[Any]:
    """``[type, value]``: numpy scalars come back as numpy scalars, as mesh_solid made them."""
    tag = _SCALAR_TAGS[type(value)]
    return [tag, value.item() if isinstance(value, np.generic) else value]


def _unscalar(data: Any) -> Any:
    tag, value = data
    kind = _SCALARS[tag]
    # exact types: json reads 1.0 back as a float and 1 as an int, so anything else is foreign
    if type(value) is not {np.float64: float, np.int64: int, np.bool_: bool}.get(kind, kind):
        raise TypeError(f"{tag} holding {type(value).__name__}")
    return kind(value)


def _array(values: Any, shape: tuple[int, ...]) -> NDArray[np.float64]:
    if not isinstance(values, list) or not all(type(v) is float for v in values):
        raise TypeError("not a list of floats")
    return np.array(values, dtype=np.float64).reshape(shape)


def encode(key: Mapping[str, Any], code: str, raw: UnscaledSolid) -> bytes | None:
    """An entry's bytes for the file ``key`` and the code key ``code``; ``None`` if unstorable."""
    try:
        solid = raw.to_json()
    except (TypeError, KeyError):
        return None
    body = json.dumps(
        {"format": FORMAT, "code": code, "key": key, "solid": solid}, separators=(",", ":")
    ).encode("ascii")
    return b"%08x " % zlib.crc32(body) + body + b"\n"


def read_entry(entry: str, key: Mapping[str, Any], code: str) -> UnscaledSolid | None:
    """The entry's solid, or ``None`` for a missing, unreadable, corrupt or foreign entry."""
    try:
        with open_regular(entry) as stream:  # a pipe planted in a shared cache never blocks
            data = stream.read(MAX_ENTRY_BYTES + 1)
            touched = os.fstat(stream.fileno()).st_mtime
    except (OSError, ValueError):
        return None
    try:
        raw = decode(data, key, code)
    except Exception:  # whatever a damaged or foreign file makes json or numpy raise
        return None
    if time.time() - touched > _DAY_SECONDS:  # keep recently used entries from being pruned
        with contextlib.suppress(OSError):
            os.utime(entry)
    return raw


def decode(data: bytes, key: Mapping[str, Any], code: str) -> UnscaledSolid:
    """The solid in an entry's bytes; raises unless they are whole and for this key and code."""
    if len(data) > MAX_ENTRY_BYTES or len(data) < 10 or data[8:9] != b" " or data[-1:] != b"\n":
        raise ValueError("not an entry")
    body = data[9:-1]
    if int(data[:8], 16) != zlib.crc32(body):
        raise ValueError("checksum")
    document = json.loads(body)
    if document["format"] != FORMAT or document["code"] != code or document["key"] != key:
        raise ValueError("another file, version or format")
    return UnscaledSolid.from_json(document["solid"])


def write_entry(folder: str, entry: str, payload: bytes | None) -> None:
    """Install ``payload`` atomically; a location we cannot write only means no caching."""
    if payload is None:
        return
    entries, name = os.path.split(entry)
    temporary = os.path.join(entries, f".{name}.{os.getpid()}.{os.urandom(4).hex()}.tmp")
    try:
        try:
            descriptor = _create(temporary)
        except FileNotFoundError:
            _make_folders(folder, entries)
            descriptor = _create(temporary)
        try:
            with os.fdopen(descriptor, "wb") as stream:
                stream.write(payload)
            os.replace(temporary, entry)
        except BaseException:
            with contextlib.suppress(OSError):
                os.unlink(temporary)
            raise
    except OSError:
        return
    if entries not in _pruned:
        _pruned.add(entries)
        prune(entries)


def _create(path: str) -> int:
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0)
    return os.open(path, flags, 0o666)  # the umask decides, as for any file the user writes


def _make_folders(folder: str, entries: str) -> None:
    os.makedirs(entries, exist_ok=True)
    tag = os.path.join(folder, "CACHEDIR.TAG")
    if not os.path.exists(tag):  # https://bford.info/cachedir/: backup tools skip the folder
        with contextlib.suppress(OSError), open(tag, "w", encoding="ascii") as stream:
            stream.write(
                "Signature: 8a477f597d28d172789f06886806bc55\n"
                "# This file is a cache tag created by inertia-kit.\n"
            )


def prune(entries: str | Path, max_entries: int | None = None) -> int:
    """
    Delete the least recently used entries beyond ``max_entries`` (default :data:`MAX_ENTRIES`),
    down to 90 % of it, and temporary files older than an hour. Returns how many were deleted.
    """
    limit = MAX_ENTRIES if max_entries is None else max_entries
    now = time.time()
    found: list[str] = []
    deleted = 0
    try:
        with os.scandir(entries) as scan:
            for item in scan:
                if item.name.endswith(".json"):
                    found.append(item.path)  # no stat: counting is all most runs need
                elif item.name.endswith(".tmp"):
                    try:
                        if now - item.stat().st_mtime > _STALE_TEMP_SECONDS:
                            os.unlink(item.path)
                            deleted += 1
                    except OSError:
                        pass
    except OSError:
        return deleted
    if len(found) <= limit:
        return deleted
    dated = []
    for path in found:
        with contextlib.suppress(OSError):
            dated.append((os.stat(path).st_mtime, path))
    dated.sort()
    for _, path in dated[: max(0, len(dated) - int(0.9 * limit))]:
        try:
            os.unlink(path)
            deleted += 1
        except OSError:
            pass
    return deleted
