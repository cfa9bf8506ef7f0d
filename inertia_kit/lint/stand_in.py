"""
A robot read from stdin (``inertia-lint -``), linted or filled as if it stood at the path
``--stdin-filename`` names (else in the current folder): its bytes are written, as read, to a
stand-in file in that folder, so that everything that reads a file beside its neighbours -
relative ``xacro:include`` and ``$(find)``, relative mesh paths, ``package://`` lookup, the
nearest configuration - reads them there. The stand-in is hidden, left out of every folder walk
(:func:`is_stand_in`) and removed when done; ``per-file-ignores`` and ``force-exclude`` judge
the name it stands for (:func:`named`).
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager, suppress
from pathlib import Path

PREFIX = ".inertia-kit-stdin-"
#: the absolute path of each stand-in -> the absolute path it stands for
_STANDING_FOR: dict[str, str] = {}


def is_stand_in(name: str) -> bool:
    """Whether a file name is a stand-in's (a walk leaves it out)."""
    return name.startswith(PREFIX)


def named(path: str | Path) -> str:
    """The path a stand-in stands for; any other path as it is."""
    return _STANDING_FOR.get(os.path.abspath(path), os.fspath(path))


@contextmanager
def stand_in(data: bytes, filename: str | None) -> Iterator[str]:
    """
    A stand-in file holding ``data`` beside ``filename`` (``None``: in the current folder,
    named as a xacro or URDF file by its content); its path as given, removed on exit. Raises
    ``OSError`` when the folder cannot take it.
    """
    from inertia_kit.description.loader import stand_in_suffix

    if filename is None:
        folder, suffix = "", stand_in_suffix(data)
        stands_for = os.path.abspath("-")
    else:
        folder, name = os.path.split(filename)
        suffix = "-" + name
        stands_for = os.path.abspath(filename)
    import secrets  # hmac and hashlib: only for a run that reads stdin

    path = os.path.join(folder, f"{PREFIX}{secrets.token_hex(4)}{suffix}")
    descriptor = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
    try:
        with os.fdopen(descriptor, "wb") as stream:
            stream.write(data)
        _STANDING_FOR[os.path.abspath(path)] = stands_for
        yield path
    finally:
        _STANDING_FOR.pop(os.path.abspath(path), None)
        with suppress(OSError):
            os.unlink(path)
