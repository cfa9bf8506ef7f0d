"""
One xacro expansion in a forked child process under resource limits, its result back through a
pipe: the only robust bound on work that runs in C (``10**10**10`` is one call to CPython's
integer power, which no signal, no trace hook and no in-process timer interrupts).

The child inherits everything loaded (:func:`preload` imports what an expansion needs first),
so a fork costs about 8-10 ms of CPU per expansion (README: "Bounded xacro expansion"). It
sets ``RLIMIT_AS`` to its current address space plus the memory limit (an allocation past it
raises ``MemoryError`` where it happens) and ``RLIMIT_CPU`` to the time limit plus a grace (a
backstop should the parent die), never above the limits it inherited (a ``ulimit``, or the
per-asset limits of ``inertia-kit scan``: :func:`memory_room_mb` says how much an inherited
one leaves), ignores ``SIGINT`` (the parent, which Ctrl-C also reaches,
kills it), runs the work and writes a pickled outcome to the pipe. The parent reads it until
the deadline, then kills the child. Where ``os.fork`` is missing or fails (:class:`CannotFork`),
or both the time and memory limits are off, the caller runs the work in-process (only the
limits checked inside the expansion then apply).

The memory limit needs ``/proc/self/statm`` (Linux) to know the address space the child starts
with; elsewhere it is not set.
"""

from __future__ import annotations

import contextlib
import math
import os
import pickle
import struct
import time
import warnings
from collections.abc import Callable
from contextlib import AbstractContextManager
from dataclasses import dataclass
from typing import Any

from inertia_kit.description.model import Source
from inertia_kit.errors import InputError

#: Seconds the parent waits past the time limit before it kills the child: the child's own
#: check (in the expansion) reports first, with the line it was on, if it can.
GRACE = 1.0

_HEADER = struct.Struct("<Q")
#: poll's longest wait, ms (a C int): a longer time limit (``timeout = 1e9``) is waited in steps
_LONGEST_POLL = 1 << 30


@dataclass(frozen=True)
class Expansion:
    """What an expansion hands over (from the child): plain, picklable values."""

    path: str
    files: tuple[str, ...]
    fragment: bool
    warnings: tuple[str, ...]
    text: str | None = None  # the expanded robot, serialised (None: a fragment)
    sources: list[Source] | None = None  # the stamp of each element of ``text``
    resolver_state: dict[str, Any] | None = None  # the child's package resolver's attributes
    # the values the environment gave ($(env), $(optenv), YAML): description.redaction
    environment_values: tuple[str, ...] = ()
    # real path -> digest of the bytes read, of every file read (description.reads)
    reads: dict[str, str | None] | None = None


def state_of(resolver: Any) -> dict[str, Any] | None:
    """``resolver``'s attributes (its caches), if they can be handed to the parent process."""
    state = dict(vars(resolver))
    try:
        pickle.dumps(state, protocol=pickle.HIGHEST_PROTOCOL)
    except Exception:  # an attribute that does not pickle: the parent looks up again
        return None
    return state


def preload() -> None:
    """What an expansion imports, imported once here rather than in every forked child."""
    import ast  # noqa: F401
    import resource  # noqa: F401
    import select  # noqa: F401
    import signal  # noqa: F401
    import xml.dom.expatbuilder  # noqa: F401

    from xacro import substitution_args  # noqa: F401


class CannotFork(Exception):
    """No pipe or no child process could be made (a process or file limit): run in-process."""


class TimedOut(Exception):
    """The child was still running at the deadline and was killed."""


class ChildDied(Exception):
    """The child ended without an outcome (killed by a signal, or out of memory in C)."""

    def __init__(self, status: int | None):
        self.status = status
        super().__init__(status)

    def reason(self) -> str:
        import signal

        if self.status is None:
            return "it ended without a result"
        if self.status < 0:
            try:
                name = signal.Signals(-self.status).name
            except ValueError:
                name = f"signal {-self.status}"
            return f"it was killed by {name}"
        return f"it exited with status {self.status} without a result"


def can_fork() -> bool:
    return hasattr(os, "fork")


def run(
    work: Callable[[], Any],
    *,
    timeout: float,
    memory_mb: int,
    start: float,
    lock: AbstractContextManager[Any] | None = None,
) -> Any:
    """
    ``work()`` in a forked child; its return value (picklable), or the ``InputError`` it
    raised. ``TimedOut`` past ``start + timeout + GRACE`` (``time.monotonic()``), ``ChildDied``
    when it ends without an outcome; ``RuntimeError`` (with the child's traceback) for any
    other exception in it; ``CannotFork`` when no pipe or process can be made. ``timeout`` 0
    and ``memory_mb`` 0: no limit. ``lock`` is held while forking (no other thread is then
    half-way through an in-process expansion).
    """
    import select

    try:
        read_end, write_end = os.pipe()
    except OSError as error:
        raise CannotFork(error) from None
    with warnings.catch_warnings():
        # Python 3.12+ warns when a process with threads forks: the child only runs the
        # expansion, which takes no lock another thread may hold (expansions hold _LOCK)
        warnings.simplefilter("ignore", DeprecationWarning)
        with lock if lock is not None else contextlib.nullcontext():
            try:
                pid = os.fork()
            except OSError as error:
                os.close(read_end)
                os.close(write_end)
                raise CannotFork(error) from None
    if pid == 0:  # pragma: no cover - the child; its outcome is what the tests check
        os.close(read_end)
        _child(work, write_end, timeout, memory_mb)
    os.close(write_end)
    deadline = start + timeout + GRACE if timeout else math.inf
    chunks: list[bytes] = []
    reaped = False
    try:
        poller = select.poll()
        poller.register(read_end, select.POLLIN | select.POLLHUP)
        while True:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimedOut()
            wait = None if left == math.inf else min(max(1, math.ceil(left * 1000)), _LONGEST_POLL)
            if poller.poll(wait):
                chunk = os.read(read_end, 1 << 20)
                if not chunk:
                    break
                chunks.append(chunk)
        status = _wait(pid)
        reaped = True
    finally:
        os.close(read_end)
        if not reaped:
            _kill(pid)
    return _outcome(b"".join(chunks), status)


def _outcome(data: bytes, status: int | None) -> Any:
    if len(data) < _HEADER.size or _HEADER.unpack_from(data)[0] != len(data) - _HEADER.size:
        raise ChildDied(status)
    kind, value = pickle.loads(data[_HEADER.size :])
    if kind == "ok":
        return value
    if kind == "input-error":
        error = InputError(*value[:4])
        error.environment_values = value[4]
        raise error
    if kind == "memory":
        raise MemoryError()
    raise RuntimeError(f"xacro expansion failed in its child process:\n{value}")


def _wait(pid: int) -> int | None:
    try:
        _, status = os.waitpid(pid, 0)
    except ChildProcessError:  # SIGCHLD ignored by whoever embeds us: the status is lost
        return None
    return os.waitstatus_to_exitcode(status)


def _kill(pid: int) -> None:
    import signal

    with contextlib.suppress(ProcessLookupError):
        os.kill(pid, signal.SIGKILL)
    _wait(pid)


def _child(
    work: Callable[[], Any], fd: int, timeout: float, memory_mb: int
) -> None:  # pragma: no cover - runs in the forked child
    try:
        import gc
        import signal

        # what the parent made is out of this child's collections (moving the collector's lists
        # touches no object): walking it would copy the parent's heap page by page
        gc.freeze()
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        _limit_resources(timeout, memory_mb)
        try:
            outcome: tuple[str, Any] = ("ok", work())
        except InputError as error:
            where = (error.message, error.path, error.line, error.column)
            outcome = ("input-error", (*where, error.environment_values))
        except MemoryError:
            outcome = ("memory", None)
        except BaseException:
            import traceback

            outcome = ("internal", traceback.format_exc())
        data = pickle.dumps(outcome, protocol=pickle.HIGHEST_PROTOCOL)
        view = memoryview(_HEADER.pack(len(data)) + data)
        while view:
            view = view[os.write(fd, view) :]
    finally:
        os._exit(0)


def _limit_resources(timeout: float, memory_mb: int) -> None:  # pragma: no cover - child
    import resource

    def lower(kind: int, soft: int) -> None:
        # never above what the process was given: a soft limit the child inherits (ulimit -v,
        # scan's --max-memory) holds for the expansion too
        current, hard = resource.getrlimit(kind)
        for bound in (current, hard):
            if bound != resource.RLIM_INFINITY:
                soft = min(soft, bound)
        # a platform that refuses, or a limit past what it holds: the parent's deadline holds
        with contextlib.suppress(ValueError, OSError, OverflowError):
            resource.setrlimit(kind, (soft, hard))

    if timeout:
        # CPU seconds count from the fork: a backstop should the parent die
        lower(resource.RLIMIT_CPU, math.ceil(timeout + GRACE) + 1)
    if memory_mb:
        size = _address_space()
        if size is not None:
            lower(resource.RLIMIT_AS, size + memory_mb * (1 << 20))


def memory_room_mb() -> float | None:
    """
    The MB this process may still map under its address-space limit (``RLIMIT_AS``, soft: a
    ``ulimit -v``, or scan's ``--max-memory``), which a forked child inherits: when it is less
    than the xacro memory limit, it is the limit an expansion meets. ``None``: no such limit,
    or not known here.
    """
    import resource

    soft, _ = resource.getrlimit(resource.RLIMIT_AS)
    if soft == resource.RLIM_INFINITY:  # the usual case: /proc is read only under a limit
        return None
    size = _address_space()
    return None if size is None else max(soft - size, 0) / (1 << 20)


def _address_space() -> int | None:
    """This process's virtual size in bytes (Linux), ``None`` where unknown."""
    try:
        with open("/proc/self/statm", "rb") as stream:
            pages = int(stream.read().split()[0])
    except (OSError, ValueError, IndexError):
        return None
    return pages * os.sysconf("SC_PAGE_SIZE")
