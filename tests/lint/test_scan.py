"""
``inertia-kit scan``'s layer (inertia_kit/lint/scan*.py): the lines equal inertia-lint's JSON
findings, resume keeps every asset exactly once, the worker pool holds each item to its limits,
the summary streams in flat memory, the keep-list keeps what it says.
"""

from __future__ import annotations

import json
import os
import signal
import time
import tracemalloc
from pathlib import Path

import pytest
from click.testing import CliRunner
from kit import urdf, write
from kit.meshes import write_box_stl

from inertia_kit.cli.lint import lint_command
from inertia_kit.lint.findings import Severity
from inertia_kit.lint.scan import MEASURED, Asset, ScanOptions, listed, scanning, walked
from inertia_kit.lint.scan_pool import Limits, run_limited
from inertia_kit.lint.scan_record import Record, encode, lines
from inertia_kit.lint.scan_summary import keeps, summarise, write_keep_list

pytestmark = pytest.mark.skipif(not os.path.exists("/proc/self/status"), reason="Linux workers")


def small_robots(folder: Path) -> list[Path]:
    """Four robots: clean, a wrong tensor, a mesh link, and one unreadable."""
    write_box_stl(folder / "meshes" / "box.stl", (0.1, 0.2, 0.3))
    box = urdf.collision(urdf.box(0.1, 0.2, 0.3))
    mesh = urdf.collision(urdf.mesh("../meshes/box.stl"))
    bodies = {
        "a/clean.urdf": (urdf.box_inertial(2.0, (0.1, 0.2, 0.3)), box),
        "a/wrong.urdf": (urdf.inertial(2.0, 1.0, 1.0, 0.0), box),
        "b/mesh.urdf": (urdf.inertial(5.0, 0.1), mesh),
    }
    files = [
        write(folder / name, urdf.robot(urdf.link("l", *body))) for name, body in bodies.items()
    ]
    return [*files, write(folder / "b" / "broken.urdf", "<robot name='r'><link name='l'>")]


def scan_all(assets, out, **options) -> list[dict]:
    for _ in scanning(assets, out, ScanOptions(**options)):
        pass
    return list(lines(out))


def test_lines_hold_the_findings_inertia_lint_gives_as_json(tmp_path):
    files = small_robots(tmp_path / "lib")
    records = {r["path"]: r for r in scan_all(walked([tmp_path / "lib"]), tmp_path / "o.jsonl")}
    assert set(records) == {str(f) for f in files}
    for file in files:
        result = CliRunner().invoke(lint_command, ["--output-format", "json", str(file)])
        expected = json.loads(result.stdout)
        record = records[str(file)]
        if record["status"] == "unreadable":
            (entry,) = expected
            assert entry["code"] == "IN000" and record["findings"] == []
            assert record["error"].startswith(f"{file}:1:") and entry["message"] in record["error"]
            continue
        assert record["findings"] == expected
        assert record["status"] == ("findings" if expected else "ok")
    assert [r["status"] for r in map(records.get, map(str, files))] == [
        "ok", "findings", "findings", "unreadable"
    ]  # fmt: skip


def test_a_line_holds_links_hashes_times_and_the_folder(tmp_path):
    files = small_robots(tmp_path / "lib")
    records = {r["path"]: r for r in scan_all(walked([tmp_path / "lib"]), tmp_path / "o.jsonl")}
    mesh = records[str(files[2])]
    assert mesh["folder"] == "b"
    (link,) = mesh["links"]
    assert link["link"] == "l" and link["mass"] == 5.0 and link["com"] == [0.0, 0.0, 0.0]
    assert link["inertia"] == [[0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]
    import hashlib

    stl = os.path.realpath(tmp_path / "lib" / "meshes" / "box.stl")
    assert mesh["files"][stl] == hashlib.sha256(Path(stl).read_bytes()).hexdigest()
    assert mesh["sha256"] == hashlib.sha256(files[2].read_bytes()).hexdigest()
    assert mesh["files"][os.path.realpath(files[2])] == mesh["sha256"]
    assert mesh["wall_seconds"] > 0 and mesh["cpu_seconds"] >= 0 and mesh["peak_memory_mb"] > 0


def test_resume_cuts_a_partial_line_skips_what_is_recorded_and_redoes_an_edited_asset(tmp_path):
    files = small_robots(tmp_path / "lib")
    out = tmp_path / "o.jsonl"
    assets = walked([tmp_path / "lib"])
    first = scan_all(assets, out)
    with open(out, "ab") as file:
        file.write(b'{"path": "half a line')  # a kill during a write
    assert list(scanning(assets, out, ScanOptions())) == []  # all recorded: nothing to do
    assert out.read_bytes().endswith(b"}\n") and len(list(lines(out))) == len(files)
    files[1].write_text(files[1].read_text().replace('ixx="1.0"', 'ixx="0.5"'))
    steps = list(scanning(assets, out, ScanOptions()))
    assert [s.current for s in steps] == [str(files[1])]
    again = list(lines(out))
    assert sorted(r["path"] for r in again) == sorted(r["path"] for r in first)
    (edited,) = [r for r in again if r["path"] == str(files[1])]
    assert edited["links"][0]["inertia"][0][0] == 0.5


def test_one_scan_writes_a_record_at_a_time(tmp_path):
    from inertia_kit.errors import InputError

    with (
        Record(tmp_path / "o.jsonl"),
        pytest.raises(InputError, match="another scan"),
        Record(tmp_path / "o.jsonl"),
    ):
        pass


def test_listed_assets_are_counted_under_their_first_folder(tmp_path):
    assets = listed([f"{tmp_path}/lib/x/a.urdf\n", "\n", f"{tmp_path}/lib/y/z/b.urdf\n"])
    assert assets == [
        Asset(f"{tmp_path}/lib/x/a.urdf", "x"),
        Asset(f"{tmp_path}/lib/y/z/b.urdf", "y"),
    ]


# --- the worker pool's limits (module-level work: it is sent to the workers) ----------------


def _work(item: str):
    if item == "sleep":
        time.sleep(60)
    if item == "allocate":
        hoard = []
        while True:
            hoard.append(bytearray(16 << 20))
    if item == "die":
        os.kill(os.getpid(), signal.SIGKILL)
    if item == "raise":
        raise ValueError("a bug")
    return item.upper()


def test_each_item_is_held_to_its_limits_and_the_run_goes_on():
    items = ["a", "sleep", "b", "allocate", "die", "raise", "c"]
    started = time.monotonic()
    outcomes = dict(run_limited(_work, items, 2, Limits(timeout=1.0, memory_mb=200)))
    assert time.monotonic() - started < 20
    statuses = {items[i]: (o.status, o.value) for i, o in outcomes.items()}
    assert statuses == {
        "a": ("done", "A"),
        "sleep": ("timeout", None),
        "b": ("done", "B"),
        "allocate": ("memory", None),
        "die": ("crashed", None),
        "raise": ("crashed", None),
        "c": ("done", "C"),
    }
    assert "signal 9" in outcomes[4].message and "ValueError: a bug" in outcomes[5].message
    assert outcomes[1].wall >= 1.0


# --- summary and keep-list ---------------------------------------------------------------


def record(path, folder, status="findings", *severities, code="IN010"):
    findings = [{"code": code, "name": "n", "severity": s} for s in severities]
    return {"path": path, "folder": folder, "status": status, "findings": findings,
            "wall_seconds": 0.5, "cpu_seconds": 0.25}  # fmt: skip


RECORDS = [
    record("x/1.urdf", "x", "ok"),
    record("x/2.urdf", "x", "findings", "info"),
    record("y/3.urdf", "y", "findings", "warning", "info"),
    record("y/4.urdf", "y", "findings", "error", code="IN023"),
    record("z/5.urdf", "z", "timeout"),
    record("z/6.urdf", "z", "unreadable"),
]


def test_summary_counts_per_rule_severity_folder_and_status():
    summary = summarise(RECORDS, Severity.ERROR)
    assert summary["assets"] == 6
    assert summary["statuses"] == {"findings": 3, "ok": 1, "timeout": 1, "unreadable": 1}
    assert summary["severities"] == {"error": 1, "warning": 1, "info": 2}
    assert summary["rules"] == {
        "IN010": {"name": "n", "info": 2, "warning": 1},
        "IN023": {"name": "n", "error": 1},
    }
    assert summary["folders"]["y"] == {"assets": 2, "findings": 3, "statuses": {"findings": 2}}
    assert summary["folders"]["z"]["statuses"] == {"timeout": 1, "unreadable": 1}
    assert summary["failing"] == 3  # the error, the timeout, the unreadable
    assert summarise(RECORDS, Severity.INFO)["failing"] == 5
    assert summary["asset_seconds"] == 3.0 and summary["cpu_seconds"] == 1.5


@pytest.mark.parametrize(
    "keep_at, kept",
    [
        ("none", ["x/1.urdf"]),
        ("info", ["x/1.urdf", "x/2.urdf"]),
        ("warning", ["x/1.urdf", "x/2.urdf", "y/3.urdf"]),
        ("error", ["x/1.urdf", "x/2.urdf", "y/3.urdf", "y/4.urdf"]),
    ],
)
def test_the_keep_list_holds_linted_assets_whose_worst_finding_is_at_most(keep_at, kept, tmp_path):
    assert [r["path"] for r in RECORDS if keeps(r, keep_at)] == kept
    assert write_keep_list(iter(RECORDS), keep_at, tmp_path / "keep.txt") == len(kept)
    assert (tmp_path / "keep.txt").read_text().splitlines() == kept


def test_the_summary_of_20000_lines_streams_in_flat_memory(tmp_path):
    out = tmp_path / "big.jsonl"
    finding = {"code": "IN010", "name": "inertia-not-positive-definite", "severity": "error",
               "message": "link `l`: " + "x" * 400}  # fmt: skip
    with open(out, "wb") as file:
        for n in range(20_000):
            line = {**record(f"f{n % 7}/{n}.urdf", f"f{n % 7}"), "findings": [finding] * 3}
            file.write(encode(line))
    size = out.stat().st_size
    tracemalloc.start()
    summary = summarise(lines(out), Severity.ERROR)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    assert summary["assets"] == 20_000 and summary["rules"]["IN010"]["error"] == 60_000
    assert size > 20_000_000 and peak < size / 100, (peak, size)


def test_measured_fields_are_the_only_ones_that_vary(tmp_path):
    small_robots(tmp_path / "lib")
    assets = walked([tmp_path / "lib"])
    one = scan_all(assets, tmp_path / "one.jsonl", jobs=1)
    two = scan_all(assets, tmp_path / "two.jsonl", jobs=2)

    def stable(records):
        return sorted(
            json.dumps({k: v for k, v in r.items() if k not in MEASURED}) for r in records
        )

    assert stable(one) == stable(two)
