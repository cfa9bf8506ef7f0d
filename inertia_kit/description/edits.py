"""
Text edits on the original bytes of a file, and atomic writes: every byte outside an edited span
stays as it was (comments, attribute order, quoting, indentation, encoding, line endings).
"""

from __future__ import annotations

import codecs
import contextlib
import os
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from inertia_kit.errors import InputError

_DECLARED_ENCODING = re.compile(rb"""^\s*<\?xml[^>]*\bencoding\s*=\s*["']([A-Za-z0-9._-]+)["']""")


@dataclass(frozen=True, order=True)
class Edit:
    """Replace ``original[start:end]`` of the file ``path`` with ``content`` (character offsets)."""

    path: str
    start: int
    end: int
    content: str


@dataclass(frozen=True)
class SourceText:
    """A file's text as read, with what it takes to write it back byte for byte."""

    path: str
    original: bytes
    text: str
    encoding: str
    bom: bytes

    @property
    def newline(self) -> str:
        """The file's line ending: the first one it uses, ``\\n`` if it has none."""
        match = re.search(r"\r\n|\n|\r", self.text)
        return match.group(0) if match else "\n"

    def encode(self, text: str) -> bytes:
        return self.bom + text.encode(self.encoding)

    def offset(self, line: int, column: int = 1) -> int:
        """Character offset of a 1-based line and column."""
        starts = self.line_starts
        if not 1 <= line <= len(starts):
            raise ValueError(f"{self.path}: no line {line}")
        return starts[line - 1] + column - 1

    @property
    def line_starts(self) -> list[int]:
        starts = [0]
        for match in re.finditer(r"\r\n|\n|\r", self.text):
            starts.append(match.end())
        return starts


def read_source(path: str | Path) -> SourceText:
    """Read a text file keeping its encoding and byte-order mark, for editing."""
    try:
        original = Path(path).read_bytes()
    except OSError as error:
        raise InputError(f"cannot read: {error.strerror or error}", path) from None
    bom = b""
    encoding = "utf-8"
    for mark, name in (
        (codecs.BOM_UTF8, "utf-8"),
        (codecs.BOM_UTF16_LE, "utf-16-le"),
        (codecs.BOM_UTF16_BE, "utf-16-be"),
    ):
        if original.startswith(mark):
            bom, encoding = mark, name
            break
    else:
        declared = _DECLARED_ENCODING.match(original)
        if declared:
            encoding = declared.group(1).decode("ascii").lower()
    try:
        text = original[len(bom) :].decode(encoding)
    except (LookupError, UnicodeDecodeError) as error:
        raise InputError(f"cannot decode as {encoding}: {error}", path) from None
    if bom + text.encode(encoding) != original:
        raise InputError(f"does not round-trip through {encoding}; refusing to edit", path)
    return SourceText(str(path), original, text, encoding, bom)


def apply_edits(text: str, edits: Iterable[Edit]) -> tuple[str, list[Edit]]:
    """
    Splice ``edits`` (character offsets into ``text``) in one pass.

    Returns the new text and the edits applied; an edit overlapping one already applied is
    skipped (the caller re-runs to a fixpoint, as ruff does).
    """
    applied: list[Edit] = []
    pieces: list[str] = []
    cursor = 0
    for edit in sorted(edits, key=lambda e: (e.start, e.end)):
        if not 0 <= edit.start <= edit.end <= len(text):
            raise ValueError(f"edit {edit.start}:{edit.end} outside the text (0:{len(text)})")
        if edit.start < cursor:
            continue
        pieces.append(text[cursor : edit.start])
        pieces.append(edit.content)
        cursor = edit.end
        applied.append(edit)
    pieces.append(text[cursor:])
    return "".join(pieces), applied


class ChangedWhileEditing(InputError):
    """The file on disk is no longer the one the edits were computed from."""


def write_atomic(
    path: str | Path, data: bytes, *, expected: bytes | None = None, create: bool = False
) -> bool:
    """
    Replace ``path``'s content with ``data`` atomically (temporary file in the same folder,
    ``fsync``, ``os.replace``), keeping its permission bits. Writes nothing when the bytes are
    already ``data``.

    ``expected`` is the content the edits were computed from: if the file no longer holds it
    (someone changed it meanwhile), nothing is written and ``ChangedWhileEditing`` is raised.
    With ``create``, a missing file is created (permissions from the umask), as for ``-o OUT``.

    Returns whether the file was written.
    """
    target = Path(path)
    current, mode = _state(target, create)
    if not _may_write(target, current, mode, data, expected):
        return False
    import tempfile  # here: its imports (shutil, random, bz2, lzma) cost start-up on every lint

    try:
        handle, temporary = tempfile.mkstemp(
            prefix=f".{target.name}.", suffix=".tmp", dir=target.parent
        )
    except OSError as error:
        raise InputError(f"cannot write: {error.strerror or error}", path) from None
    try:
        with os.fdopen(handle, "wb") as stream:
            stream.write(data)
            stream.flush()
            os.fsync(stream.fileno())
        os.chmod(temporary, mode)
        # a last look: a change between our read and now must not be overwritten
        if expected is not None and target.read_bytes() != expected:
            raise ChangedWhileEditing(
                "the file changed while it was being processed; nothing was written", path
            )
        os.replace(temporary, target)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(temporary)
        raise
    return True


def write_all_atomic(writes: Sequence[tuple[str | Path, bytes, bytes]]) -> bool:
    """
    ``(path, data, expected)`` for several files, each written as :func:`write_atomic` does;
    every file is checked first (still ``expected``, writable), so one that changed or is
    read-only stops the whole set before any file is written. Returns whether any was written.
    """
    for path, data, expected in writes:
        target = Path(path)
        _may_write(target, *_state(target, False), data, expected)
    written = False
    for path, data, expected in writes:
        written = write_atomic(path, data, expected=expected) or written
    return written


def _state(target: Path, create: bool) -> tuple[bytes | None, int]:
    """The file's bytes (``None``: to be created) and the permission bits to write with."""
    if target.is_dir():
        raise InputError("is a folder, not a file; nothing was written", target)
    if create and not target.exists():
        if not target.parent.is_dir():
            raise InputError(f"no folder {str(target.parent)!r} to write into", target)
        umask = os.umask(0)
        os.umask(umask)
        return None, 0o666 & ~umask
    try:
        current = target.read_bytes()
    except OSError as error:
        raise InputError(f"cannot read: {error.strerror or error}", target) from None
    return current, target.stat().st_mode & 0o7777


def _may_write(
    target: Path, current: bytes | None, mode: int, data: bytes, expected: bytes | None
) -> bool:
    """Whether ``data`` needs writing; ``InputError`` when it must not be."""
    if expected is not None and current != expected:
        raise ChangedWhileEditing(
            "the file changed while it was being processed; nothing was written", target
        )
    if current == data:
        return False
    # the permission bits, not os.access: a read-only file says "don't touch", even to root
    if current is not None and (not mode & 0o222 or not os.access(target, os.W_OK)):
        raise InputError("the file is read-only; nothing was written", target)
    return True
