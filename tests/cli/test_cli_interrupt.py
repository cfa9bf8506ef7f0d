"""
Ctrl-C through the real console scripts: SIGINT while a slow xacro expands (in its forked,
SIGINT-ignoring child, cli/guard.py and description/urdf/xacro_sandbox.py) is exit 130 with
``interrupted`` and no traceback, at once, and the expansion's child process is gone.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from console_scripts import console_script
from kit.runaway_xacro import doubling_chain

WORKTREE = str(Path(__file__).resolve().parents[2])
#: generous limits: the expansion is still running when Ctrl-C comes
LIMITS = ("--xacro-limit", "timeout=60", "--xacro-limit", "memory=3000")
LIMITS += ("--xacro-limit", "elements=100000000")

pytestmark = pytest.mark.skipif(
    not sys.platform.startswith("linux"), reason="reads /proc for the xacro child"
)


def children(pid: int) -> list[int]:
    text = Path(f"/proc/{pid}/task/{pid}/children").read_text()
    return [int(child) for child in text.split()]


def default_sigint() -> None:
    # a shell without job control starts background commands with SIGINT ignored, which
    # Python keeps; a user's terminal does not
    signal.signal(signal.SIGINT, signal.SIG_DFL)


@pytest.mark.parametrize("script", ["inertia-lint", "inertia-fill"])
def test_sigint_during_a_slow_xacro_is_exit_130_and_leaves_no_child(tmp_path, script):
    robot = tmp_path / "slow.xacro"
    robot.write_text(doubling_chain(19))
    process = subprocess.Popen(
        [console_script(script), *LIMITS, str(robot)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "PYTHONPATH": WORKTREE},
        preexec_fn=default_sigint,
    )
    try:
        deadline = time.monotonic() + 30
        expanding: list[int] = []
        while not expanding and process.poll() is None and time.monotonic() < deadline:
            time.sleep(0.05)
            expanding = children(process.pid)
        assert expanding, "the xacro expansion's child process never appeared"
        time.sleep(0.3)  # well inside the expansion
        interrupted_at = time.monotonic()
        process.send_signal(signal.SIGINT)
        stdout, stderr = process.communicate(timeout=30)
    finally:
        if process.poll() is None:
            process.kill()
            process.communicate()
    assert (process.returncode, stdout, stderr) == (130, "", "interrupted\n")
    assert time.monotonic() - interrupted_at < 10  # not after the 60 s time limit
    for child in expanding:
        assert not Path(f"/proc/{child}").exists(), f"xacro child {child} outlived Ctrl-C"


def descendants(pid: int) -> list[int]:
    found = []
    for child in children(pid):
        found += [child, *descendants(child)]
    return found


def test_sigint_with_worker_processes_is_exit_130_and_leaves_no_process(tmp_path):
    """Ctrl-C reaches the whole process group: the command, its workers, their xacro children."""
    for name in ("a.xacro", "b.xacro"):
        (tmp_path / name).write_text(doubling_chain(19))
    process = subprocess.Popen(
        [console_script("inertia-lint"), "-j", "2", *LIMITS, str(tmp_path)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "PYTHONPATH": WORKTREE},
        start_new_session=True,  # its own process group, as a terminal's foreground job
        preexec_fn=default_sigint,
    )
    try:
        deadline = time.monotonic() + 60
        tree: list[int] = []
        # the forkserver, two workers, and an expansion's child under each worker
        while len(tree) < 5 and process.poll() is None and time.monotonic() < deadline:
            time.sleep(0.05)
            tree = descendants(process.pid)
        assert len(tree) >= 5, f"workers and their xacro children never all appeared: {tree}"
        time.sleep(0.3)
        interrupted_at = time.monotonic()
        os.killpg(process.pid, signal.SIGINT)
        stdout, stderr = process.communicate(timeout=30)
    finally:
        if process.poll() is None:
            process.kill()
            process.communicate()
    assert (process.returncode, stdout, stderr) == (130, "", "interrupted\n")
    assert time.monotonic() - interrupted_at < 10
    deadline = time.monotonic() + 5
    while any(Path(f"/proc/{pid}").exists() for pid in tree) and time.monotonic() < deadline:
        time.sleep(0.05)
    left = [pid for pid in tree if Path(f"/proc/{pid}").exists()]
    assert not left, f"processes outlived Ctrl-C: {left}"


def test_sigint_while_the_command_imports_is_exit_130_without_a_traceback(tmp_path):
    """
    Ctrl-C in the first moments, before the command's guard exists (cli/__init__.py): at
    delays spread over a small robot's whole run, never a traceback; interrupted, exit 130.
    """
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/></robot>')
    outcomes = []
    for step in range(15):
        process = subprocess.Popen(
            [console_script("inertia-lint"), str(robot)],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            env={**os.environ, "PYTHONPATH": WORKTREE},
            preexec_fn=default_sigint,
        )
        time.sleep(0.02 * step)
        process.send_signal(signal.SIGINT)
        stdout, stderr = process.communicate(timeout=30)
        if "init_import_site" in stderr:
            continue  # Python itself was still starting (its site module), before any of ours
        if "Traceback" in stderr and "/inertia_kit/" not in stderr:
            continue  # the console script's own lines (`import re`, finding the package)
        assert "Traceback" not in stderr and "KeyboardInterrupt" not in stderr, stderr
        if process.returncode == -signal.SIGINT and not stderr:
            continue  # killed before Python set up its own handler: silent, as any program
        if "No findings" not in stdout + stderr:  # interrupted before it finished
            assert (process.returncode, stderr[-12:]) == (130, "interrupted\n"), stderr
        outcomes.append(process.returncode)
    assert outcomes
