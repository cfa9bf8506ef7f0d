"""
Work in worker processes (lint/parallel.py): results in input order, told in input order as
soon as every earlier item is done, an exception or a dying worker failing its item only.
"""

from __future__ import annotations

import os
import time

import pytest

from inertia_kit.lint import parallel


def slow_square(item: int) -> int:
    """A module-level function, so that a worker process can import it."""
    time.sleep(0.3 if item == 0 else 0.01)  # the first item finishes last
    return item * item


def troubled(item: int) -> int:
    if item == 2:
        raise ValueError("item 2 is bad")
    if item == 4:
        os._exit(3)  # the worker dies, as in a crash in C
    return item * 10


def failed(item: int, error: BaseException) -> str:
    return f"{item}: {type(error).__name__}: {error}"


@pytest.mark.parametrize("jobs", [1, 2, 3])
def test_results_and_telling_in_input_order(jobs):
    told, counts = [], []
    results = parallel.run_ordered(
        slow_square,
        list(range(6)),
        jobs,
        failed=failed,
        told=lambda index, result: told.append((index, result)),
        done=lambda count, first: counts.append((count, first)),
    )
    assert results == [0, 1, 4, 9, 16, 25]
    assert told == list(enumerate(results))
    assert [count for count, _ in counts] == [1, 2, 3, 4, 5, 6]
    assert counts[-1] == (6, 6)
    if jobs > 1:  # item 0 was the slowest: others were done while it was not told
        assert counts[0][1] == 0


@pytest.mark.parametrize("jobs", [1, 2])
def test_an_exception_fails_its_item_only(jobs):
    items = [0, 1, 2, 3]
    results = parallel.run_ordered(troubled, items, jobs, failed=failed)
    assert results == [0, 10, "2: ValueError: item 2 is bad", 30]


def test_a_dying_worker_fails_its_item_only():
    results = parallel.run_ordered(troubled, [0, 1, 3, 4, 5, 6], 2, failed=failed)
    assert results == [0, 10, 30, "4: WorkerDied: its worker process died", 50, 60]


def test_worker_count(monkeypatch):
    monkeypatch.setattr(parallel, "usable_cores", lambda: 4)
    assert parallel.worker_count(None, 10) == 4  # the default: the usable cores
    assert parallel.worker_count(0, 10) == 4  # -j 0: the same
    assert parallel.worker_count(None, 1) == 1  # one file: no worker process
    assert parallel.worker_count(3, 2) == 2  # never more than the files
    assert parallel.worker_count(1, 10) == 1


def test_usable_cores_are_this_process_affinity():
    expected = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else None
    assert parallel.usable_cores() == (expected or os.cpu_count() or 1)


def in_this_process(item: int) -> tuple[int, int]:
    return item, os.getpid()


def test_without_posix_semaphores_the_items_are_worked_on_in_this_process(monkeypatch):
    """Some containers and serverless sandboxes have no sem_open: the run must not fail."""
    import multiprocessing.synchronize

    def unavailable(*args, **kwargs):
        raise OSError(38, "Function not implemented")

    monkeypatch.setattr(multiprocessing.synchronize.SemLock, "__init__", unavailable)
    told = []
    results = parallel.run_ordered(
        in_this_process, [0, 1, 2], 2, failed=failed, told=lambda i, r: told.append(i)
    )
    assert results == [(0, os.getpid()), (1, os.getpid()), (2, os.getpid())]
    assert told == [0, 1, 2]


def test_when_worker_processes_cannot_start_the_items_are_worked_on_in_this_process(
    monkeypatch,
):
    import multiprocessing.context

    def cannot_start(self):
        raise OSError(11, "Resource temporarily unavailable")

    for name in ("ForkServerProcess", "SpawnProcess"):
        if hasattr(multiprocessing.context, name):
            monkeypatch.setattr(getattr(multiprocessing.context, name), "start", cannot_start)
    results = parallel.run_ordered(in_this_process, [0, 1, 2], 2, failed=failed)
    assert results == [(0, os.getpid()), (1, os.getpid()), (2, os.getpid())]


def test_a_forkserver_started_early_serves_the_pool_and_one_that_cannot_start_is_no_error(
    monkeypatch,
):
    from multiprocessing import forkserver

    parallel.start_early()  # the server the pool then uses: same results
    assert parallel.run_ordered(slow_square, [3, 4], 2, failed=failed) == [9, 16]

    def refused():
        raise OSError(38, "Function not implemented")

    monkeypatch.setattr(forkserver, "ensure_running", refused)
    parallel.start_early()  # says nothing: the pool falls back later as it would have


def test_the_forkserver_is_started_early_only_for_a_run_likely_to_use_it(monkeypatch):
    from inertia_kit.lint.paths import _parallel_likely

    monkeypatch.setattr(parallel, "usable_cores", lambda: 2)
    assert _parallel_likely(600, None, None, False, None)
    assert _parallel_likely(2, 2, None, False, None)
    assert not _parallel_likely(1, None, None, False, None)  # one file: one process
    assert not _parallel_likely(600, 1, None, False, None)  # -j 1
    assert not _parallel_likely(600, None, True, False, None)  # --fix runs here
    assert _parallel_likely(600, None, True, True, None)  # --diff does not
    assert not _parallel_likely(600, None, None, False, object())  # the API's loader
    monkeypatch.setattr(parallel, "usable_cores", lambda: 1)
    assert not _parallel_likely(600, None, None, False, None)  # one core


def test_a_script_read_from_stdin_is_worked_on_in_this_process(tmp_path):
    """Workers import the caller's __main__ from its file: `python -` has none (`<stdin>`)."""
    import subprocess
    import sys

    script = (
        "from inertia_kit.lint import parallel\n"
        "def failed(item, error):\n"
        "    return repr(error)\n"
        "print(parallel.run_ordered(abs, [-1, -2, -3], 2, failed=failed))\n"
    )
    done = subprocess.run(
        [sys.executable, "-"], input=script, capture_output=True, text=True, cwd=tmp_path
    )
    assert (done.returncode, done.stdout) == (0, "[1, 2, 3]\n"), done.stderr


def test_the_heap_is_settled_once_and_never_by_the_api(monkeypatch, tmp_path):
    """settle_start_up freezes what the process holds once (later calls add nothing); the API
    (lint_paths) never calls it: an API caller's heap is its own."""
    import gc

    from inertia_kit.lint import parallel
    from inertia_kit.lint.paths import lint_paths

    monkeypatch.setattr(parallel, "_settled", False)
    gc.unfreeze()  # a command run in this process before (CliRunner) may have settled it
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/></robot>')
    lint_paths([robot])
    assert not parallel._settled
    assert gc.get_freeze_count() == 0
    try:
        parallel.settle_start_up()
        frozen = gc.get_freeze_count()
        assert frozen > 0
        kept = [[k] for k in range(1000)]  # tracked objects made after it
        parallel.settle_start_up()
        assert gc.get_freeze_count() == frozen
        assert kept
    finally:
        gc.unfreeze()
