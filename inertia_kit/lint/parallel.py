"""
Work on many files in worker processes (``inertia-lint -j N``), results given back in input
order as they are ready (:func:`in_order`): the caller, in the main process, prints them.

Workers come from a ``forkserver`` context (``spawn`` where there is none): the server imports
the linter once and forks each worker from it, so a worker starts without re-importing, and
never inherits the parent's threads or open files. A worker ignores Ctrl-C (the parent alone
decides: it ends the workers and exits 130); the parent ends a worker with SIGTERM, which the
worker turns into an exit through ``finally`` blocks, so that a xacro expansion's sandbox child
(:mod:`inertia_kit.description.urdf.xacro_sandbox`) is killed with it, not orphaned.

A worker that dies (a crash in C, out of memory) breaks the pool; the files not yet done are
then tried again one at a time, each in a pool of its own, so that only the file that kills
its worker gets the error. Where worker processes cannot be started at all (no POSIX
semaphores, as in some containers and serverless sandboxes: ``OSError`` "Function not
implemented"), or could not import the caller's main module (a script read from standard
input), the files are worked on in this process, with the same results.
"""

from __future__ import annotations

import contextlib
import gc
import os
import pickle
import signal
import sys
from collections.abc import Callable, Generator, Iterator, Sequence
from dataclasses import dataclass
from typing import Any, Generic, TypeVar

Item = TypeVar("Item")
Result = TypeVar("Result")

#: what the forkserver imports once, before forking workers
PRELOAD = ["inertia_kit.lint.paths", "inertia_kit.lint.runner", "inertia_kit.lint.applying"]

_settled = False


def settle_start_up() -> None:
    """
    Take what the process holds by now out of the garbage collector's generations, once: the
    modules, the rule catalog and a first file's caches live as long as the process, and every
    later collection would walk them again (``gc.freeze``; ~4 % of the CPU per object of an
    asset library, benchmarks/README.md). Called after the first file, by processes of ours
    only (the CLI, its workers), never in an API caller's process, whose heap is its own.
    """
    global _settled
    if not _settled:
        _settled = True
        gc.freeze()


def usable_cores() -> int:
    """The cores this process may run on (its CPU affinity), at least 1."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)


def worker_count(jobs: int | None, files: int) -> int:
    """``-j``: ``None`` or 0 → the usable cores; never more workers than files, at least 1."""
    wanted = jobs or usable_cores()
    return max(1, min(wanted, files))


class WorkerDied(Exception):
    """A worker process ended while working on a file (a crash in C, killed, out of memory)."""


@dataclass(frozen=True)
class Step(Generic[Result]):
    """
    One more item done (in any order). ``ready``: ``(index, result)`` of the items now done
    together with every item before them, in input order (none, one, or several at once);
    ``done``: how many items are done; ``first``: the first item in input order not done
    (``len(items)`` once all are).
    """

    ready: tuple[tuple[int, Result], ...]
    done: int
    first: int


def in_order(
    work: Callable[[Item], Result],
    items: Sequence[Item],
    jobs: int,
    *,
    failed: Callable[[Item, BaseException], Result],
) -> Generator[Step[Result], None, None]:
    """
    ``work(item)`` for every item in ``jobs`` processes (``work`` a module-level function, items
    and results picklable), a :class:`Step` each time one is done, so that the caller can tell
    the results in input order as soon as they are ready (and its progress meanwhile). An
    exception ``work`` raises, or its worker's death (:class:`WorkerDied`), gives
    ``failed(item, exception)`` as that item's result. Closing the iteration before its end (an
    exception in the caller's loop; a ``with contextlib.closing(...)``) ends the workers.
    """
    waiting: dict[int, Result] = {}
    first = 0
    for done, (index, result) in enumerate(_done(work, items, jobs, failed), start=1):
        waiting[index] = result
        ready = []
        while first in waiting:
            ready.append((first, waiting.pop(first)))
            first += 1
        yield Step(tuple(ready), done, first)


def run_ordered(
    work: Callable[[Item], Result],
    items: Sequence[Item],
    jobs: int,
    *,
    failed: Callable[[Item, BaseException], Result],
    told: Callable[[int, Result], None] | None = None,
    done: Callable[[int, int], None] | None = None,
) -> list[Result]:
    """
    ``[work(item) for item in items]`` as :func:`in_order` works them. ``told(index, result)``
    is called in input order, as soon as an item and every item before it are done;
    ``done(count, first)`` whenever one more item is done (``first``: the first item in input
    order not done).
    """
    results = []
    with contextlib.closing(in_order(work, items, jobs, failed=failed)) as steps:
        for step in steps:
            for index, result in step.ready:
                results.append(result)
                if told is not None:
                    told(index, result)
            if done is not None:
                done(step.done, step.first)
    return results


def _done(
    work: Callable[[Item], Result],
    items: Sequence[Item],
    jobs: int,
    failed: Callable[[Item, BaseException], Result],
) -> Iterator[tuple[int, Result]]:
    """``(index, result)`` of every item, as each is done (in any order)."""
    if jobs <= 1 or not _main_importable():
        for index, item in enumerate(items):
            yield index, _guarded(work, item, failed)
        return
    try:
        broken = yield from _pooled(work, items, list(range(len(items))), jobs, failed)
    except _NoWorkers:  # raised before any item was worked on
        yield from _done(work, items, 1, failed)
        return
    for index in broken:  # one at a time: the file that kills its worker is the one told
        if (yield from _pooled(work, items, [index], 1, failed)):
            yield index, failed(items[index], WorkerDied("its worker process died"))


def _guarded(
    work: Callable[[Item], Result], item: Item, failed: Callable[[Item, BaseException], Result]
) -> Result:
    try:
        return work(item)
    except Exception as error:
        return failed(item, error)


def _pooled(
    work: Callable[[Item], Result],
    items: Sequence[Item],
    indices: list[int],
    jobs: int,
    failed: Callable[[Item, BaseException], Result],
) -> Generator[tuple[int, Result], None, list[int]]:
    """
    Run ``indices`` in a pool of ``jobs``, ``(index, result)`` as each is done; return the
    indices left undone when the pool broke. The workers are ended when the iteration is
    closed or interrupted before its end.
    """
    from concurrent.futures import ProcessPoolExecutor, as_completed
    from concurrent.futures.process import BrokenProcessPool

    try:
        pool = ProcessPoolExecutor(
            jobs,
            mp_context=worker_context(),
            initializer=_worker_started,
            initargs=(dict(os.environ),),
        )
    except (OSError, ImportError, NotImplementedError) as error:
        raise _NoWorkers from error
    try:
        futures = {pool.submit(_call, work, items[i]): i for i in indices}
    except OSError as error:  # the worker processes could not be started (nothing ran yet)
        _terminate(pool)
        raise _NoWorkers from error
    try:
        # as_completed waits on every future once; wait(FIRST_COMPLETED) in a loop installs a
        # waiter on each future left at every turn, quadratic in the number of files
        finished = set()
        for future in as_completed(futures):
            index = futures[future]
            try:
                kind, value = future.result()
            except BrokenProcessPool:
                pool.shutdown()
                return sorted(futures[f] for f in futures if f not in finished)
            finished.add(future)
            yield index, value if kind == "ok" else failed(items[index], value)
        pool.shutdown()
        return []
    except BaseException:  # Ctrl-C, or the caller stopped: end the workers (and their xacro
        _terminate(pool)  # children), then go on with the exception (GeneratorExit included)
        raise


def _main_importable() -> bool:
    """
    Whether a worker can prepare itself as multiprocessing does, by importing the caller's
    ``__main__`` by name or from its file: not a script read from standard input
    (``python - <<EOF``, whose ``__main__.__file__`` is ``<stdin>``), where every worker would
    die at start.
    """
    main = sys.modules.get("__main__")
    if getattr(getattr(main, "__spec__", None), "name", None) is not None:
        return True
    path = getattr(main, "__file__", None)
    return path is None or os.path.isfile(path)


class _NoWorkers(Exception):
    """This system cannot start worker processes (the pool's locks or processes)."""


def start_early() -> None:
    """
    Start the forkserver now, where this system has one: it imports the linter while the caller
    goes on (looking for the robots that include the files found), instead of once the pool is
    made (about a third of a second off a parallel run). Nothing is started where workers
    cannot be; the pool then falls back as it would have.
    """
    context = worker_context()
    if context.get_start_method() != "forkserver":
        return
    from multiprocessing import forkserver

    with contextlib.suppress(OSError, ImportError, NotImplementedError):
        forkserver.ensure_running()


def worker_context(preload: list[str] = PRELOAD) -> Any:
    """The multiprocessing context workers start from: a forkserver that imports ``preload``
    once (``spawn`` where there is none)."""
    import multiprocessing

    methods = multiprocessing.get_all_start_methods()
    context = multiprocessing.get_context("forkserver" if "forkserver" in methods else "spawn")
    if context.get_start_method() == "forkserver":
        context.set_forkserver_preload(preload)
    return context


def _terminate(pool: Any) -> None:
    """End every worker of ``pool`` at once (SIGTERM) and wait for them."""
    processes = list(getattr(pool, "_processes", {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        if process.is_alive():
            process.terminate()
    for process in processes:
        process.join(10)
        if process.is_alive():
            process.kill()
            process.join()


def _worker_started(environment: dict[str, str]) -> None:
    # the forkserver kept the environment of its own start; the caller's may have changed since
    # (INERTIA_KIT_CACHE_DIR, ...); the working folder comes with the pool's preparation data
    os.environ.clear()
    os.environ.update(environment)
    # Ctrl-C reaches the whole process group: the parent alone handles it
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, _ended)


def _ended(signum: int, frame: Any) -> None:
    # unwinds through `finally` (the xacro sandbox kills its child there), then exits
    raise SystemExit(128 + signum)


def _call(work: Callable[[Any], Any], item: Any) -> tuple[str, Any]:
    """In a worker: ``("ok", result)`` or ``("error", exception)``, both picklable."""
    try:
        result = work(item)
        settle_start_up()
        return "ok", result
    except SystemExit:
        os._exit(1)  # SIGTERM from the parent: nothing to send back
    except Exception as error:
        if os.environ.get("INERTIA_KIT_TRACEBACK"):
            import traceback

            traceback.print_exception(type(error), error, error.__traceback__, file=sys.stderr)
        return "error", _picklable(error)


def _picklable(error: Exception) -> Exception:
    try:
        pickle.loads(pickle.dumps(error))
    except Exception:
        return RuntimeError(f"{type(error).__name__}: {error}")
    return error
