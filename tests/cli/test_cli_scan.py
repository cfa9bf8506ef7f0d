"""
``inertia-kit scan`` through the real console script: killed with SIGKILL at random moments and
resumed, it records every asset exactly once, as an uninterrupted run does; a runaway xacro is
recorded and the run goes on; Ctrl-C is exit 130 with a record ready to resume; exit codes,
summary, keep-list and the progress bar's rate and ETA.
"""

from __future__ import annotations

import io
import json
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from click.testing import CliRunner
from console_scripts import console_script
from kit import urdf, write
from kit.assets import asset_library
from kit.runaway_xacro import HUGE_POWER, doubling_chain, expression_robot

from inertia_kit.cli import main as kit_command
from inertia_kit.cli.progress import Progress, rate_text
from inertia_kit.lint.scan import MEASURED

WORKTREE = str(Path(__file__).resolve().parents[2])
#: generous xacro limits: the expansion runs until scan's own --timeout stops it
GENEROUS = ["--xacro-limit", "timeout=60,memory=3000,elements=100000000"]

pytestmark = pytest.mark.skipif(
    not sys.platform.startswith("linux"), reason="worker limits read /proc"
)


def library(folder: Path, count: int) -> Path:
    """``count`` small robots in ten folders, a third with a mesh, a third with a wrong tensor."""
    return asset_library(folder, count)


def scan_process(*args: str, cwd: Path, **options) -> subprocess.Popen:
    return subprocess.Popen(
        [console_script("inertia-kit"), "scan", *args],
        cwd=cwd,
        env={**os.environ, "PYTHONPATH": WORKTREE},
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        **options,
    )


def records(path: Path) -> list[dict]:
    text = path.read_text()
    assert text == "" or text.endswith("\n")
    return [json.loads(line) for line in text.splitlines()]


def _lines(path: Path) -> int:
    """Complete lines in ``path`` (a kill may leave one partial line after them)."""
    return path.read_bytes().count(b"\n") if path.exists() else 0


def stable(found: list[dict]) -> list[str]:
    return sorted(json.dumps({k: v for k, v in r.items() if k not in MEASURED}) for r in found)


def test_killed_five_times_and_resumed_it_records_each_asset_once_as_an_uninterrupted_run(
    tmp_path,
):
    lib = library(tmp_path / "lib", 60)
    whole = scan_process("-q", "-j", "2", "-o", "whole.jsonl", "lib", cwd=tmp_path)
    whole.communicate(timeout=120)
    expected = records(tmp_path / "whole.jsonl")
    assert len(expected) == 60

    chance = random.Random(20240611)
    counts = []
    killed = tmp_path / "killed.jsonl"
    for _ in range(5):
        before = _lines(killed)
        process = scan_process("-q", "-j", "2", "-o", "killed.jsonl", "lib", cwd=tmp_path)
        # at a random moment once this run has recorded something (a loaded machine starts
        # slowly: a fixed delay would kill it before its first asset)
        deadline = time.monotonic() + 60
        while _lines(killed) <= before and process.poll() is None and time.monotonic() < deadline:
            time.sleep(0.01)
        # soon after: a fast machine lints the 60 assets in about a second, and each kill
        # must land mid-run for the test to kill anything
        time.sleep(chance.uniform(0.0, 0.05))
        process.send_signal(signal.SIGKILL)
        process.communicate(timeout=30)
        counts.append(_lines(killed))
    last = scan_process("-q", "-j", "2", "-o", "killed.jsonl", "lib", cwd=tmp_path)
    last.communicate(timeout=120)
    assert last.returncode == 1  # the wrong tensors
    resumed = records(tmp_path / "killed.jsonl")
    paths = [r["path"] for r in resumed]
    assert len(paths) == len(set(paths)) == 60
    assert stable(resumed) == stable(expected)
    assert counts == sorted(counts), counts  # each resumed run kept what the ones before recorded
    assert sum(0 < count < 60 for count in counts) >= 3, counts  # kills landed mid-run
    assert lib.exists()


def test_a_runaway_xacro_is_recorded_and_the_run_goes_on(tmp_path):
    write(tmp_path / "lib" / "a" / "power.xacro", expression_robot(HUGE_POWER))
    write(tmp_path / "lib" / "a" / "chain.xacro", doubling_chain(22))
    write(tmp_path / "lib" / "b" / "fine.urdf", urdf.robot(urdf.link("l")))
    # the project's own xacro limits stop both first: unreadable, said where
    result = CliRunner().invoke(
        kit_command, ["scan", "-q", "-o", f"{tmp_path}/o.jsonl", f"{tmp_path}/lib"]
    )
    assert result.exit_code == 1, result.output
    status = {Path(r["path"]).name: r for r in records(tmp_path / "o.jsonl")}
    assert {name: r["status"] for name, r in status.items()} == {
        "power.xacro": "unreadable",
        "chain.xacro": "unreadable",
        "fine.urdf": "ok",
    }
    assert status["power.xacro"]["error"].startswith(f"{tmp_path}/lib/a/power.xacro:3:")
    # with them raised, scan's --timeout stops the expansion, and the run goes on
    started = time.monotonic()
    given = [f"{tmp_path}/lib/a/chain.xacro", f"{tmp_path}/lib/b"]
    result = CliRunner().invoke(
        kit_command,
        ["scan", "-q", "--timeout", "1", *GENEROUS, "-o", f"{tmp_path}/t.jsonl", *given],
    )
    assert time.monotonic() - started < 20
    assert result.exit_code == 1, result.output
    status = {Path(r["path"]).name: r for r in records(tmp_path / "t.jsonl")}
    assert status["chain.xacro"]["status"] == "timeout"
    assert status["chain.xacro"]["error"] == "stopped after 1 s, the time limit (--timeout)"
    assert status["fine.urdf"]["status"] == "ok"


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="RLIMIT_AS is set on Linux")
def test_a_xacro_asset_is_held_to_the_scan_memory_limit_below_the_xacro_one(tmp_path):
    """The expansion's child process keeps the worker's --max-memory, though the xacro memory
    limit it sets for itself is larger, and says which limit it met."""
    write(tmp_path / "lib" / "a" / "string.xacro", expression_robot("'x'*10**9"))  # 1 GB
    write(tmp_path / "lib" / "b" / "fine.urdf", urdf.robot(urdf.link("l")))
    started = time.monotonic()
    given = ["--max-memory", "300", "--timeout", "60", *GENEROUS]  # xacro's: 3000 MB
    result = CliRunner().invoke(
        kit_command, ["scan", "-q", *given, "-o", f"{tmp_path}/o.jsonl", f"{tmp_path}/lib"]
    )
    assert time.monotonic() - started < 30  # refused at once, not 1 GB filled and timed out
    assert result.exit_code == 1, result.output
    status = {Path(r["path"]).name: r for r in records(tmp_path / "o.jsonl")}
    assert status["fine.urdf"]["status"] == "ok"
    assert status["string.xacro"]["status"] == "unreadable"
    assert (
        "MB this process may still take (its address-space limit" in status["string.xacro"]["error"]
    ), status["string.xacro"]["error"]


def test_ctrl_c_is_exit_130_and_the_record_resumes(tmp_path):
    write(tmp_path / "lib" / "a" / "chain.xacro", doubling_chain(22))
    library(tmp_path / "lib", 6)
    process = scan_process(
        "-j", "1", *GENEROUS, "-o", "o.jsonl", "lib", cwd=tmp_path,
        start_new_session=True, preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )  # fmt: skip
    time.sleep(2.5)  # the chain, first in order, is expanding
    os.killpg(process.pid, signal.SIGINT)
    stdout, stderr = process.communicate(timeout=30)
    assert (process.returncode, stdout, stderr) == (130, "", "interrupted\n")
    records(tmp_path / "o.jsonl")  # complete lines only
    done = CliRunner().invoke(
        kit_command,
        ["scan", "-q", "--timeout", "1", "-o", f"{tmp_path}/o.jsonl", f"{tmp_path}/lib"],
    )
    assert done.exit_code == 1
    assert len(records(tmp_path / "o.jsonl")) == 7


def test_exit_codes_summary_keep_list_and_list_input(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    library(tmp_path / "lib", 6)
    clean = [f"lib/g{n}/r{n}.urdf" for n in (0, 3)]
    (tmp_path / "clean.txt").write_text("\n".join(clean) + "\n")
    runner = CliRunner()
    result = runner.invoke(kit_command, ["scan", "--list", "clean.txt", "-o", "c.jsonl"])
    assert result.exit_code == 0, result.output
    assert "Scanned 2 assets: 2 ok\n" in result.stderr and "assets/s" in result.stderr
    result = runner.invoke(kit_command, ["scan", "-q", "--list", "-", "-o", "s.jsonl"],
                           input="\n".join(clean))  # fmt: skip
    assert (result.exit_code, result.stderr) == (0, "")
    args = ["scan", "-o", "all.jsonl", "--summary", "sum.json", "--keep", "keep.txt"]
    result = runner.invoke(kit_command, [*args, "--keep-at", "none", "lib"])
    assert result.exit_code == 1
    summary = json.loads((tmp_path / "sum.json").read_text())
    assert summary["assets"] == 6 and summary["statuses"] == {"findings": 2, "ok": 4}
    assert set(summary["folders"]) == {f"g{n}" for n in range(6)}
    assert summary["run"]["assets"] == 6 and summary["run"]["assets_per_second"] > 0
    assert "IN010" in summary["rules"]
    kept = (tmp_path / "keep.txt").read_text().splitlines()
    assert sorted(kept) == sorted(str(Path("lib", f"g{n}", f"r{n}.urdf")) for n in (0, 2, 3, 5))
    result = runner.invoke(kit_command, ["scan", "--fail-on", "error", "-o", "x.jsonl"])
    assert result.exit_code == 2 and "give files or folders" in result.stderr
    result = runner.invoke(kit_command, ["scan", "--list", "missing.txt", "-o", "x.jsonl"])
    assert result.exit_code == 2 and "--list: missing.txt" in result.stderr


def test_a_listed_path_no_file_can_have_is_recorded_unreadable_and_the_run_goes_on(
    tmp_path, monkeypatch
):
    """A NUL in a line of --list (a list cut from a binary file) is an asset that cannot be
    read, not an internal error of the whole scan."""
    monkeypatch.chdir(tmp_path)
    library(tmp_path / "lib", 3)
    (tmp_path / "list.txt").write_bytes(b"lib/g0/r0.urdf\nbad\x00name.urdf\n\xff\xfe\n")
    result = CliRunner().invoke(kit_command, ["scan", "-q", "--list", "list.txt", "-o", "o.jsonl"])
    assert result.exit_code == 1, result.output  # an asset not linted counts as an error
    assert "internal error" not in result.stderr
    status = {r["path"]: (r["status"], r["error"]) for r in records(tmp_path / "o.jsonl")}
    assert status["lib/g0/r0.urdf"] == ("ok", None)
    assert status["bad\x00name.urdf"][0] == "unreadable"
    assert "null byte" in status["bad\x00name.urdf"][1]


@pytest.mark.parametrize(
    "limits",
    [
        ["--timeout", "0"],
        ["--timeout", "1e300"],
        ["--max-memory", str(10**30)],
        ["--max-memory", "0"],
    ],
)
def test_no_limit_and_limits_past_what_the_platform_holds_scan_everything(tmp_path, limits):
    """``--timeout 0`` is no time limit (it was an internal error: an infinite wait); a limit
    no platform holds is none either."""
    library(tmp_path / "lib", 3)
    out = tmp_path / "o.jsonl"
    result = CliRunner().invoke(
        kit_command, ["scan", "-q", *limits, "-o", str(out), f"{tmp_path}/lib"]
    )
    assert result.exit_code == 1, result.output  # one wrong tensor
    assert "internal error" not in result.stderr
    assert sorted(r["status"] for r in records(out)) == ["findings", "ok", "ok"]


@pytest.mark.parametrize("value", ["nan", "inf"])
def test_a_timeout_that_is_no_number_is_refused(tmp_path, value):
    library(tmp_path / "lib", 1)
    result = CliRunner().invoke(
        kit_command, ["scan", "--timeout", value, "-o", f"{tmp_path}/o.jsonl", f"{tmp_path}/lib"]
    )
    assert result.exit_code == 2
    assert f"Invalid value for '--timeout': a number of seconds (0: none), got {value}" in (
        result.stderr
    )
    assert not (tmp_path / "o.jsonl").exists()


@pytest.mark.parametrize("option", ["--keep", "--summary"])
def test_a_file_written_at_the_end_into_no_folder_fails_before_the_scan(tmp_path, option):
    """Not after hours of scanning (it was an internal error then, for --keep)."""
    library(tmp_path / "lib", 2)
    written = f"{tmp_path}/nowhere/x"
    result = CliRunner().invoke(
        kit_command, ["scan", "-q", "-o", f"{tmp_path}/o.jsonl", option, written, f"{tmp_path}/lib"]
    )
    assert result.exit_code == 2
    assert f"error: {written}: cannot write: no folder {tmp_path}/nowhere\n" == result.stderr
    assert not (tmp_path / "o.jsonl").exists()  # nothing was scanned


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes here")
def test_a_record_that_is_no_regular_file_is_refused(tmp_path):
    """A record is read back (resume, summary, keep-list): a named pipe we hold open would
    never end; a device is no record either."""
    library(tmp_path / "lib", 2)
    os.mkfifo(tmp_path / "o.jsonl")
    result = CliRunner().invoke(
        kit_command, ["scan", "-q", "-o", f"{tmp_path}/o.jsonl", f"{tmp_path}/lib"]
    )
    assert result.exit_code == 2
    assert "o.jsonl: is not a regular file: a record is read back; give a file" in result.stderr


def test_rate_and_eta_text():
    assert rate_text(0, 5.0, 10) == "0.0/s ETA -"
    assert rate_text(50, 10.0, 450) == "5.0/s ETA 1:30"
    assert rate_text(1, 1.0, 4000) == "1.0/s ETA 1:06:40"


def test_the_scan_bar_shows_the_rate_of_this_run_and_the_eta():
    stream = io.StringIO()
    progress = Progress(True, stream, delay=0.0, rate=True)
    progress.done_before = 400  # a resumed run: those are not in the rate
    progress.start -= 10.0
    progress.update(500, 1000, "a.urdf")
    assert stream.getvalue() == "[" + "=" * 10 + " " * 10 + "] 500/1000 10.0/s ETA 0:50 a.urdf"
    plain = io.StringIO()
    Progress(True, plain, delay=0.0).update(1, 2, None)
    assert plain.getvalue() == "[" + "=" * 10 + " " * 10 + "] 1/2"


@pytest.mark.parametrize("option", ["-o", "--keep", "--summary"])
def test_a_file_the_scan_writes_is_never_written_through_a_link(tmp_path, option):
    """A symbolic link planted at (or on the way to) a file the scan writes: exit 2, said, and
    nothing written where it points."""
    library(tmp_path / "assets", 2)
    target = tmp_path / "elsewhere.txt"
    (tmp_path / "planted").symlink_to(target)
    written = {"-o": "record.jsonl", "--keep": "keep.txt", "--summary": "summary.json"}
    written[option] = "planted"
    args = ["scan", "-q", "assets"]
    for flag, name in written.items():
        args += [flag, str(tmp_path / name)]
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        result = CliRunner().invoke(kit_command, args)
    finally:
        os.chdir(cwd)
    assert result.exit_code == 2, result.output
    assert "symbolic link" in result.output and "not written" in result.output
    assert not target.exists()
    assert not (tmp_path / "record.jsonl").exists()
