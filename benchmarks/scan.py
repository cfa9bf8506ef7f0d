"""
Issue 23's dataset-mode acceptance, measured in one run: ``inertia-kit scan`` killed at random
moments and resumed, runaway assets cut at their limits, memory in the number of assets, and
the same assets on a local Dask cluster.

    python benchmarks/scan.py                          # 2000 assets, 10 kills (~4 min)
    python benchmarks/scan.py --assets 400 --kills 4   # a quicker look
    python benchmarks/scan.py --no-dask                # without the Dask case

The library is ``tests/kit/assets.py``'s, generated in a temporary folder: small robots in ten
folders, a third with a binary STL mesh, a third with a wrong tensor. Every scan runs the
``inertia-kit`` console script next to this Python, ``-j 2``, ``-q``. Printed, with the
targets:

1. **uninterrupted**: one scan to the end; its time and rate. Every asset has one line.
2. **killed**: the same scan into another record, killed with SIGKILL (the parent; its workers
   die with it) at a random moment, ``--kills`` times (the moments seeded: ``--seed``; each
   once the run has recorded a random number of new lines, so that it lands mid-run), then run
   to the end: every kill mid-run, every asset recorded exactly once, and the lines the
   uninterrupted ones, apart from the measured fields (``lint.scan.MEASURED``: wall and CPU
   time, peak memory).
3. **runaway**: the library's first 20 assets with two runaway xacro files beside them
   (``tests/kit/runaway_xacro.py``): a doubling chain of 2**22 links, which loops, and a link
   named ``${'x'*10**10}``, a 10 GB string, which allocates; with xacro's own limits raised
   out of the way, the scan's ``--timeout 3 --max-memory 500`` cut them: the chain recorded
   ``timeout``, the string ``unreadable`` at once, its expansion refused the memory its
   worker's limit leaves (the message says so), and the run goes on: every other asset
   linted.
4. **memory**: the largest resident set of any of the scan's processes (a wrapper's
   ``RUSAGE_CHILDREN`` maximum) over a tenth of the library and over all of it; target: at
   most 1.5 times.
5. **Dask**: ``--dask local -j 2`` (a ``LocalCluster`` of two worker processes, the
   ``[dask]`` extra) over the same library: the same lines as the local scan, apart from the
   measured fields. Skipped, saying so, without Dask's ``distributed``.
"""

from __future__ import annotations

import argparse
import json
import os
import random
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from kit import write  # noqa: E402
from kit.assets import asset_library  # noqa: E402
from kit.runaway_xacro import HUGE_STRING, doubling_chain, expression_robot  # noqa: E402
from lint import console_script  # noqa: E402
from output_memory import PEAK  # noqa: E402  (a wrapper: its children's peak, in kB)

from inertia_kit.lint.scan import MEASURED  # noqa: E402

MEMORY_TARGET = 1.5
#: xacro's own limits out of the way, so that the scan's --timeout and --max-memory decide
RAISED = ["--xacro-limit", "timeout=600,memory=100000,elements=1000000000"]


def scan_command(record: Path, *paths: Path | str, extra: tuple[str, ...] = ()) -> list[str]:
    return [console_script("inertia-kit"), "scan", "-q", "-j", "2", "-o", str(record), *extra] + [
        str(p) for p in paths
    ]


def environment() -> dict[str, str]:
    # each run its own cache, as on a fresh CI runner: the assets are meshed alike either way
    return {**os.environ, "INERTIA_KIT_NO_CACHE": "1", "OPENBLAS_NUM_THREADS": "1"}


def run(command: list[str]) -> tuple[float, int]:
    started = time.monotonic()
    done = subprocess.run(
        command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=environment()
    )
    return time.monotonic() - started, done.returncode


def lines(record: Path) -> int:
    """Complete lines (a kill may leave a partial one after them)."""
    return record.read_bytes().count(b"\n") if record.exists() else 0


def records(record: Path) -> list[dict]:
    return [json.loads(line) for line in record.read_text(encoding="utf-8").splitlines()]


def stable(found: list[dict]) -> list[str]:
    """The lines without their measured fields, sorted: what two runs must agree on."""
    return sorted(
        json.dumps({k: v for k, v in r.items() if k not in MEASURED}, sort_keys=True) for r in found
    )


def killed(library: Path, record: Path, assets: int, kills: int, seed: int) -> list[int]:
    """The record's complete lines at each kill. Each kill waits for a random number of new
    lines (up to twice an even share of what is left), so every one lands mid-run however fast
    the machine is."""
    chance = random.Random(seed)
    counts: list[int] = []
    for left in range(kills, 0, -1):
        before = lines(record)
        share = max(1, min(2 * (assets - before) // (left + 1), assets - before - 1))
        target = before + chance.randint(1, share)
        process = subprocess.Popen(
            scan_command(record, library),
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            env=environment(),
        )
        deadline = time.monotonic() + 300
        while lines(record) < target and process.poll() is None and time.monotonic() < deadline:
            time.sleep(0.002)
        process.send_signal(signal.SIGKILL)
        process.wait()
        counts.append(lines(record))
    return counts


def peak_mb(library: Path, record: Path) -> float:
    done = subprocess.run(
        [sys.executable, "-c", PEAK, *scan_command(record, library)],
        capture_output=True,
        text=True,
        env=environment(),
        check=True,
    )
    return int(done.stdout.split()[-1]) / 1024


def runaway_case(scratch: Path, library: Path) -> tuple[bool, str]:
    folder = scratch / "runaway"
    for path in sorted(library.rglob("*.urdf"))[:20]:
        target = folder / path.relative_to(library)
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(path.read_bytes())
    (folder / "meshes").mkdir(exist_ok=True)
    (folder / "meshes" / "box.stl").write_bytes((library / "meshes" / "box.stl").read_bytes())
    write(folder / "runaway" / "chain.xacro", doubling_chain(22))
    write(folder / "runaway" / "string.xacro", expression_robot(HUGE_STRING))
    record = scratch / "runaway.jsonl"
    extra = ("--timeout", "3", "--max-memory", "500", *RAISED)
    seconds, _ = run(scan_command(record, folder, extra=extra))
    found = records(record)
    status = {Path(r["path"]).name: r["status"] for r in found}
    cut = {name: status.get(name) for name in ("chain.xacro", "string.xacro")}
    others = {s for name, s in status.items() if name not in cut}
    said = next(r.get("error") or "" for r in found if Path(r["path"]).name == "string.xacro")
    held = "MB this process may still take" in said
    ok = cut == {"chain.xacro": "timeout", "string.xacro": "unreadable"} and held
    ok &= others <= {"ok", "findings"}
    return ok, (
        f"chain.xacro {cut['chain.xacro']}, string.xacro {cut['string.xacro']} "
        f"({'held to the worker limit' if held else said[:80]}), the other "
        f"{len(status) - 2} {'/'.join(sorted(others))}, in {seconds:.1f} s"
    )


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--assets", type=int, default=2000)
    parser.add_argument("--kills", type=int, default=10)
    parser.add_argument("--seed", type=int, default=7)
    parser.add_argument("--no-dask", action="store_true", help="skip the Dask case")
    options = parser.parse_args()
    results: list[tuple[str, str, bool | None]] = []
    with tempfile.TemporaryDirectory(prefix="inertia-kit-scan-") as name:
        scratch = Path(name)
        library = asset_library(scratch / "library", options.assets)
        tenth = asset_library(scratch / "tenth", max(1, options.assets // 10))

        seconds, code = run(scan_command(scratch / "whole.jsonl", library))
        whole = records(scratch / "whole.jsonl")
        paths = {r["path"] for r in whole}
        results.append(
            (
                "uninterrupted",
                f"{len(whole)} lines, {len(paths)} assets in {seconds:.1f} s "
                f"({len(whole) / seconds:.0f} assets/s), exit {code}",
                len(whole) == len(paths) == options.assets,
            )
        )

        record = scratch / "killed.jsonl"
        counts = killed(library, record, options.assets, options.kills, options.seed)
        seconds, _ = run(scan_command(record, library))
        resumed = records(record)
        once = len(resumed) == len({r["path"] for r in resumed}) == options.assets
        same = stable(resumed) == stable(whole)
        results.append(
            (
                f"killed {options.kills} times",
                f"lines at the kills {counts}; the last run {seconds:.1f} s: "
                f"{len(resumed)} lines, each asset once: {once}, as uninterrupted: {same}",
                once and same and all(0 < c < options.assets for c in counts),
            )
        )

        ok, text = runaway_case(scratch, library)
        results.append(("runaway assets", text, ok))

        small = peak_mb(tenth, scratch / "tenth.jsonl")
        large = peak_mb(library, scratch / "memory.jsonl")
        results.append(
            (
                "memory",
                f"peak {small:.1f} MB for {max(1, options.assets // 10)} assets, {large:.1f} MB "
                f"for {options.assets}: {large / small:.2f}x (target <= {MEMORY_TARGET:g}x)",
                large / small <= MEMORY_TARGET,
            )
        )

        if options.no_dask:
            results.append(("Dask LocalCluster", "skipped (--no-dask)", None))
        else:
            try:
                import distributed  # noqa: F401
            except ImportError:
                results.append(("Dask LocalCluster", "skipped: pip install '.[dask]'", None))
            else:
                dasked = scratch / "dask.jsonl"
                extra = ("--dask", "local")
                seconds, code = run(scan_command(dasked, library, extra=extra))
                found = records(dasked) if dasked.exists() else []
                same = stable(found) == stable(whole)
                results.append(
                    (
                        "Dask LocalCluster, 2 workers",
                        f"{len(found)} lines in {seconds:.1f} s, exit {code}; "
                        f"as the local scan: {same}",
                        same,
                    )
                )

    print(f"inertia-kit scan, -j 2, {options.assets} generated assets (tests/kit/assets.py)")
    for case, text, passed in results:
        verdict = "" if passed is None else ("PASS" if passed else "FAIL")
        print(f"{case:<30} {verdict:<5} {text}")
    failed = any(passed is False for _, _, passed in results)
    print("FAIL" if failed else "PASS")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
