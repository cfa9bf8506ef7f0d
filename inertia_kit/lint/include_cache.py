"""
The include graph's on-disk cache: what each robot file of a repository is and which files it
read, so that a hook run re-expands only the robots whose files changed.

Location
  Beside the mesh cache (:func:`~inertia_kit.physics.mesh_cache.cache_location`:
  ``$INERTIA_KIT_CACHE_DIR``, ``$XDG_CACHE_HOME/inertia-kit`` or ``~/.cache/inertia-kit``;
  ``INERTIA_KIT_NO_CACHE=1`` turns it off), one file per repository and expansion options:
  ``includes-v2/<folder name>-<64-bit hash>.json``.
Key
  The file holds the repository's real path, the ``--xacro-arg`` values and package paths the
  robots were expanded with, and a code key (this format, the package version, the size and
  mtime of the modules that scan); any difference and the whole file is ignored. Each entry is
  kept only while its file and every file it read have the size and mtime recorded (a robot
  whose includes changed is scanned again).
Format and failures
  One line ``<crc32 hex> <json>``, written to a temporary file and renamed over the old one
  (the mesh cache's :func:`~inertia_kit.physics.mesh_cache_entries.write_entry`); a corrupt,
  truncated, foreign or unreadable file is ignored (everything is scanned again) and replaced.
"""

from __future__ import annotations

import functools
import json
import os
import zlib
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, NamedTuple

from inertia_kit.reading import open_regular, read_at_most
from inertia_kit.version import __version__

#: Version of the file layout; part of the folder name and of every file.
FORMAT = 2  # 2: a xacro file without links or joints is a fragment, whatever tags its top holds
#: A cache file larger than this is not one of ours (some 100 000 robot files).
MAX_BYTES = 64 << 20
KINDS = ("plain", "robot", "fragment", "error", "static")
# the modules whose code decides what a scan records
_SOURCES = (
    "include_graph.py",
    "include_cache.py",
    "../description/urdf/xacro_expand.py",
    "../description/urdf/reader.py",
    "../description/urdf/xacro_includes.py",
)


class Stamp(NamedTuple):
    size: int
    mtime_ns: int


def stamp(path: str) -> Stamp | None:
    """The file's size and mtime, or ``None`` for a missing or unreadable one."""
    try:
        status = os.stat(path)
    except (OSError, ValueError):
        return None
    return Stamp(status.st_size, status.st_mtime_ns)


@dataclass(frozen=True)
class Entry:
    """
    One robot file: ``kind`` (``plain``: reads no other file, not expanded; ``robot``;
    ``fragment``; ``error``: xacro refuses it on its own; ``static``: not expanded, as its
    includes as written reach no file asked about) and ``reads``, the files its expansion read
    (for ``static``, every file its includes as written reach) with their stamps, the file
    itself first.
    """

    kind: str
    reads: tuple[tuple[str, Stamp], ...]

    def current(self) -> bool:
        """Whether every file read is still as it was."""
        return all(stamp(path) == found for path, found in self.reads)

    def to_json(self) -> list[Any]:
        return [self.kind, [[path, *found] for path, found in self.reads]]

    @classmethod
    def from_json(cls, data: Any) -> Entry:
        kind, reads = data
        if kind not in KINDS or not isinstance(reads, list) or not reads:
            raise ValueError("not an entry")
        parsed = []
        for path, size, mtime_ns in reads:
            if not (isinstance(path, str) and type(size) is int and type(mtime_ns) is int):
                raise TypeError("not a stamp")
            parsed.append((path, Stamp(size, mtime_ns)))
        return cls(kind, tuple(parsed))


def load_entries(
    root: Path, options: Mapping[str, Any], cache_dir: str | Path | None = None
) -> dict[str, Entry]:
    """The cached entries of the repository at ``root`` (real path → entry); ``{}`` if none."""
    file = _file(root, options, cache_dir)
    if file is None:
        return {}
    try:
        with open_regular(file) as stream:  # a pipe planted in a shared cache never blocks
            data = read_at_most(stream, MAX_BYTES)
    except OSError:
        return {}
    try:
        return _decode(data, _key(root, options))
    except Exception:  # whatever a damaged or foreign file makes json raise: scan again
        return {}


def save_entries(
    root: Path,
    options: Mapping[str, Any],
    entries: Mapping[str, Entry],
    cache_dir: str | Path | None = None,
) -> None:
    """Replace the repository's cache file atomically; an unwritable location stores nothing."""
    from inertia_kit.physics.mesh_cache import cache_location
    from inertia_kit.physics.mesh_cache_entries import write_entry

    file = _file(root, options, cache_dir)
    folder = cache_location(cache_dir)
    if file is None or folder is None:
        return
    body = json.dumps(
        {
            "format": FORMAT,
            "key": _key(root, options),
            "entries": {path: entry.to_json() for path, entry in sorted(entries.items())},
        },
        separators=(",", ":"),
    ).encode("utf-8")
    write_entry(str(folder), str(file), b"%08x " % zlib.crc32(body) + body + b"\n")


def _decode(data: bytes, key: Mapping[str, Any]) -> dict[str, Entry]:
    if len(data) > MAX_BYTES:
        raise ValueError("too large")
    crc, _, body = data.rstrip(b"\n").partition(b" ")
    if int(crc, 16) != zlib.crc32(body):
        raise ValueError("CRC")
    document = json.loads(body)
    if document["format"] != FORMAT or document["key"] != key:
        raise ValueError("another key")
    return {path: Entry.from_json(entry) for path, entry in document["entries"].items()}


def _key(root: Path, options: Mapping[str, Any]) -> dict[str, Any]:
    # through json, so that it compares equal to what is read back (tuples become lists)
    return json.loads(json.dumps({"root": str(root), **options, "code": code_key()}))


def _file(root: Path, options: Mapping[str, Any], cache_dir: str | Path | None) -> Path | None:
    from inertia_kit.physics.mesh_cache import cache_location

    folder = cache_location(cache_dir)
    if folder is None:
        return None
    data = json.dumps({"root": str(root), **options}, sort_keys=True).encode()
    digest = f"{zlib.crc32(data):08x}{zlib.adler32(data):08x}"
    name = "".join(c if c.isalnum() or c in "._-" else "_" for c in root.name) or "root"
    return folder / f"includes-v{FORMAT}" / f"{name[:64]}-{digest}.json"


@functools.cache
def code_key() -> str:
    """What the recorded reads depend on besides the files: a change drops every entry."""
    here = Path(__file__).parent
    parts = [f"format {FORMAT}", f"inertia-kit {__version__}"]
    for name in _SOURCES:
        found = stamp(os.path.normpath(here / name))
        parts.append(f"{name} {'absent' if found is None else f'{found[0]}:{found[1]}'}")
    return "; ".join(parts)
