"""
Reading files of a tree we do not trust (a pull request's robots, meshes, ignore files,
configuration): only a regular file, and only up to a bound. A named pipe would block the read
for ever, ``/dev/zero`` never ends, and a 3 GB "mesh" is a MemoryError: each is refused before
it is read, with a message naming the file. Every layer reads through here (it stands outside
them, as :mod:`inertia_kit.errors` does).
"""

from __future__ import annotations

import errno
import io
import os
import stat
from pathlib import Path
from typing import BinaryIO

from inertia_kit.errors import InputError

_KINDS = (
    (stat.S_ISDIR, "a directory"),
    (stat.S_ISFIFO, "a named pipe"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISSOCK, "a socket"),
)


class Refused(InputError):
    """A file that exists but is not read: not a regular file, or larger than its bound."""


def size_text(count: int) -> str:
    """``50 MB``, ``4 kB`` or ``64 bytes``."""
    for unit, scale in (("MB", 1 << 20), ("kB", 1 << 10)):
        if count >= scale and count % scale == 0:
            return f"{count // scale} {unit}"
    return f"{count} bytes"


def read_regular(
    path: str | Path,
    limit: int,
    shown: str | Path | None = None,
    *,
    what: str = "file",
    follow_links: bool = True,
) -> bytes:
    """
    The bytes of the regular file ``path``, at most ``limit`` of them.

    Raises ``InputError`` naming ``shown`` (default: ``path``) for a file that is missing or
    unreadable, and :class:`Refused` (an ``InputError``) for one that is not a regular file (a
    folder, a named pipe, a device; checked before it is opened and again on what was opened)
    or larger than ``limit`` (``what`` says what the file was read as: "no robot description
    is that big"); with ``follow_links`` false, for a symbolic link too.
    """
    shown = path if shown is None else shown
    flags = os.O_RDONLY | getattr(os, "O_BINARY", 0) | getattr(os, "O_NONBLOCK", 0)
    if not follow_links:
        flags |= getattr(os, "O_NOFOLLOW", 0)
    try:
        if not follow_links and os.path.islink(path):
            raise Refused("is a symbolic link: not read", shown)
        check_regular_status(os.stat(path), limit, shown, what)  # a device is never opened
        handle = os.open(path, flags)
    except FileNotFoundError:
        raise InputError("no such file", shown) from None
    except OSError as error:
        raise InputError(_reason(error), shown) from None
    except ValueError as error:  # a NUL character in the path
        raise InputError(f"cannot read: {error}", repr(str(shown))) from None
    with os.fdopen(handle, "rb") as stream:
        check_regular_status(os.fstat(handle), limit, shown, what)  # swapped meanwhile
        try:
            data = read_at_most(stream, limit)
        except OSError as error:
            raise InputError(_reason(error), shown) from None
    if len(data) > limit:  # it grew since
        raise Refused(_too_big(limit, what), shown)
    return data


def open_regular(path: str | Path) -> BinaryIO:
    """
    ``path`` open for binary reading if it is a regular file, else ``OSError``: for readers
    that take anything odd for "nothing there" (a cache entry, an asset's hash, a file's first
    bytes). Opened without waiting (a named pipe opens at once and is then refused) and judged
    on what was opened, so a pipe or a link to one swapped in meanwhile never blocks a read.
    """
    flags = os.O_RDONLY | getattr(os, "O_BINARY", 0) | getattr(os, "O_NONBLOCK", 0)
    handle = os.open(path, flags)
    try:
        if not stat.S_ISREG(os.fstat(handle).st_mode):
            raise OSError(errno.EINVAL, "not a regular file", os.fspath(path))
        return os.fdopen(handle, "rb")
    except BaseException:
        os.close(handle)
        raise


def read_at_most(stream: BinaryIO, limit: int) -> bytes:
    """
    ``stream.read(limit + 1)``: at most one byte more than ``limit`` (which shows the file is
    larger), without that call's buffer of ``limit + 1`` bytes made before a byte is read
    (CPython's does: 256 MB for a 28 KB mesh, some 30 µs of mapping memory every read, and a
    ``MemoryError`` where memory is not overcommitted). A file is read to its size as
    measured, and on only if it holds more by then (it grew, or it reports no size).
    """
    try:
        size = os.fstat(stream.fileno()).st_size
    except (OSError, AttributeError, ValueError, io.UnsupportedOperation):
        size = limit
    data = stream.read(min(size, limit) + 1)
    if size < len(data) <= limit:
        data += stream.read(limit + 1 - len(data))
    return data


def check_regular(path: str | Path, limit: int, shown: str | Path | None = None, what="file"):
    """
    Refuse (``InputError``) what :func:`read_regular` refuses, for a file another library reads
    by its name (trimesh, xacro's YAML): missing, not a regular file, larger than ``limit``.
    """
    shown = path if shown is None else shown
    try:
        status = os.stat(path)
    except FileNotFoundError:
        raise InputError("no such file", shown) from None
    except OSError as error:
        raise InputError(_reason(error), shown) from None
    except ValueError as error:
        raise InputError(f"cannot read: {error}", repr(str(shown))) from None
    check_regular_status(status, limit, shown, what)


def check_regular_status(status: os.stat_result, limit: int, shown: str | Path, what: str):
    for test, kind in _KINDS:
        if test(status.st_mode):
            if kind == "a directory":
                raise Refused(f"is a directory, not a {what}", shown)
            raise Refused(f"is {kind}, not a regular file: not read", shown)
    if status.st_size > limit:
        raise Refused(_too_big(limit, what), shown)


def _too_big(limit: int, what: str) -> str:
    return f"is larger than {size_text(limit)}; no {what} is that big (nothing was read)"


def _reason(error: OSError) -> str:
    if error.errno == errno.ELOOP:
        return "is a symbolic link that cannot be followed (a loop of links): not read"
    if error.errno == errno.EISDIR:
        return "is a directory, not a file"
    return f"cannot read: {error.strerror or error}"
