"""
The JSON Lines record of ``inertia-kit scan``: one line per asset, each appended with one
``write`` of the whole line (``O_APPEND``), so that a run killed at any moment leaves complete
lines and at most one partial line at the end.

Resuming (:meth:`Record.resume`) cuts that partial line off, then keeps one line per asset: an
asset recorded with the content it has now is done; its line is dropped when the asset has
changed since (it is scanned again), or when it repeats a path already recorded. The file is
rewritten only when a line is dropped. One scan writes a record at a time (an exclusive
``flock`` on it while the scan runs).
"""

from __future__ import annotations

import json
import os
import stat
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any

from inertia_kit.errors import InputError

#: bytes read at a time from the end, looking for the last newline
_TAIL = 1 << 16


def encode(record: Mapping[str, Any]) -> bytes:
    """One line: compact JSON, ASCII (a newline or an undecodable file name is escaped)."""
    text = json.dumps(record, ensure_ascii=True, allow_nan=False, separators=(",", ":"))
    return text.encode("ascii") + b"\n"


def lines(path: str | Path) -> Iterator[dict[str, Any]]:
    """The records of a complete file, one at a time (a line that is no JSON object skipped)."""
    with open(path, "rb") as file:
        for raw in file:
            record = _parsed(raw)
            if record is not None:
                yield record


def _parsed(raw: bytes) -> dict[str, Any] | None:
    if not raw.endswith(b"\n"):
        return None  # the partial last line of a killed run
    try:
        record = json.loads(raw)
    except ValueError:
        return None
    return record if isinstance(record, dict) and isinstance(record.get("path"), str) else None


class Record:
    """The record file of a scan, opened for appending and locked (use in a ``with`` block)."""

    def __init__(self, path: str | Path):
        self.path = os.fspath(path)
        self.fd = -1

    def __enter__(self) -> Record:
        self._open()
        return self

    def __exit__(self, *exception: object) -> None:
        if self.fd >= 0:
            os.close(self.fd)
            self.fd = -1

    def _open(self) -> None:
        import fcntl

        try:
            self.fd = os.open(
                self.path, os.O_RDWR | os.O_APPEND | os.O_CREAT | os.O_NOFOLLOW, 0o644
            )
        except OSError as error:
            raise InputError(f"cannot write: {error.strerror}", self.path) from None
        if not stat.S_ISREG(os.fstat(self.fd).st_mode):
            # a device or a named pipe: the record is read back (to resume, for the summary and
            # the keep-list), and reading a pipe we hold open would wait for ever
            os.close(self.fd)
            self.fd = -1
            raise InputError("is not a regular file: a record is read back; give a file", self.path)
        try:
            fcntl.flock(self.fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            os.close(self.fd)
            self.fd = -1
            raise InputError("another scan is writing this record", self.path) from None

    def resume(self, hashes: Mapping[str, str | None]) -> set[str]:
        """
        The paths of ``hashes`` (path → sha256 now) recorded with that content, after cutting
        a partial last line and dropping stale and repeated lines.
        """
        _cut_partial(self.fd)
        done, dropped = _judged(self.path, hashes, None)
        if dropped:
            partial = self.path + ".partial"
            with open(partial, "wb") as kept:
                done, _ = _judged(self.path, hashes, kept)
            os.replace(partial, self.path)
            self.__exit__()  # the lock was on the file replaced
            self._open()
        return done

    def write(self, record: Mapping[str, Any]) -> None:
        """Append ``record``'s line: one ``write`` of the whole line."""
        data = encode(record)
        written = os.write(self.fd, data)
        while written < len(data):  # a short write (a full disk): the rest, or OSError
            written += os.write(self.fd, data[written:])


def _cut_partial(fd: int) -> None:
    """Truncate the file after its last newline (a line a kill cut short)."""
    end = os.lseek(fd, 0, os.SEEK_END)
    at = end
    while at > 0:
        start = max(0, at - _TAIL)
        block = os.pread(fd, at - start, start)
        newline = block.rfind(b"\n")
        if newline >= 0:
            at = start + newline + 1
            break
        at = start
    if at != end:
        os.ftruncate(fd, at)


def _judged(path: str, hashes: Mapping[str, str | None], kept: Any) -> tuple[set[str], int]:
    """
    The paths of ``hashes`` recorded with their content now, and how many lines are dropped
    (no record, a stale or a repeated one); each kept line written to ``kept`` if given.
    """
    done: set[str] = set()
    seen: set[str] = set()  # every path recorded: a repeated line is dropped
    dropped = 0
    with open(path, "rb") as file:
        for raw in file:
            record = _parsed(raw)
            stale = (
                record is not None
                and record["path"] in hashes
                and (hashes[record["path"]] != record.get("sha256"))
            )
            if record is None or stale or record["path"] in seen:
                dropped += 1
                continue
            seen.add(record["path"])
            if record["path"] in hashes:
                done.add(record["path"])
            if kept is not None:
                kept.write(raw)
    return done, dropped
