"""
Output as the work goes, through the real ``inertia-lint`` script: text findings of a file are
printed as soon as it and every file before it are linted; a progress bar on a terminal's
stderr after two seconds, erased before findings and at the end; none when stderr is no
terminal or with ``-q``. The slow file is a runaway xacro stopped by a 3-second time limit.
"""

from __future__ import annotations

import os
import pty
import select
import subprocess
import sys
import time
from pathlib import Path

import pytest
from console_scripts import console_script
from kit.runaway_xacro import doubling_chain
from kit.urdf import inertial, link, robot

WORKTREE = str(Path(__file__).resolve().parents[2])
#: the runaway expansion is stopped after 3 s (an error for that file, exit 2)
SLOW = ("--xacro-limit", "timeout=3", "--xacro-limit", "elements=100000000", "-j", "1")

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="pty, /proc")


def massless(name: str) -> str:
    """A robot whose one link has a mass of 0 kg: IN002."""
    return robot(link("base", inertial(0, 1e-3)), name=name)


@pytest.fixture
def files(tmp_path):
    (tmp_path / "a.urdf").write_text(massless("a"))
    (tmp_path / "m.xacro").write_text(doubling_chain(22))
    (tmp_path / "z.urdf").write_text(massless("z"))
    return tmp_path


def start(args, cwd, **streams) -> subprocess.Popen:
    return subprocess.Popen(
        [console_script("inertia-lint"), *args],
        cwd=cwd,
        env={**os.environ, "PYTHONPATH": WORKTREE},
        **streams,
    )


def test_a_files_findings_are_printed_before_a_later_slow_file_is_done(files):
    process = start(
        [*SLOW, "--output-format", "concise", "."],
        files,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    try:
        first = process.stdout.readline().decode()
        running = process.poll() is None
        rest, stderr = process.communicate(timeout=60)
    finally:
        if process.poll() is None:
            process.kill()
    assert first.startswith("a.urdf:")
    assert running  # printed while m.xacro was still expanding
    assert process.returncode == 2  # m.xacro ran out of time: unreadable
    assert "z.urdf:" in rest.decode() and "a.urdf:" not in rest.decode()
    assert b"time limit" in stderr


def read_all(fd: int, process: subprocess.Popen) -> bytes:
    """Everything written to the pty ``fd`` until the process ends."""
    data = b""
    while True:
        ready, _, _ = select.select([fd], [], [], 0.1)
        if ready:
            try:
                chunk = os.read(fd, 4096)
            except OSError:  # EIO: the other end closed
                break
            if not chunk:
                break
            data += chunk
        elif process.poll() is not None:
            break
    return data


def run_with_terminal_stderr(args, cwd) -> tuple[int, bytes, bytes]:
    parent, child = pty.openpty()
    process = start(args, cwd, stdout=subprocess.PIPE, stderr=child)
    os.close(child)
    stdout = b""
    try:
        terminal = read_all(parent, process)
        stdout = process.stdout.read()
        process.wait(timeout=60)
    finally:
        os.close(parent)
        if process.poll() is None:
            process.kill()
    return process.returncode, stdout, terminal


def test_a_progress_bar_on_a_terminal_after_two_seconds_erased_at_the_end(files):
    code, stdout, terminal = run_with_terminal_stderr(
        [*SLOW, "--output-format", "concise", "."], files
    )
    assert code == 2
    text = terminal.decode()
    bar = "[" + "=" * 13 + " " * 7 + "] 2/3 z.urdf"  # after m.xacro's 3 s: 2 of 3, z next
    assert bar in text
    # erased, with the cursor back at the line's start, before anything else is written
    after = text[text.index(bar) + len(bar) :]
    assert after.startswith("\r" + " " * len(bar) + "\r")
    assert "Found" in after
    assert b"[" not in stdout.replace(b"[error]", b"").replace(b"[warning]", b"")


def test_no_bar_with_quiet_or_when_stderr_is_no_terminal(files):
    code, _, terminal = run_with_terminal_stderr([*SLOW, "-q", "."], files)
    assert code == 2
    # a terminal writes a newline as \r\n; a bar is drawn and erased with a lone \r
    assert b"2/3" not in terminal and b"\r" not in terminal.replace(b"\r\n", b"")
    started = time.monotonic()
    done = subprocess.run(
        [console_script("inertia-lint"), *SLOW, "."],
        cwd=files,
        env={**os.environ, "PYTHONPATH": WORKTREE},
        capture_output=True,
        check=False,
    )
    assert time.monotonic() - started > 2  # long enough for a bar
    assert done.returncode == 2
    assert b"2/3" not in done.stderr and b"\r" not in done.stderr
