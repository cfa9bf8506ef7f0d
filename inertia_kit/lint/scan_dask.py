"""
``inertia-kit scan --dask ADDRESS``: the assets of a scan linted on a Dask cluster
(``distributed``, the ``dask`` extra), the record still written by the client alone
(:func:`~inertia_kit.lint.scan.scanning`), so resume is the same.

:func:`run_on_dask` yields ``(index, outcome)`` as :func:`~.scan_pool.run_limited` does. A
Dask task takes a batch of assets (1 to :data:`MOST_PER_TASK`: a task costs the scheduler and
the client a few milliseconds, about what a small asset costs to lint); on the Dask worker it
hands them one at a time to a worker process of :mod:`.scan_pool` (one per Dask worker thread,
kept from task to task), each held to the same ``--timeout`` and ``--max-memory``: a runaway
asset costs that process, replaced for the next asset, and never the Dask worker. At most
:data:`IN_FLIGHT` tasks per Dask thread are submitted at a time, more as results arrive, so the
client's memory stays flat in the number of assets.

A Dask worker started by a nanny (``dask worker``, ``LocalCluster(processes=True)``) is a
daemonic ``multiprocessing`` process, which ``multiprocessing`` forbids to start children; the
first task lifts that flag in its Dask worker (the worker processes it starts die with the Dask
worker: each is killed when its parent, the forkserver, dies, and the forkserver ends with the
Dask worker). At the end of a scan the client asks every Dask worker to end its idle ones.

Only imported for ``--dask``: neither ``inertia-lint`` nor a local scan imports Dask, and this
module imports it only inside :func:`run_on_dask` (the workers import it to run a task; what the
task runs needs no Dask).
"""

from __future__ import annotations

import contextlib
import logging
import math
import os
import signal
import threading
import time
import uuid
from collections.abc import Callable, Iterator, Sequence
from typing import Any

from inertia_kit.errors import InputError
from inertia_kit.lint.parallel import worker_context
from inertia_kit.lint.scan_pool import PRELOAD, Limits, Outcome, _collect, _Worker

#: tasks in flight per Dask worker thread
IN_FLIGHT = 4
#: tasks per Dask worker thread a scan is cut into, when its assets allow
TASKS_PER_THREAD = 8
#: assets in one task at most
MOST_PER_TASK = 16
#: seconds to wait for the scheduler, and for a first worker to join it
CONNECT_TIMEOUT = 30.0
#: seconds between two counts of the cluster's threads (workers that join get work)
RECOUNT = 10.0
#: what to say when Dask is not installed
INSTALL = "--dask needs Dask's distributed: pip install 'inertia-kit[dask]'"


def require() -> None:
    """``InputError`` saying how to install Dask when ``distributed`` cannot be imported."""
    try:
        import distributed  # noqa: F401
    except ImportError:
        raise InputError(INSTALL) from None


def run_on_dask(
    address: str, work: Callable[[Any], Any], items: Sequence[Any], jobs: int, limits: Limits
) -> Iterator[tuple[int, Outcome]]:
    """
    ``(index, outcome)`` of ``work(item)`` for every item, as :func:`~.scan_pool.run_limited`
    gives them, on the Dask scheduler at ``address`` (``local``: a ``LocalCluster`` of ``jobs``
    worker processes, one thread each), in the order they finish. ``work`` is a module-level
    function the workers can import. ``InputError`` when Dask is missing or the scheduler
    cannot be reached. Closing the iteration (Ctrl-C) cancels the tasks in flight and closes
    the client (and the local cluster).
    """
    require()
    if not items:
        return
    from distributed import as_completed

    scan = uuid.uuid4().hex  # this scan's tasks, for _stop_here
    with _connected(address, jobs) as client:
        threads = _threads(client)
        size = batch_size(len(items), threads)
        batches = (range(i, min(i + size, len(items))) for i in range(0, len(items), size))
        indices: dict[Any, range] = {}

        def submit() -> Any:
            batch = next(batches, None)
            if batch is None:
                return None
            given = [items[index] for index in batch]
            future = client.submit(_run_here, work, given, limits, scan, pure=False)
            indices[future.key] = batch
            return future

        first = [submit() for _ in range(IN_FLIGHT * threads)]
        running = as_completed([future for future in first if future is not None])
        asked = time.monotonic()
        try:
            for future in running:
                batch = indices.pop(future.key)
                yield from zip(batch, _outcomes(future, len(batch)), strict=True)
                future.release()
                if time.monotonic() - asked > RECOUNT:  # workers come and go
                    threads, asked = _threads(client), time.monotonic()
                while running.count() < IN_FLIGHT * threads:
                    more = submit()
                    if more is None:
                        break
                    running.add(more)
        finally:
            with contextlib.suppress(Exception):
                client.cancel(list(running.futures))
            with contextlib.suppress(Exception):
                client.run(_stop_here, scan)


def _threads(client: Any) -> int:
    """The threads of the cluster's workers now (at least 1)."""
    try:
        return max(1, sum(client.nthreads().values()))
    except Exception:  # the scheduler busy or gone: as_completed will tell
        return 1


def batch_size(items: int, threads: int) -> int:
    """Assets per task: enough tasks to keep every thread busy (:data:`TASKS_PER_THREAD` each),
    at most :data:`MOST_PER_TASK` assets in one (a task costs the scheduler a few ms, an asset
    of pybullet's objects about 20 ms)."""
    return max(1, min(MOST_PER_TASK, math.ceil(items / (threads * TASKS_PER_THREAD))))


def _outcomes(future: Any, count: int) -> list[Outcome]:
    """The task's outcomes; a task Dask could not run (its worker lost too often, an error
    outside the assets' worker process) is ``crashed`` for each of its assets, saying so."""
    if future.status == "finished":
        return future.result()
    try:
        error = future.exception()
    except Exception as raised:  # cancelled
        error = raised
    message = f"its Dask task failed ({type(error).__name__}: {error})"
    return [Outcome("crashed", message=message) for _ in range(count)]


@contextlib.contextmanager
def _connected(address: str, jobs: int) -> Iterator[Any]:
    """A client of the scheduler at ``address``, or of a new local cluster (``local``)."""
    from distributed import Client, LocalCluster

    cluster = None
    try:
        if address == "local":
            with _deaf_to_ctrl_c():
                cluster = LocalCluster(
                    n_workers=max(1, jobs),
                    threads_per_worker=1,
                    processes=True,
                    memory_limit=0,  # --max-memory holds each asset; the nanny would not know
                    dashboard_address=None,
                    # no dashboard; its HTTP server (health checks) on a free port, not 8787
                    scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
                    silence_logs=logging.ERROR,  # not a worker's cancelled task on Ctrl-C
                )
            client = Client(cluster)
        else:
            client = Client(address, timeout=CONNECT_TIMEOUT)
        client.wait_for_workers(1, timeout=CONNECT_TIMEOUT)
    except (OSError, TimeoutError, ValueError) as error:
        if cluster is not None:
            cluster.close()
        raise InputError(f"--dask {address}: {error}") from None
    try:
        yield client
    finally:
        with contextlib.suppress(Exception):
            client.close()
        if cluster is not None:
            with contextlib.suppress(Exception):
                cluster.close()


@contextlib.contextmanager
def _deaf_to_ctrl_c() -> Iterator[None]:
    """Ctrl-C ignored while the local cluster starts its worker processes, which inherit that:
    Ctrl-C reaches the whole foreground process group, and the client alone should answer it
    (cancel, stop, close the cluster), not each worker dying on its own."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    handler = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, handler)


# --- on a Dask worker ---------------------------------------------------------------------

#: per Dask worker thread: the scan_pool worker process its tasks run in
_here = threading.local()
#: every such worker process of this Dask worker (by id) and the scan whose asset it is on
_all: dict[int, tuple[_Worker, str | None]] = {}
#: the scans :func:`_stop_here` stopped
_stopped: set[str] = set()
#: held while a worker process is handed an item or stopped
_lock = threading.Lock()


def _run_here(
    work: Callable[[Any], Any], items: Sequence[Any], limits: Limits, scan: str
) -> list[Outcome]:
    """A Dask task of the scan ``scan``: ``work(item)`` for each item in turn, in this thread's
    worker process, each under ``limits``."""
    outcomes = []
    for item in items:
        if scan in _stopped:  # cancelled: no one waits for the rest
            outcomes.append(Outcome("crashed", message="the scan was stopped"))
        else:
            outcomes.append(_run_one(work, item, limits, scan))
    return outcomes


def _run_one(work: Callable[[Any], Any], item: Any, limits: Limits, scan: str) -> Outcome:
    context = worker_context(PRELOAD)
    _may_have_children()
    with _lock:
        worker: _Worker | None = getattr(_here, "worker", None)
        fresh = getattr(_here, "work", None) is not work or worker is None
        if fresh or worker.limits != limits or not worker.alive():
            if worker is not None:
                worker.kill()
                _all.pop(id(worker), None)
            worker = _here.worker = _Worker.start(context, work, limits)
            _here.work = work
        worker.give(0, [item])
        _all[id(worker)] = (worker, scan)
    workers = [worker]
    while True:  # _collect yields once the worker answered, died or overran
        for _, outcome in _collect(workers, context, work, limits):
            with _lock:  # _collect started a new worker for one that is gone
                _all.pop(id(worker), None)
                _here.worker = workers[0]
                _all[id(workers[0])] = (workers[0], None)
                if scan in _stopped:  # killed by _stop_here: not its replacement either
                    workers[0].kill()
            return outcome


def _may_have_children() -> None:
    """Let this process (a Dask worker under a nanny: daemonic) start children, which
    ``multiprocessing`` refuses a daemonic process lest they outlive it. Ours do not: a
    scan_pool worker is killed when its parent dies, and is itself daemonic (ended at exit)."""
    import multiprocessing

    multiprocessing.current_process()._config["daemon"] = False  # type: ignore[attr-defined]


def _stop_here(scan: str) -> None:
    """The scan ``scan`` is over (or cancelled): end this Dask worker's idle worker processes,
    and those still on one of its assets (their task returns at once, to no one); one on
    another scan's asset is left to it."""
    with _lock:
        _stopped.add(scan)
        for key, (worker, on) in list(_all.items()):
            if worker.index is None:
                worker.kill()
                del _all[key]
            elif on == scan:  # its thread sees it die, and ends it
                with contextlib.suppress(OSError):
                    os.killpg(worker.process.pid, signal.SIGKILL)
