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
Location
  ``$INERTIA_KIT_CACHE_DIR``, else ``$XDG_CACHE_HOME/inertia-kit``, else
  ``~/.cache/inertia-kit``; ``INERTIA_KIT_NO_CACHE=1`` turns the cache off.
Errors
  Not stored: a missing file has nothing to key on, and an unreadable one can be caused by
  things the key does not see (permissions, a missing optional dependency). Every error comes
  from ``mesh_solid`` itself, so it is the same as without the cache.
Entries
  One JSON file per mesh and code key, written atomically and checked by a CRC when read; the
  folder is kept to a bounded size. How: :mod:`.mesh_cache_entries`.
"""

from __future__ import annotations

import functools
import importlib.util
import math
import os
import stat
import time
import zlib
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from inertia_kit.physics.mesh_cache_entries import (
    FORMAT,
    UnscaledSolid,
    encode,
    read_entry,
    write_entry,
)
from inertia_kit.physics.mesh_formats import FORMATS
from inertia_kit.physics.meshes import MeshSolid, mesh_solid, scaled_solid
from inertia_kit.version import __version__

#: A mesh changed more recently than this is computed but not stored (see the module docstring).
RACY_SECONDS = 2.0

ENV_DIR = "INERTIA_KIT_CACHE_DIR"
ENV_DISABLE = "INERTIA_KIT_NO_CACHE"

# the modules whose code decides the numbers (every physics module computing a mesh imports:
# tests/physics/test_mesh_cache.py), and the libraries they may call
_SOURCES = (
    "meshes.py",
    "mesh_formats.py",
    "mesh_closure.py",
    "volume_moments.py",
    "polyhedra.py",
    "stl.py",
    "collada.py",
    "obj_soup.py",
    "decimal_text.py",
    "obj_polygons.py",
    "frames.py",
    "manifolds.py",
    "mass.py",
    "primitives.py",
    "numbers.py",
    "formatting.py",
    "tensor_names.py",
    "mesh_cache.py",
    "mesh_cache_entries.py",
)
_LIBRARIES = ("trimesh", "manifold3d", "collada", "networkx")


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
    raw = read_entry(entry, key, code)
    if raw is None:
        raw = _unscaled(path)
        if raw is None:
            return mesh_solid(path, scale)
        if _storable(path, key):
            write_entry(folder, entry, encode(key, code, raw))
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


def _unscaled(path: str | Path) -> UnscaledSolid | None:
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
    return UnscaledSolid.of(solid)


def _exact_inverse(unit: float) -> float | None:
    guess = 1.0 / unit
    for c in (guess, math.nextafter(guess, math.inf), math.nextafter(guess, 0.0)):
        if math.isfinite(c) and unit * c == 1.0:
            return c
    return None
