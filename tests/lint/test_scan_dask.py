"""
``inertia-kit scan --dask`` (inertia_kit/lint/scan_dask.py) on a real local Dask cluster (worker
processes under nannies, as ``dask worker`` starts them): the same lines as a local scan apart
from the measured fields, resume after a partial record, an asset over ``--timeout`` recorded
``timeout`` while the others go on, and exit 2 saying how to install Dask when it is missing.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from click.testing import CliRunner
from kit import write
from kit.assets import asset_library
from kit.runaway_xacro import doubling_chain

from inertia_kit.cli import main as kit_command
from inertia_kit.lint.scan import MEASURED
from inertia_kit.physics import mesh_cache

distributed = pytest.importorskip("distributed")

pytestmark = pytest.mark.skipif(
    not sys.platform.startswith("linux"), reason="worker limits read /proc"
)

ROOT = Path(__file__).resolve().parents[2]
#: generous xacro limits: the expansion runs until scan's own --timeout stops it
GENEROUS = ["--xacro-limit", "timeout=60,memory=3000,elements=100000000"]


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    """A scheduler and two worker processes of one thread each, under nannies (daemonic, as
    ``dask worker`` starts them); their cache in the session's temporary folder."""
    cache = tmp_path_factory.getbasetemp() / "mesh-cache"
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("INERTIA_KIT_CACHE_DIR", str(cache))
        local = distributed.LocalCluster(
            n_workers=2,
            processes=True,
            threads_per_worker=1,
            dashboard_address=None,
            scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},  # not 8787
        )
    with local:
        yield local.scheduler_address


def library(folder: Path, count: int = 40) -> Path:
    """``count`` small robots in ten folders: a third with a mesh, a third with a wrong tensor,
    and one unreadable."""
    return asset_library(folder, count, broken=True)


def scan(*args: str):
    return CliRunner().invoke(kit_command, ["scan", "-q", *args])


def records(path: Path) -> list[dict]:
    text = path.read_text()
    assert text == "" or text.endswith("\n")
    return [json.loads(line) for line in text.splitlines()]


def stable(found: list[dict]) -> list[str]:
    return sorted(json.dumps({k: v for k, v in r.items() if k not in MEASURED}) for r in found)


def test_a_local_cluster_records_the_lines_a_local_scan_does(tmp_path):
    lib = str(library(tmp_path / "lib"))
    here = scan("-j", "2", "-o", f"{tmp_path}/here.jsonl", lib)
    cache = tmp_path / "shared-cache"
    # the cache stores no mesh changed in the last RACY_SECONDS (physics.mesh_cache): on a
    # fast machine both scans end inside that window, and the workers rightly store nothing
    mesh = tmp_path / "lib" / "meshes" / "box.stl"
    changed = max(mesh.stat().st_mtime, mesh.stat().st_ctime)
    time.sleep(max(0.0, changed + mesh_cache.RACY_SECONDS + 0.5 - time.time()))
    there = scan(
        "--dask", "local", "-j", "2", "--mesh-cache", str(cache), "-o", f"{tmp_path}/d.jsonl", lib
    )
    assert here.exit_code == there.exit_code == 1, there.output
    expected, found = records(tmp_path / "here.jsonl"), records(tmp_path / "d.jsonl")
    assert len(found) == 40 and stable(found) == stable(expected)
    statuses = {r["status"] for r in found}
    assert statuses == {"ok", "findings", "unreadable"}
    assert all(r["wall_seconds"] > 0 and r["peak_memory_mb"] for r in found)
    assert any(cache.iterdir())  # the workers used the cache they were given


def test_a_partial_record_resumes_on_the_cluster(tmp_path, cluster):
    lib = str(library(tmp_path / "lib"))
    whole = tmp_path / "whole.jsonl"
    assert scan("--dask", cluster, "-o", str(whole), lib).exit_code == 1
    expected = records(whole)
    partial = tmp_path / "partial.jsonl"
    lines = whole.read_text().splitlines(keepends=True)
    partial.write_text("".join(lines[:15]) + lines[15][:40])  # the 16th cut by a kill
    summary = tmp_path / "summary.json"
    result = scan("--dask", cluster, "-o", str(partial), "--summary", str(summary), lib)
    assert result.exit_code == 1, result.output
    resumed = records(partial)
    assert len({r["path"] for r in resumed}) == len(resumed) == 40
    assert stable(resumed) == stable(expected)
    assert resumed[:15] == records(whole)[:15]  # kept as they were
    run = json.loads(summary.read_text())["run"]
    assert run["assets"] == 25


def test_an_asset_over_the_timeout_is_recorded_and_the_cluster_goes_on(tmp_path, cluster):
    lib = library(tmp_path / "lib", 8)
    write(lib / "a" / "chain.xacro", doubling_chain(22))
    out = tmp_path / "t.jsonl"
    result = scan("--dask", cluster, "--timeout", "1", *GENEROUS, "-o", str(out), str(lib))
    assert result.exit_code == 1, result.output
    status = {Path(r["path"]).name: r for r in records(out)}
    assert len(status) == 9
    assert status["chain.xacro"]["status"] == "timeout"
    assert status["chain.xacro"]["error"] == "stopped after 1 s, the time limit (--timeout)"
    assert {r["status"] for n, r in status.items() if n != "chain.xacro"} == {
        "ok", "findings", "unreadable"
    }  # fmt: skip
    # the Dask workers survived: the cluster scans again
    again = scan("--dask", cluster, "-o", str(tmp_path / "again.jsonl"), str(lib / "g1"))
    assert again.exit_code == 1 and len(records(tmp_path / "again.jsonl")) == 1


def test_ctrl_c_closes_the_local_cluster_and_the_record_resumes(tmp_path):
    import psutil

    lib = library(tmp_path / "lib", 7)
    write(lib / "a" / "chain.xacro", doubling_chain(22))  # expands until Ctrl-C
    out = tmp_path / "o.jsonl"
    process = subprocess.Popen(
        [sys.executable, "-m", "inertia_kit", "scan", "-q", "--dask", "local", "-j", "2",
         *GENEROUS, "-o", str(out), str(lib)],
        env={**os.environ, "PYTHONPATH": str(ROOT)}, stdout=subprocess.PIPE,
        stderr=subprocess.PIPE, text=True, start_new_session=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )  # fmt: skip
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and not (out.exists() and out.read_text().count("\n") == 7):
        time.sleep(0.1)
    children = psutil.Process(process.pid).children(recursive=True)
    assert len(children) >= 4  # two Dask workers, their forkservers and asset processes
    os.killpg(process.pid, signal.SIGINT)  # as a terminal's Ctrl-C: the whole group
    stdout, stderr = process.communicate(timeout=60)
    assert (process.returncode, stdout, stderr) == (130, "", "interrupted\n")
    _, alive = psutil.wait_procs(children, timeout=20)
    assert alive == []
    assert len(records(out)) == 7
    result = scan(
        "--dask", "local", "-j", "2", "--timeout", "1", *GENEROUS, "-o", str(out), str(lib)
    )
    assert result.exit_code == 1, result.output
    status = {Path(r["path"]).name: r["status"] for r in records(out)}
    assert len(status) == 8 and status["chain.xacro"] == "timeout"


def test_without_dask_it_says_how_to_install_it(tmp_path, monkeypatch):
    library(tmp_path / "lib", 2)
    monkeypatch.setitem(sys.modules, "distributed", None)  # import distributed: ImportError
    out = tmp_path / "o.jsonl"
    result = scan("--dask", "local", "-o", str(out), str(tmp_path / "lib"))
    assert result.exit_code == 2
    said = "error: --dask needs Dask's distributed: pip install 'inertia-kit[dask]'\n"
    assert result.stderr == said
    assert not out.exists()


def test_a_local_scan_imports_no_dask(tmp_path):
    library(tmp_path / "lib", 2)
    code = (
        "import sys\n"
        "from inertia_kit.cli import main\n"
        f"main(['scan', '-q', '-j', '1', '-o', {str(tmp_path / 'o.jsonl')!r},"
        f" {str(tmp_path / 'lib')!r}], standalone_mode=False)\n"
        "print(sorted(m for m in sys.modules if m.split('.')[0] in ('dask', 'distributed')))\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip().splitlines()[-1] == "[]"
    assert len(records(tmp_path / "o.jsonl")) == 2
