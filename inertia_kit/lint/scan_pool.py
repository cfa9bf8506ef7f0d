"""
Worker processes for ``inertia-kit scan`` that hold each item to a time and a memory limit:
an item over a limit ends as ``timeout`` or ``memory``, its worker is replaced, the run goes on.

:mod:`.parallel`'s pool cannot do this: ``concurrent.futures`` cannot end one worker without
breaking the whole pool, so a runaway item would cost every item in flight. Here each worker is
one process with a pipe of its own, so the parent can kill exactly the one that overran.

A worker starts its own process group (the xacro sandbox's child joins it), so that killing the
group ends the expansion too; it ignores Ctrl-C (the parent alone decides) and SIGTTOU (a
background group may still write a warning). Before each item it lowers ``RLIMIT_AS`` to its
address space plus the memory limit (an allocation past it raises ``MemoryError`` where it
happens) and ``RLIMIT_CPU`` to its CPU time plus the time limit and a grace (a backstop should
the parent die without killing it); the parent kills the group at the wall-clock deadline.
"""

from __future__ import annotations

import contextlib
import errno
import math
import os
import resource
import signal
import time
from collections import deque
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any

from inertia_kit.lint.parallel import settle_start_up

#: seconds past the time limit the CPU backstop allows (the parent's deadline comes first)
GRACE = 5.0
#: what the forkserver imports once, before forking workers: an import inside an item would
#: count against its memory limit (a tight limit fails to map lxml's library)
PRELOAD = [
    "inertia_kit.lint.scan",
    "inertia_kit.lint.runner",
    "inertia_kit.lint.output.common",
    "inertia_kit.analysis.declared",
    "inertia_kit.description.loader",
    "lxml.etree",
]


#: the longest one wait for the workers, s
_LONGEST_WAIT = 86_400.0


@dataclass(frozen=True)
class Limits:
    """Per item: ``timeout`` seconds of wall-clock time, ``memory_mb`` MB of new address
    space (0: none)."""

    timeout: float = 60.0
    memory_mb: int = 2048


@dataclass
class Outcome:
    """
    How one item ended: ``status`` ``done`` (``value`` is what the work returned), ``timeout``,
    ``memory`` or ``crashed`` (``message`` says how); ``wall`` and ``cpu`` seconds and
    ``peak_mb`` of the worker (``None`` where the worker could not tell).
    """

    status: str
    value: Any = None
    message: str = ""
    wall: float = 0.0
    cpu: float | None = None
    peak_mb: float | None = None


def run_limited(
    work: Callable[[Any], Any], items: Sequence[Any], jobs: int, limits: Limits
) -> Iterator[tuple[int, Outcome]]:
    """
    ``(index, outcome)`` of ``work(item)`` for every item, in ``jobs`` worker processes, in
    the order they finish. ``work`` is a module-level function, items and results picklable.
    Closing the iteration (or Ctrl-C in it) kills the workers.
    """
    if not items:
        return
    from inertia_kit.lint.parallel import worker_context

    context = worker_context(PRELOAD)
    pending = deque(range(len(items)))
    workers: list[_Worker] = []
    try:
        for _ in range(max(1, min(jobs, len(items)))):
            workers.append(_Worker.start(context, work, limits))
        while pending or any(w.index is not None for w in workers):
            for slot, worker in enumerate(workers):
                if worker.index is None and pending:
                    if not worker.alive():
                        worker = workers[slot] = _Worker.start(context, work, limits)
                    worker.give(pending.popleft(), items)
            yield from _collect(workers, context, work, limits)
    finally:
        for worker in workers:
            worker.kill()


def _collect(
    workers: list[_Worker], context: Any, work: Callable[[Any], Any], limits: Limits
) -> Iterator[tuple[int, Outcome]]:
    """Wait until a busy worker answers, dies or overruns; the outcomes of those."""
    from multiprocessing.connection import wait

    busy = [w for w in workers if w.index is not None]
    now = time.monotonic()
    deadline = min(w.deadline for w in busy)
    # no deadline (--timeout 0) is no timeout; a far one (--timeout 1e300) is waited for a day
    # at a time: the selector turns its timeout into milliseconds of a C int
    left = None if deadline == math.inf else min(max(0.0, deadline - now), _LONGEST_WAIT)
    ready = set(wait([h for w in busy for h in w.handles()], left))
    now = time.monotonic()
    for slot, worker in enumerate(workers):
        if worker.index is None:
            continue
        if worker.connection in ready or worker.process.sentinel in ready:
            index, outcome = worker.answer()
        elif now >= worker.deadline:
            index, outcome = worker.overran()
        else:
            continue
        if not worker.alive():
            workers[slot] = _Worker.start(context, work, limits)
        yield index, outcome


@dataclass
class _Worker:
    """One worker process, the item it is on and since when."""

    process: Any
    connection: Any
    limits: Limits
    index: int | None = None
    started: float = 0.0
    deadline: float = math.inf
    _killed: bool = field(default=False)

    @classmethod
    def start(cls, context: Any, work: Callable[[Any], Any], limits: Limits) -> _Worker:
        ours, theirs = context.Pipe()
        process = context.Process(target=_serve, args=(theirs, work, limits), daemon=True)
        process.start()
        theirs.close()
        return cls(process, ours, limits)

    def handles(self) -> list[Any]:
        return [self.connection, self.process.sentinel]

    def alive(self) -> bool:
        return not self._killed and self.process.is_alive()

    def give(self, index: int, items: Sequence[Any]) -> None:
        self.index, self.started = index, time.monotonic()
        self.deadline = self.started + self.limits.timeout if self.limits.timeout else math.inf
        self.connection.send(items[index])

    def answer(self) -> tuple[int, Outcome]:
        """The item's outcome once its worker answered or died."""
        index, wall = self._done()
        try:
            if self.connection.poll():
                return index, self.connection.recv()
        except (EOFError, OSError):
            pass
        self.process.join(5)
        self.kill()
        code = self.process.exitcode
        if code == -signal.SIGXCPU:  # the CPU backstop: the item ran past its time
            return index, Outcome("timeout", message=self._over_time(), wall=wall)
        how = f"signal {-code}" if code is not None and code < 0 else f"exit code {code}"
        return index, Outcome("crashed", message=f"its worker process died ({how})", wall=wall)

    def overran(self) -> tuple[int, Outcome]:
        index, wall = self._done()
        self.kill()
        return index, Outcome("timeout", message=self._over_time(), wall=wall)

    def _over_time(self) -> str:
        return f"stopped after {self.limits.timeout:g} s, the time limit (--timeout)"

    def _done(self) -> tuple[int, float]:
        index, wall = self.index, time.monotonic() - self.started
        self.index, self.deadline = None, math.inf
        assert index is not None
        return index, wall

    def kill(self) -> None:
        """End the worker and its process group (a xacro expansion's child with it)."""
        if self._killed:
            return
        self._killed = True
        pid = self.process.pid
        if pid is not None:
            with contextlib.suppress(OSError):
                os.killpg(pid, signal.SIGKILL)
            with contextlib.suppress(OSError):
                os.kill(pid, signal.SIGKILL)
        self.process.join(5)
        self.connection.close()


# --- in the worker ------------------------------------------------------------------------


def _serve(connection: Any, work: Callable[[Any], Any], limits: Limits) -> None:
    """A worker's loop: an item in, its :class:`Outcome` out, until the pipe closes."""
    with contextlib.suppress(OSError):
        os.setpgid(0, 0)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTTOU, signal.SIG_IGN)
    _die_with_parent()
    while True:
        try:
            item = connection.recv()
        except (EOFError, OSError):
            return
        outcome = _measured(work, item, limits)
        settle_start_up()
        try:
            connection.send(outcome)
        except (OSError, ValueError):
            return


def _measured(work: Callable[[Any], Any], item: Any, limits: Limits) -> Outcome:
    """``work(item)`` under the limits, with its wall and CPU time and peak memory."""
    _limit(limits)
    _reset_peak()
    children_before = _children_peak_mb()
    cpu_before, started = _cpu(), time.monotonic()
    try:
        outcome = Outcome("done", work(item))
    except Exception as error:
        outcome = _failed(error, limits)
    finally:
        _unlimit()
    outcome.wall, outcome.cpu = time.monotonic() - started, _cpu() - cpu_before
    peak, children = _peak_mb(), _children_peak_mb()
    # the children's peak is a maximum over every child so far: only a rise is this item's
    if peak is not None and children is not None and children > (children_before or 0):
        peak = max(peak, children)
    outcome.peak_mb = peak
    return outcome


def _failed(error: Exception, limits: Limits) -> Outcome:
    """An item that raised: over its memory limit (an allocation or a mapping refused), or a
    bug in the linter (told for this item; the run goes on)."""
    if isinstance(error, MemoryError) or getattr(error, "errno", None) == errno.ENOMEM:
        return Outcome("memory", message=_over_memory(limits))
    return Outcome("crashed", message=f"{type(error).__name__}: {error}")


def _over_memory(limits: Limits) -> str:
    return f"needed more than {limits.memory_mb} MB, the memory limit (--max-memory)"


def _limit(limits: Limits) -> None:
    if limits.memory_mb:
        size = _address_space()
        if size is not None:
            _lower(resource.RLIMIT_AS, size + limits.memory_mb * (1 << 20))
    if limits.timeout:
        _lower(resource.RLIMIT_CPU, math.ceil(_cpu() + limits.timeout + GRACE))


#: the worker's own limits, before any item lowered them
_ORIGINAL: dict[int, tuple[int, int]] = {}


def _unlimit() -> None:
    # back to the worker's own limits: the worker itself (pickling a result) is not the item
    for kind, limits in _ORIGINAL.items():
        with contextlib.suppress(ValueError, OSError, OverflowError):
            resource.setrlimit(kind, limits)


def _lower(kind: int, value: int) -> None:
    soft, hard = _ORIGINAL.setdefault(kind, resource.getrlimit(kind))
    if soft != resource.RLIM_INFINITY:
        value = min(value, soft)
    # a limit past what the platform holds (--max-memory 10**30, --timeout 1e300): none then,
    # and the wall-clock deadline still holds
    with contextlib.suppress(ValueError, OSError, OverflowError):
        resource.setrlimit(kind, (value, hard))


def _cpu() -> float:
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)  # the xacro sandbox's children
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def _address_space() -> int | None:
    """This process's address space in bytes (Linux's /proc), else ``None``."""
    try:
        with open("/proc/self/statm") as file:
            return int(file.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        return None


def _reset_peak() -> None:
    # Linux ≥ 4.0: "5" resets VmHWM, so the peak read after the item is the item's own
    with contextlib.suppress(OSError), open("/proc/self/clear_refs", "w") as file:
        file.write("5")


def _peak_mb() -> float | None:
    """The peak resident memory since :func:`_reset_peak` (VmHWM), else the process's."""
    try:
        with open("/proc/self/status") as file:
            for line in file:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024
    except (OSError, ValueError, IndexError):
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def _children_peak_mb() -> float | None:
    return resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024 or None


def _die_with_parent() -> None:
    """Linux: SIGKILL this worker when its parent dies (a killed scan leaves none behind)."""
    with contextlib.suppress(Exception):
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
