"""
What a load read: a digest of the bytes of every file (the input and every xacro file it
includes), by real path, so that whoever later edits one of them (``--fix``, ``inertia-fill``,
``--add-noqa``) edits the very text the findings and the edits were computed on.

A file the load read is read again for editing with :func:`as_loaded`, which refuses it
(:class:`~inertia_kit.description.edits.ChangedWhileEditing`) when its bytes are no longer the
ones the load read; the write then checks, at the atomic replace, that the file still holds
those bytes (``expected`` of :func:`~inertia_kit.description.edits.write_all_atomic`). Between
the two, another writer (an editor's save, a second hook, another ``inertia-fill``) is seen,
and nothing is written.

A file read twice in one load with different bytes (a xacro file included twice while it was
being saved) has no digest (``None``): it is refused for editing.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING

try:
    # hashlib's own blake2b (``hashlib.blake2b is _blake2.blake2b``), without importing hashlib,
    # which loads OpenSSL for its other algorithms: ~3 ms of every run, for one digest
    from _blake2 import blake2b
except ImportError:  # pragma: no cover - an interpreter built without its BLAKE2 module
    from hashlib import blake2b

if TYPE_CHECKING:
    from inertia_kit.description.edits import SourceText

#: real path -> digest of the bytes read (``None``: read twice, with different bytes)
Reads = Mapping[str, "str | None"]


def digest(data: bytes) -> str:
    """A digest of ``data`` (BLAKE2b, 128 bits: no two texts of a run share one)."""
    return blake2b(data, digest_size=16).hexdigest()


def key(path: str | Path) -> str:
    """The name a file is known by in :data:`Reads`: its real path."""
    return os.path.realpath(path)


def record(reads: dict[str, str | None], path: str | Path, data: bytes) -> None:
    """Note that ``path`` was read holding ``data``."""
    name, found = key(path), digest(data)
    if name in reads and reads[name] != found:
        reads[name] = None  # two reads, two texts: no edit can be computed on "the" text
    else:
        reads[name] = found


def combined(each: Iterable[Reads]) -> dict[str, str | None]:
    """Several loads' reads as one; a file two loads read with different bytes has none."""
    result: dict[str, str | None] = {}
    for reads in each:
        for name, found in reads.items():
            if name in result and result[name] != found:
                result[name] = None
            else:
                result[name] = found
    return result


def changed(path: str | Path, data: bytes, reads: Reads) -> bool:
    """Whether the load read ``path`` with other bytes than ``data`` (unknown files: no)."""
    name = key(path)
    return name in reads and reads[name] != digest(data)


def as_loaded(path: str | Path, reads: Reads) -> SourceText:
    """
    ``path`` read for editing (:func:`~inertia_kit.description.edits.read_source`), refused
    with ``ChangedWhileEditing`` when the load read other bytes there.
    """
    from inertia_kit.description.edits import read_source

    source = read_source(path)
    check(source, reads)
    return source


def check(source: SourceText, reads: Reads) -> None:
    """``ChangedWhileEditing`` when ``source`` is not the text the load read."""
    from inertia_kit.description.edits import CHANGED, ChangedWhileEditing

    if changed(source.path, source.original, reads):
        raise ChangedWhileEditing(CHANGED, source.path)
