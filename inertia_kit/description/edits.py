"""
Text edits on the original bytes of a file, and atomic writes: every byte outside an edited span
stays as it was (comments, attribute order, quoting, indentation, encoding, line endings).
"""

from __future__ import annotations

import codecs
import contextlib
import itertools
import os
import re
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import Any

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

    @cached_property
    def line_starts(self) -> list[int]:
        """Where each line begins, lines counted as XML counts them (:mod:`.lines`)."""
        from inertia_kit.description.lines import line_starts

        return line_starts(self.text)

    def byte_offset(self, offset: int) -> int:
        """The offset in the file's bytes of the character offset ``offset`` (after the mark):
        the bytes of the lines before counted once per text, then of the rest of its line."""
        import bisect

        line = bisect.bisect_right(self.line_starts, offset) - 1
        start = self.line_starts[line]
        return self._line_bytes[line] + len(self.text[start:offset].encode(self.encoding))

    @cached_property
    def _line_bytes(self) -> list[int]:
        """The byte offset where each line begins (the mark included)."""
        starts, text, found = self.line_starts, self.text, [len(self.bom)]
        for begin, end in itertools.pairwise(starts):
            found.append(found[-1] + len(text[begin:end].encode(self.encoding)))
        return found


def read_source(path: str | Path) -> SourceText:
    """Read a text file keeping its encoding and byte-order mark, for editing."""
    from inertia_kit.description.safexml import read_bounded

    try:
        original = read_bounded(path)
    except InputError:
        real_target(path)  # a link that leads nowhere: say so
        raise
    return decode_source(original, path)


def source_encoding(original: bytes) -> tuple[bytes, str]:
    """
    ``(byte-order mark, encoding)`` of a file's bytes as the parser reads them: its mark, else
    the encoding it declares (but for one libxml2 does not know, on bytes that are UTF-8: the
    parser read them as UTF-8), else UTF-16 by its first bytes, else UTF-8. Edits and the
    columns of elements are in the characters of this decoding.
    """
    bom = b""
    encoding = "utf-8"
    for mark, name in (  # UTF-32's marks first: UTF-32-LE's begins with UTF-16-LE's
        (codecs.BOM_UTF32_LE, "utf-32-le"),
        (codecs.BOM_UTF32_BE, "utf-32-be"),
        (codecs.BOM_UTF8, "utf-8"),
        (codecs.BOM_UTF16_LE, "utf-16-le"),
        (codecs.BOM_UTF16_BE, "utf-16-be"),
    ):
        if original.startswith(mark):
            return mark, name
    declared = _DECLARED_ENCODING.match(original)
    if declared:
        from inertia_kit.description.xmlparse import reads_declared

        encoding = declared.group(1).decode("ascii").lower()
        if not reads_declared(encoding) and _is_utf8(original):
            # the parser read it as UTF-8, and told positions in those characters
            encoding = "utf-8"
    elif original.startswith((b"<\x00\x00\x00", b"\x00\x00\x00<")):  # UTF-32, no mark (F.1)
        # before UTF-16's test, which its first two bytes also pass (fuzz s1, input 15055:
        # read as UTF-16, the columns of every element were off and the fix hit no tag)
        encoding = "utf-32-le" if original[0] else "utf-32-be"
    elif original.startswith((b"<\x00", b"\x00<")):  # UTF-16 without a mark (XML 1.0, F.1)
        encoding = "utf-16-le" if original[0] else "utf-16-be"
    return bom, encoding


def decode_source(original: bytes, path: str | Path) -> SourceText:
    """``original``, the bytes of the file ``path``, as text to edit (see :func:`read_source`)."""
    bom, encoding = source_encoding(original)
    try:
        text = original[len(bom) :].decode(encoding)
    except (LookupError, UnicodeDecodeError) as error:
        raise InputError(f"cannot decode as {encoding}: {error}", path) from None
    if bom + text.encode(encoding) != original:
        raise InputError(f"does not round-trip through {encoding}; refusing to edit", path)
    return SourceText(str(path), original, text, encoding, bom)


def _is_utf8(data: bytes) -> bool:
    try:
        data.decode("utf-8")
    except UnicodeDecodeError:
        return False
    return True


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


def unified_diff(changes: Iterable[tuple[str, str, str]]) -> str:
    """
    A unified diff of ``(name, text before, text after)`` changes, file after file: ``a/NAME``
    and ``b/NAME`` for a relative name (as git shows it), the name itself for an absolute one.
    """
    from inertia_kit.description import line_diff
    from inertia_kit.printable import printable

    parts = []
    for name, before, after in changes:
        name = printable(name)  # a header is one line, whatever the file is called
        shown = (name, name) if Path(name).is_absolute() else (f"a/{name}", f"b/{name}")
        lines = line_diff.unified_diff(
            before.splitlines(keepends=True), after.splitlines(keepends=True), *shown
        )
        parts.append("".join(lines))
    return "".join(parts)


#: what a writer says when the file is no longer the text its edits were computed on
CHANGED = "the file changed while it was being processed; nothing was written"


class ChangedWhileEditing(InputError):
    """The file on disk is no longer the one the edits were computed from."""


def real_target(path: str | Path) -> Path:
    """
    The file a write to ``path`` must replace: ``path`` itself, or for a symbolic link the file
    at the end of its chain of links, so the link stays a link (``os.replace`` on the link's
    own name would turn it into a regular file).

    Raises ``InputError`` for a link that leads nowhere (dangling, or a loop of links).
    """
    target = Path(path)
    if not os.path.islink(target):
        return target
    try:
        return target.resolve(strict=True)
    except FileNotFoundError:
        missing = os.path.realpath(target)
        raise InputError(
            f"is a symbolic link to {os.readlink(target)} ({missing}), which does not exist: "
            "point the link at the file, or give the file itself",
            path,
        ) from None
    except (OSError, RuntimeError) as error:  # a loop: RuntimeError before Python 3.13
        reason = getattr(error, "strerror", None) or "a loop of links"
        raise InputError(
            f"is a symbolic link that cannot be followed ({reason}): point it at the file, "
            "or give the file itself",
            path,
        ) from None


def write_atomic(
    path: str | Path,
    data: bytes | Iterable[bytes],
    *,
    expected: bytes | None = None,
    create: bool = False,
    follow_symlinks: bool = True,
) -> bool:
    """
    Replace ``path``'s content with ``data`` atomically (temporary file in the same folder,
    ``fsync``, ``os.replace``), keeping its permission bits (and its owner and group where
    the system lets us). Writes nothing when the bytes are already ``data``. ``data`` may
    come in pieces (an iterable of bytes, written as they come, without all of it in memory:
    a long report); then the file is always written.

    A symbolic link is followed (through a chain of links) and the file it points to is
    replaced, with the temporary file beside that file; the link itself is left as it is. A
    link that leads nowhere is an ``InputError``. Without ``follow_symlinks`` the name itself is
    replaced: a link there becomes a file, and what it pointed to is not touched. Temporary
    files of an earlier write that was killed (:func:`remove_stale_temporaries`) are removed
    from the folder first.

    ``expected`` is the content the edits were computed from: if the file no longer holds it
    (someone changed it meanwhile), nothing is written and ``ChangedWhileEditing`` is raised.
    With ``create``, a missing file is created (permissions from the umask), as for ``-o OUT``.

    An output (``create``) that is a device or a named pipe (``-o /dev/null``, a FIFO a
    pipeline reads) is written into, never renamed over: as root, a rename would replace the
    system's ``/dev/null`` with a regular file. A file to edit must be a regular one.

    Returns whether the file was written.
    """
    target = real_target(path) if follow_symlinks else Path(path)
    special = _special(target, follow_symlinks)
    if special is not None:
        if not create or expected is not None:
            raise InputError(f"is {special}, not a file to edit; nothing was written", path)
        return _write_through(target, path, data)
    with _commit_lock([target.parent] if expected is not None else []):
        return _write_set([(target, path, data, expected)], create)


def _special(target: Path, follow_symlinks: bool = True) -> str | None:
    """What ``target`` is when it exists and is neither a regular file nor a folder (a
    device, a named pipe, a socket), else ``None``; a link itself is none of these (without
    ``follow_symlinks`` it is replaced, as a file is)."""
    import stat

    try:
        mode = os.stat(target, follow_symlinks=follow_symlinks).st_mode
    except (OSError, ValueError):
        return None
    if stat.S_ISREG(mode) or stat.S_ISDIR(mode) or stat.S_ISLNK(mode):
        return None
    if stat.S_ISFIFO(mode):
        return "a named pipe"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "a device"


def _write_through(target: Path, shown: str | Path, data: bytes | Iterable[bytes]) -> bool:
    """``data`` written into the device or named pipe ``target`` (a pipe waits for its reader,
    as a shell's ``> fifo`` does)."""
    try:
        with open(target, "wb") as stream:
            for piece in [data] if isinstance(data, bytes) else data:
                stream.write(piece)
    except OSError as error:  # /dev/full, a socket, a pipe whose reader left
        raise InputError(f"cannot write: {error.strerror or error}", shown) from None
    return True


def write_all_atomic(
    writes: Sequence[tuple[str | Path, bytes, bytes]],
    unchanged: Mapping[str, str | None] | None = None,
) -> bool:
    """
    ``(path, data, expected)`` for several files, each written as :func:`write_atomic` does,
    as one change: every file is checked first (its links lead to a file, still ``expected``,
    writable), so one that changed or is read-only stops the whole set before any file is
    written; then every new file is written beside its target, checked once more against
    ``expected`` and only then all renamed into place. Returns whether any was written.

    ``unchanged``: the other files the edits were computed from, real path -> digest of the
    bytes read (:data:`~inertia_kit.description.reads.Reads`), checked at that last look too:
    edits to ``robot.xacro`` computed while ``base.xacro`` held other text are stale when
    another writer has saved ``base.xacro`` since (fuzz s1, input 17823: ``--fix`` on the
    included files and ``--add-noqa`` on the main one at once kept comments for findings the
    fix had removed).

    Our writers (``--fix``, ``inertia-fill``, ``--add-noqa``, in any process) check and
    replace one at a time in a folder (:func:`_commit_lock`), so two of them never both see
    the text they expect and then both replace it: the second finds the first one's bytes
    and writes nothing.
    """
    planned = [(real_target(path), path, data, expected) for path, data, expected in writes]
    for target, path, *_ in planned:
        special = _special(target)
        if special is not None:
            raise InputError(f"is {special}, not a file to edit; nothing was written", path)
    written = {str(target) for target, *_ in planned}
    others = {n: found for n, found in (unchanged or {}).items() if n not in written}
    folders = [target.parent for target, *_ in planned] + [Path(n).parent for n in others]
    with _commit_lock(folders):
        return _write_set(planned, create=False, unchanged=others)


def _write_set(
    planned: Sequence[tuple[Path, str | Path, bytes, bytes | None]],
    create: bool,
    unchanged: Mapping[str, str | None] | None = None,
) -> bool:
    """Check, write beside, check again, rename: ``(target, name told, data, expected)``;
    the files of ``unchanged`` must still hold the bytes of their digests."""
    states = []
    for target, path, data, expected in planned:
        # pieces are not compared: the file's bytes need not be read
        current, mode = _state(target, create, path, isinstance(data, bytes) or bool(expected))
        if _may_write(target, current, mode, data, expected, path):
            states.append((target, path, data, expected, current, mode))
    prepared: list[tuple[Path, str | Path, bytes | None, str, Any]] = []
    try:
        for target, path, data, expected, current, mode in states:
            prepared.append((target, path, expected, *_prepare(target, path, data, current, mode)))
        # a last look: a change between our read and now must not be overwritten
        for target, path, expected, _, _ in prepared:
            if expected is not None and target.read_bytes() != expected:
                raise ChangedWhileEditing(CHANGED, path)
        if prepared:
            _check_unchanged(unchanged or {})
        for target, path, _, temporary, stream in prepared:
            try:
                if os.name == "nt":  # pragma: no cover - Windows renames no open file
                    stream.close()
                os.replace(temporary, target)
            except OSError as error:  # a full disk, a lost network file system, ...
                raise InputError(
                    f"cannot write: {error.strerror or error}; the file was left as it was", path
                ) from None
    except BaseException:
        for _, _, _, temporary, _ in prepared:
            with contextlib.suppress(OSError):
                os.unlink(temporary)
        raise
    finally:
        for *_, stream in prepared:
            stream.close()
    return bool(prepared)


def _check_unchanged(unchanged: Mapping[str, str | None]) -> None:
    """``ChangedWhileEditing`` when a file read (not written) holds other bytes than read."""
    from inertia_kit.description.reads import digest

    for name, found in unchanged.items():
        if found is None:
            continue  # read twice with two texts: the load already told (or refused) it
        try:
            now = digest(Path(name).read_bytes())
        except OSError:
            now = None
        if now != found:
            raise ChangedWhileEditing(CHANGED, name)


def _prepare(
    target: Path, path: str | Path, data: bytes | Iterable[bytes], current: bytes | None, mode: int
):
    """``data`` in a new temporary file beside ``target``, synced, with ``target``'s mode and
    owner: its name and the open stream (kept open, and locked, until the rename)."""
    remove_stale_temporaries(target.parent)
    try:
        handle, temporary = _create_temporary(target)
    except OSError as error:
        raise InputError(
            f"cannot write: no temporary file in {target.parent} ({error.strerror or error}); "
            "nothing was written",
            path,
        ) from None
    # the descriptor stays open, and locked, until the file has its name: a run that finds
    # our temporary file meanwhile sees that it is in use (remove_stale_temporaries)
    stream = os.fdopen(handle, "wb")
    try:
        for piece in [data] if isinstance(data, bytes) else data:
            stream.write(piece)
        stream.flush()
        os.fsync(stream.fileno())
        if current is not None:
            _keep_owner(stream.fileno(), target)
        _set_mode(stream.fileno(), temporary, mode)
    except BaseException as error:
        stream.close()
        with contextlib.suppress(OSError):
            os.unlink(temporary)
        if isinstance(error, OSError):  # a full disk, a lost network file system, ...
            raise InputError(
                f"cannot write: {error.strerror or error}; the file was left as it was", path
            ) from None
        raise
    return temporary, stream


#: How long a writer waits for another one's check-and-replace in a folder (which takes
#: milliseconds) before it goes on without the lock (its content check still holds).
COMMIT_WAIT_SECONDS = 10.0


@contextlib.contextmanager
def _commit_lock(folders: Iterable[Path]) -> Iterator[None]:
    """
    An exclusive ``flock`` on each folder (in one order: no two writers wait for each other)
    while a set of files is checked and replaced. Where a folder cannot be opened or locked
    (another system, a file system without locks) the write goes on without it.
    """
    import time

    handles = []
    try:
        for folder in sorted({os.path.realpath(folder) for folder in folders}):
            try:
                handle = os.open(folder, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
            except OSError:
                continue
            handles.append(handle)
            deadline = time.monotonic() + COMMIT_WAIT_SECONDS
            while True:
                try:
                    _lock(handle, blocking=False)
                    break
                except BlockingIOError:
                    if time.monotonic() > deadline:
                        break
                    time.sleep(0.002)
                except OSError:  # no locks here
                    break
        yield
    finally:
        for handle in handles:
            os.close(handle)


# --- temporary files ---------------------------------------------------------------------------

#: ``.robot.urdf.inertia-kit-0123456789ab.tmp``: ours, whatever the name of the file it was for
_TEMPORARY = re.compile(r"\..+\.inertia-kit-[0-9a-f]{12}\.tmp")
#: A temporary file younger than this is left alone, lock or no lock: a write takes
#: milliseconds, so a younger one is most likely being written (or was killed just now).
MIN_STALE_SECONDS = 60.0
#: Where a lock cannot tell (no ``flock``; another user's file), only a file this old is stale.
UNPROVEN_STALE_SECONDS = 3600.0


def _create_temporary(target: Path) -> tuple[int, str]:
    """A new temporary file beside ``target``, created exclusively (0600) and locked."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0)
    for _ in range(100):
        name = target.parent / f".{target.name}.inertia-kit-{os.urandom(6).hex()}.tmp"
        try:
            handle = os.open(name, flags, 0o600)
        except FileExistsError:  # pragma: no cover - 48 random bits
            continue
        _lock(handle, blocking=True)
        try:
            ours = os.path.samestat(os.fstat(handle), os.stat(name))
        except OSError:
            ours = False
        if ours:
            return handle, str(name)
        # removed before we held its lock (a cleaner misled by a skewed clock): another name
        os.close(handle)
    raise FileExistsError(f"no free temporary name beside {target}")  # pragma: no cover


def remove_stale_temporaries(folder: str | Path) -> list[Path]:
    """
    Remove the temporary files our writes left in ``folder`` when they were killed (a SIGKILL
    or a power cut between creating the file and renaming it): only files named as ours
    (``.NAME.inertia-kit-<12 hex digits>.tmp``), regular files, at least
    :data:`MIN_STALE_SECONDS` old and provably not in use (nobody holds their lock), or, where
    the lock cannot tell, :data:`UNPROVEN_STALE_SECONDS` old. A live write's file (another run,
    another thread) is never removed. Returns the files removed; errors only mean a file stays.
    """
    import stat
    import time

    removed: list[Path] = []
    now = time.time()
    try:
        with os.scandir(folder) as scan:
            candidates = [entry for entry in scan if _TEMPORARY.fullmatch(entry.name)]
    except OSError:
        return removed
    for entry in candidates:
        try:
            status = entry.stat(follow_symlinks=False)
        except OSError:
            continue
        age = now - status.st_mtime
        if not stat.S_ISREG(status.st_mode) or age < MIN_STALE_SECONDS:
            continue
        if _remove_if_unlocked(entry.path, unproven=age >= UNPROVEN_STALE_SECONDS):
            removed.append(Path(entry.path))
    return removed


def _remove_if_unlocked(path: str, *, unproven: bool) -> bool:
    """Remove ``path`` while holding its lock; without a lock to ask, only when ``unproven``."""
    try:
        handle = os.open(path, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0))
    except OSError:  # not ours to read (another user): only the age can tell
        return unproven and _unlink(path)
    try:
        try:
            _lock(handle, blocking=False)
        except BlockingIOError:
            return False  # a live writer holds it
        except OSError:  # no locks on this file system
            return unproven and _unlink(path)
        return _unlink(path)
    finally:
        os.close(handle)


def _unlink(path: str) -> bool:
    try:
        os.unlink(path)
    except OSError:
        return False
    return True


def _lock(handle: int, *, blocking: bool) -> None:
    """An exclusive ``flock`` (per open file, so it also tells apart two threads of a
    process); released when the process ends, however it ends. No-op without ``fcntl``."""
    try:
        import fcntl
    except ImportError:  # pragma: no cover - Windows: only the age tells
        if not blocking:
            raise OSError("no flock") from None
        return
    if blocking:
        with contextlib.suppress(OSError):  # a file system without locks: the age tells
            fcntl.flock(handle, fcntl.LOCK_EX)
    else:
        fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)


def _keep_owner(handle: int, target: Path) -> None:
    """Give the new file the target's owner and group, where we may (root; a group we are in)."""
    if not hasattr(os, "fchown"):  # pragma: no cover - Windows
        return
    status = target.stat()
    mine = os.fstat(handle)
    if (status.st_uid, status.st_gid) != (mine.st_uid, mine.st_gid):
        with contextlib.suppress(OSError):
            os.fchown(handle, status.st_uid, status.st_gid)
        if os.fstat(handle).st_gid != status.st_gid:
            with contextlib.suppress(OSError):
                os.fchown(handle, -1, status.st_gid)


def _set_mode(handle: int, name: str, mode: int) -> None:
    if hasattr(os, "fchmod"):
        os.fchmod(handle, mode)
    else:  # pragma: no cover - Windows
        os.chmod(name, mode)


def _state(
    target: Path, create: bool, shown: str | Path, read: bool = True
) -> tuple[bytes | None, int]:
    """The file's bytes (``None``: to be created; empty when not ``read``) and the permission
    bits to write with."""
    if os.path.isdir(target):
        raise InputError("is a folder, not a file; nothing was written", shown)
    if create and not os.path.exists(target):
        if not os.path.isdir(target.parent):
            raise InputError(f"no folder {str(target.parent)!r} to write into", shown)
        umask = os.umask(0)
        os.umask(umask)
        return None, 0o666 & ~umask
    try:
        current = target.read_bytes() if read else b""
        return current, target.stat().st_mode & 0o7777
    except OSError as error:
        raise InputError(f"cannot read: {error.strerror or error}", shown) from None


def _may_write(
    target: Path,
    current: bytes | None,
    mode: int,
    data: bytes | Iterable[bytes],
    expected: bytes | None,
    shown: str | Path,
) -> bool:
    """Whether ``data`` needs writing; ``InputError`` (naming ``shown``) when it must not be."""
    if expected is not None and current != expected:
        raise ChangedWhileEditing(CHANGED, shown)
    if current == data:
        return False
    # the permission bits, not os.access: a read-only file says "don't touch", even to root
    if current is not None and (not mode & 0o222 or not os.access(target, os.W_OK)):
        raise InputError("the file is read-only; nothing was written", shown)
    return True
