"""
An on-disk cache of mesh mass properties, so that linting again without changing a mesh does
not read it (nor import trimesh for it).

:func:`cached_mesh_solid` is :func:`inertia_kit.physics.meshes.mesh_solid` with a memory: the same
results, bit for bit, and the same errors.

What is stored
  The solid before any scale: the volume integrals and bounds in the file's own unit, with every
  other :class:`~.meshes.MeshSolid` field (method, closure, triangle count, unit...).
  The URDF ``scale`` and the file's unit are applied on the way out with the arithmetic
  ``mesh_solid`` uses, so one entry serves every ``scale`` a mesh is used with.
Key
  The resolved absolute path (symbolic links followed), the suffix the caller named it by (it
  picks the reader), and the file's size, mtime, ctime and inode: any write, rename over it,
  ``chmod`` or checkout changes one of them. A file changed less than :data:`RACY_SECONDS` ago
  is not stored, since a second write within the file system's timestamp tick would leave the
  key unchanged (git's "racily clean" problem). Entries also carry a *code key* (this format's
  version, the package version, numpy's version, the size and mtime of the modules that compute
  the numbers, and of trimesh, manifold3d, pycollada and networkx as installed), so an upgrade,
  or an edit of an editable install, recomputes instead of serving old numbers.
Format
  One file per mesh and code key: ``<cache>/meshes-v1/<name>-<64-bit hash>.json``, holding one
  line ``<crc32 hex> <json>``. JSON because Python's float ``repr`` round-trips every float64
  exactly (and ``-0.0``, ``inf``, ``nan``), ``json`` is already imported by the CLI, an entry
  (~1 KB) is checked and parsed in ~25 µs, and a person can read it; an ``.npz`` of the same
  arrays takes ~600 µs to load (a zip archive). The CRC catches truncation and bit rot; the key
  inside the entry is compared in full.
Location
  ``$INERTIA_KIT_CACHE_DIR``, else ``$XDG_CACHE_HOME/inertia-kit``, else
  ``~/.cache/inertia-kit``; ``INERTIA_KIT_NO_CACHE=1`` turns the cache off.
Concurrency and failures
  An entry is written to a temporary file in the same folder and renamed over the old one
  (``os.replace``), so readers see a whole entry or none, and concurrent writers of the same
  entry each install a whole, identical file. A corrupt, truncated, foreign or unreadable entry
  is ignored, recomputed and overwritten; an unwritable location only means nothing is stored.
  No ``fsync``: a crash can at worst leave an entry that fails its CRC, which is recomputed.
Errors
  Not stored: a missing file has nothing to key on, and an unreadable one can be caused by
  things the key does not see (permissions, a missing optional dependency). Every error comes
  from ``mesh_solid`` itself, so it is the same as without the cache.
Size
  At most :data:`MAX_ENTRIES` entries (a few KB each on disk, so some 40 MB at worst): a process
  that writes an entry then deletes the least recently used ones beyond the cap, and temporary
  files abandoned by crashed writers. Hits refresh an entry's mtime at most once a day.
"""

from __future__ import annotations

import contextlib
import functools
import importlib.util
import json
import math
import os
import stat
import time
import zlib
from collections.abc import Mapping
from dataclasses import fields
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from inertia_kit.physics.mesh_formats import FORMATS
from inertia_kit.physics.meshes import MeshSolid, mesh_solid, scaled_solid
from inertia_kit.physics.volume_moments import VolumeMoments
from inertia_kit.version import __version__

#: Version of the entry layout; part of the folder name and of every entry.
FORMAT = 1
#: Entries kept at most; pruning brings the count down to 90 % of it.
MAX_ENTRIES = 10_000
#: A mesh changed more recently than this is computed but not stored (see the module docstring).
RACY_SECONDS = 2.0
#: An entry larger than this is not one of ours.
MAX_ENTRY_BYTES = 1 << 16

ENV_DIR = "INERTIA_KIT_CACHE_DIR"
ENV_DISABLE = "INERTIA_KIT_NO_CACHE"

# the modules whose code decides the numbers, and the libraries they may call
_SOURCES = (
    "meshes.py",
    "mesh_formats.py",
    "mesh_closure.py",
    "volume_moments.py",
    "polyhedra.py",
    "stl.py",
    "mesh_cache.py",
)
_LIBRARIES = ("trimesh", "manifold3d", "collada", "networkx")
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


def cached_mesh_solid(
    path: str | Path,
    scale: ArrayLike = (1.0, 1.0, 1.0),
    *,
    cache_dir: str | Path | None = None,
) -> MeshSolid:
    """
    :func:`~.meshes.mesh_solid`, served from the on-disk cache when the file has not changed.

    Parameters
    ----------
    path : str or Path
      STL, OBJ, DAE, PLY, GLB or glTF file.
    scale : (3,) float
      URDF per-axis ``scale``; negative factors mirror.
    cache_dir : str or Path, optional
      The cache folder; default :func:`cache_location`. ``INERTIA_KIT_NO_CACHE`` overrides it.

    Raises
    ------
    MeshError, ValueError
      As ``mesh_solid``, which raises them: errors are never cached.
    """
    factors = _valid_scale(scale)
    folder = _location(cache_dir)
    key = None if factors is None or folder is None else _key(path)
    if key is None:
        # a bad scale, no cache, or a file that is missing or of an unknown format: mesh_solid
        # raises exactly what it raises
        return mesh_solid(path, scale)
    assert factors is not None and folder is not None
    code = code_key()
    entry = os.path.join(folder, f"meshes-v{FORMAT}", _entry_name(key, code))
    raw = _read(entry, key, code)
    if raw is None:
        raw = _unscaled(path)
        if raw is None:
            return mesh_solid(path, scale)
        if _storable(path, key):
            _write(folder, entry, _encode(key, code, raw))
    return scaled_solid(path, raw.moments, raw.bounds, factors, **raw.other)


def cache_location(cache_dir: str | Path | None = None) -> Path | None:
    """
    The cache folder: ``cache_dir`` if given, else ``$INERTIA_KIT_CACHE_DIR``, else
    ``$XDG_CACHE_HOME/inertia-kit`` (an absolute one), else ``~/.cache/inertia-kit``;
    ``None`` when ``INERTIA_KIT_NO_CACHE`` is set (to anything but ``0``, ``false``, ``no``,
    ``off`` or nothing) or there is no home folder.
    """
    folder = _location(cache_dir)
    return None if folder is None else Path(folder)


def _location(cache_dir: str | Path | None) -> str | None:
    # os.path, not pathlib: this runs for every mesh, and Path() costs ~20 µs each
    if os.environ.get(ENV_DISABLE, "").strip().lower() not in ("", "0", "false", "no", "off"):
        return None
    if cache_dir is not None:
        return os.path.expanduser(os.fspath(cache_dir))
    configured = os.environ.get(ENV_DIR)
    if configured:
        return os.path.expanduser(configured)
    xdg = os.environ.get("XDG_CACHE_HOME")
    if xdg and os.path.isabs(xdg):  # the XDG spec: a relative value is invalid, ignore it
        return os.path.join(xdg, "inertia-kit")
    home = os.path.expanduser("~")
    return None if home == "~" else os.path.join(home, ".cache", "inertia-kit")


@functools.cache
def code_key() -> str:
    """
    What the cached numbers depend on besides the file: a change invalidates every entry.

    Stat calls only (no imports): ~0.3 ms, once per process.
    """
    parts = [f"format {FORMAT}", f"inertia-kit {__version__}", f"numpy {np.__version__}"]
    here = Path(__file__).parent
    parts += [f"{name} {_stamp(here / name)}" for name in _SOURCES]
    for name in _LIBRARIES:
        try:
            spec = importlib.util.find_spec(name)
        except (ImportError, ValueError):
            spec = None
        origin = spec.origin if spec is not None else None
        parts.append(f"{name} {_stamp(origin) if origin else 'absent'}")
    return "; ".join(parts)


def _stamp(path: str | Path) -> str:
    try:
        status = os.stat(path)
    except OSError:
        return "unreadable"
    return f"{status.st_size}:{status.st_mtime_ns}"


def _valid_scale(scale: ArrayLike) -> tuple[float, float, float] | None:
    """``scale`` as mesh_solid accepts it, or ``None`` (mesh_solid then raises its error)."""
    try:
        factors = np.asarray(scale, dtype=np.float64)
    except (TypeError, ValueError):
        return None
    if factors.shape != (3,) or not np.isfinite(factors).all() or np.any(factors == 0):
        return None
    x, y, z = (float(s) for s in factors)
    return x, y, z


def _key(path: str | Path) -> dict[str, Any] | None:
    """What identifies the file's content; ``None`` for anything but a regular mesh file."""
    try:
        file = Path(path)
        suffix = file.suffix.lower()  # the suffix mesh_solid picks the reader by
        if suffix not in FORMATS:
            return None
        resolved = os.path.realpath(file)
        status = os.stat(resolved)
    except (OSError, TypeError, ValueError):
        return None
    if not stat.S_ISREG(status.st_mode):
        return None
    return {
        "path": resolved,
        "suffix": suffix,
        "size": status.st_size,
        "mtime_ns": status.st_mtime_ns,
        "ctime_ns": status.st_ctime_ns,
        "inode": status.st_ino,
    }


def _entry_name(key: Mapping[str, Any], code: str) -> str:
    """``<file name>-<64-bit hash of code key, suffix and path>.json``: readable, no clashes."""
    data = f"{code}\0{key['suffix']}\0".encode() + os.fsencode(key["path"])
    digest = f"{zlib.crc32(data):08x}{zlib.adler32(data):08x}"
    name = "".join(c if c.isalnum() or c in "._-" else "_" for c in os.path.basename(key["path"]))
    return f"{name[:64]}-{digest}.json"


def _storable(path: str | Path, key: Mapping[str, Any]) -> bool:
    """The file did not change while it was read, and not so recently that it may again."""
    if _key(path) != key:
        return False
    changed = max(key["mtime_ns"], key["ctime_ns"])
    return time.time_ns() - changed >= RACY_SECONDS * 1e9


# --- the unscaled solid --------------------------------------------------------------------------


class _Raw:
    """A mesh's solid before its unit and ``scale``: what an entry holds."""

    # a plain class: a dataclass costs ~1 ms of start-up to create
    __slots__ = ("bounds", "moments", "other")

    def __init__(self, moments: VolumeMoments, bounds: NDArray[np.float64], other: dict[str, Any]):
        self.moments = moments  # in the file's unit
        self.bounds = bounds  # (2, 3), in the file's unit
        self.other = other  # every other MeshSolid field but path, scale, moments and bounds

    @classmethod
    def of(cls, solid: MeshSolid) -> _Raw | None:
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
    def from_json(cls, data: Mapping[str, Any]) -> _Raw:
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


def _unscaled(path: str | Path) -> _Raw | None:
    """
    Compute the solid before unit and scale with ``mesh_solid`` itself (raising its errors).

    At scale 1 a file in metres gives exactly that (scaling by ones is exact). A file in another
    unit ``u`` (COLLADA ``<unit meter>``) is read again at a scale ``c`` with ``u * c == 1.0``
    exactly, once, when it is first cached; ``None`` if no such ``c`` exists.
    """
    solid = mesh_solid(path)
    unit = solid.unit_scale
    if unit != 1.0:
        inverse = _exact_inverse(unit)
        if inverse is None:
            return None
        solid = mesh_solid(path, (inverse, inverse, inverse))
        if solid.unit_scale != unit:  # the file changed in between
            return None
    return _Raw.of(solid)


def _exact_inverse(unit: float) -> float | None:
    guess = 1.0 / unit
    for c in (guess, math.nextafter(guess, math.inf), math.nextafter(guess, 0.0)):
        if math.isfinite(c) and unit * c == 1.0:
            return c
    return None


# --- entries ------------------------------------------------------------------------------------


def _encode(key: Mapping[str, Any], code: str, raw: _Raw) -> bytes | None:
    try:
        solid = raw.to_json()
    except (TypeError, KeyError):
        return None
    body = json.dumps(
        {"format": FORMAT, "code": code, "key": key, "solid": solid}, separators=(",", ":")
    ).encode("ascii")
    return b"%08x " % zlib.crc32(body) + body + b"\n"


def _read(entry: str, key: Mapping[str, Any], code: str) -> _Raw | None:
    """The entry's solid, or ``None`` for a missing, unreadable, corrupt or foreign entry."""
    try:
        with open(entry, "rb") as stream:
            data = stream.read(MAX_ENTRY_BYTES + 1)
            touched = os.fstat(stream.fileno()).st_mtime
    except (OSError, ValueError):
        return None
    try:
        raw = _decode(data, key, code)
    except Exception:  # whatever a damaged or foreign file makes json or numpy raise
        return None
    if time.time() - touched > _DAY_SECONDS:  # keep recently used entries from being pruned
        with contextlib.suppress(OSError):
            os.utime(entry)
    return raw


def _decode(data: bytes, key: Mapping[str, Any], code: str) -> _Raw:
    if len(data) > MAX_ENTRY_BYTES or len(data) < 10 or data[8:9] != b" " or data[-1:] != b"\n":
        raise ValueError("not an entry")
    body = data[9:-1]
    if int(data[:8], 16) != zlib.crc32(body):
        raise ValueError("checksum")
    document = json.loads(body)
    if document["format"] != FORMAT or document["code"] != code or document["key"] != key:
        raise ValueError("another file, version or format")
    return _Raw.from_json(document["solid"])


def _write(folder: str, entry: str, payload: bytes | None) -> None:
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
