"""The forked child an expansion runs in: outcomes, the deadline, signals, and reaping."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import pytest

from inertia_kit.description.urdf import xacro_sandbox
from inertia_kit.errors import InputError

pytestmark = pytest.mark.skipif(not xacro_sandbox.can_fork(), reason="no os.fork here")


def run(work, timeout: float = 10, memory_mb: int = 0):
    return xacro_sandbox.run(work, timeout=timeout, memory_mb=memory_mb, start=time.monotonic())


def test_the_value_comes_back_from_the_child():
    parent = os.getpid()
    assert run(lambda: (os.getpid() != parent, "x" * 3_000_000)) == (True, "x" * 3_000_000)


def test_an_input_error_comes_back_whole():
    def work():
        raise InputError("bad", "robot.xacro", 3, 7)

    with pytest.raises(InputError) as caught:
        run(work)
    assert (caught.value.message, caught.value.path, caught.value.line, caught.value.column) == (
        "bad",
        "robot.xacro",
        3,
        7,
    )


def test_any_other_exception_is_an_internal_error_with_the_childs_traceback():
    def work():
        raise KeyError("oops")

    with pytest.raises(RuntimeError, match=r"(?s)failed in its child process:.*KeyError: 'oops'"):
        run(work)


def test_a_child_killed_by_a_signal_is_reported(tmp_path):
    def work():
        os.kill(os.getpid(), signal.SIGKILL)

    with pytest.raises(xacro_sandbox.ChildDied) as caught:
        run(work)
    assert caught.value.reason() == "it was killed by SIGKILL"


def test_the_deadline_kills_and_reaps_the_child(tmp_path):
    pid_file = tmp_path / "pid"

    def work():
        pid_file.write_text(str(os.getpid()))
        while True:  # Python-level, but the child's own check is not in this loop
            time.sleep(0.01)

    began = time.monotonic()
    with pytest.raises(xacro_sandbox.TimedOut):
        run(work, timeout=0.2)
    assert time.monotonic() - began < 0.2 + xacro_sandbox.GRACE + 2
    with pytest.raises(ProcessLookupError):  # killed and reaped: no zombie left
        os.kill(int(pid_file.read_text()), 0)


def test_work_in_c_is_stopped_too():
    began = time.monotonic()
    with pytest.raises(xacro_sandbox.TimedOut):
        run(lambda: sum(range(10**15)), timeout=0.2)  # one C call: no signal reaches Python
    assert time.monotonic() - began < 0.2 + xacro_sandbox.GRACE + 2


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="RLIMIT_AS is set on Linux")
def test_the_memory_limit_makes_a_large_allocation_fail_in_the_child():
    with pytest.raises(MemoryError):
        run(lambda: len(bytearray(300 << 20)), memory_mb=100)
    assert run(lambda: len(bytearray(50 << 20)), memory_mb=100) == 50 << 20


def test_ctrl_c_in_the_child_is_left_to_the_parent():
    def work():
        os.kill(os.getpid(), signal.SIGINT)  # as a terminal's Ctrl-C reaches the whole group
        return "finished"

    assert run(work) == "finished"


def test_no_fork_possible_says_so(monkeypatch):
    def refuse():
        raise BlockingIOError(11, "Resource temporarily unavailable")

    monkeypatch.setattr(os, "fork", refuse)
    before = len(os.listdir("/proc/self/fd")) if os.path.isdir("/proc/self/fd") else None
    with pytest.raises(xacro_sandbox.CannotFork):
        run(lambda: 1)
    if before is not None:
        assert len(os.listdir("/proc/self/fd")) == before  # the pipe was closed


def test_the_child_leaves_the_parents_objects_out_of_its_collections():
    """Frozen in the child: its collections do not walk (and copy) the parent's heap; the
    parent itself is left as it was."""
    import gc

    before = gc.get_freeze_count()
    assert run(gc.get_freeze_count) > before
    assert gc.get_freeze_count() == before


def test_limits_too_large_to_wait_or_set_are_no_error():
    """``timeout = 1e9`` in [tool.inertia-kit.xacro]: poll takes no such wait (fuzz input 156)."""
    assert run(lambda: "done", timeout=1e12, memory_mb=1 << 60) == "done"


#: in a fresh interpreter: its address-space limit lowered to 200 MB above what it holds (as
#: scan's --max-memory lowers a worker's), an expansion child with a far larger limit of its own
HELD_TO_INHERITED = """
import resource, time
from inertia_kit.description.urdf import xacro_sandbox
size = xacro_sandbox._address_space()
resource.setrlimit(resource.RLIMIT_AS, (size + (200 << 20), resource.RLIM_INFINITY))
print(round(xacro_sandbox.memory_room_mb()))
try:
    xacro_sandbox.run(
        lambda: len(bytearray(400 << 20)), timeout=30, memory_mb=100_000, start=time.monotonic()
    )
    print("allocated")
except MemoryError:
    print("MemoryError")
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="RLIMIT_AS is set on Linux")
def test_the_child_never_raises_the_memory_limit_it_inherits():
    done = subprocess.run(
        [sys.executable, "-c", HELD_TO_INHERITED], capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0, done.stderr
    room, outcome = done.stdout.split()
    assert 190 <= int(room) <= 200  # what the limit leaves, read before the fork
    assert outcome == "MemoryError"  # not 100 000 MB of its own: the 200 MB it was given


def test_no_inherited_limit_leaves_no_room_to_tell():
    import resource

    if resource.getrlimit(resource.RLIMIT_AS)[0] == resource.RLIM_INFINITY:
        assert xacro_sandbox.memory_room_mb() is None
