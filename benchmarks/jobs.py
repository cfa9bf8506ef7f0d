"""
``inertia-lint -j 1`` against ``-j 2`` on 600 files, and memory in the number of files.

    python benchmarks/jobs.py             # best of 3 runs each
    python benchmarks/jobs.py --runs 5    # steadier on a busy machine

The corpus: 50 copies of ``examples/`` (12 robot files each: 600 files, 300 robots and their
xacro fragments, meshes included) in a temporary folder, with its own mesh cache
(``INERTIA_KIT_CACHE_DIR``), warmed by one untimed run first. Each run is the
``inertia-lint`` console script next to this Python, as a subprocess, stdout kept to compare.

Printed, each measured in this one run:

- wall time of ``-j 1`` and ``-j 2`` on the 600 files (best of N) and their ratio (target
  ≥ 1.7× on two cores);
- peak RSS of ``inertia-lint -j 1`` on 150 files (12 whole copies and the 6 files of a 13th
  copy's ``my_robot_description``, so that no robot is split from its fragments) and on 600
  files, and their ratio (target ≤ 1.2: memory flat in the number of files). Each is read
  with ``getrusage(RUSAGE_CHILDREN)`` in a fresh Python that runs only that command, since
  the figure is the largest of all children a process ever waited for;
- the CPU time (user + system) of ``-j 1``, its xacro children included, as a share of its
  wall time: well under 1, other jobs keep the machine busy, and ``-j 2`` cannot have two free
  cores either (the workers' CPU time is not measured: they are the forkserver's children,
  which nobody waits for);
- whether ``-j 2``'s stdout, stderr and exit code are byte-identical to ``-j 1``'s, for the
  ``full`` and ``json`` formats.
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
COPIES = 50
SPEED_UP = 1.7
FLAT = 1.2


def script() -> str:
    found = Path(sys.executable).with_name("inertia-lint")
    return str(found) if found.exists() else "inertia-lint"


def corpus(folder: Path, copies: int) -> list[Path]:
    """``copies`` copies of the examples under ``folder``; the copies' folders."""
    made = []
    for number in range(copies):
        target = folder / f"copy{number:02d}"
        shutil.copytree(EXAMPLES, target)
        made.append(target)
    return made


def robot_files(folder: Path) -> list[Path]:
    return sorted(p for p in folder.rglob("*") if p.suffix.lower() in (".urdf", ".xacro"))


#: CPU seconds (user + system) of each -j 1 run and its xacro children
CPU: list[float] = []


def children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run(arguments: list[str], env: dict[str, str]) -> tuple[float, subprocess.CompletedProcess]:
    start, cpu = time.perf_counter(), children_cpu()
    done = subprocess.run([script(), *arguments], capture_output=True, env=env, check=False)
    elapsed = time.perf_counter() - start
    if arguments[:2] == ["-j", "1"]:
        CPU.append(children_cpu() - cpu)
    if done.returncode not in (0, 1):
        sys.exit(f"inertia-lint {' '.join(arguments)} exited {done.returncode}:\n{done.stderr}")
    return elapsed, done


def peak_rss_mb(arguments: list[str], env: dict[str, str]) -> float:
    """Peak RSS of one ``inertia-lint`` run, from a Python that runs nothing else."""
    probe = (
        "import resource, subprocess, sys;"
        "subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL);"
        "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)"
    )
    out = subprocess.run(
        [sys.executable, "-c", probe, script(), *arguments],
        capture_output=True,
        text=True,
        env=env,
        check=True,
    )
    return int(out.stdout) / 1024  # Linux: kilobytes


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=3, help="timed runs of each (best kept)")
    options = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="inertia-jobs-") as tmp:
        folder = Path(tmp)
        copies = corpus(folder / "corpus", COPIES)
        files = robot_files(folder / "corpus")
        env = {**os.environ, "INERTIA_KIT_CACHE_DIR": str(folder / "cache")}
        env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT), env.get("PYTHONPATH")]))
        everything = [str(folder / "corpus")]
        run(["-q", "-j", "1", *everything], env)  # warms the mesh cache and the page cache
        times: dict[str, list[float]] = {"1": [], "2": []}
        outputs = {}
        for _ in range(options.runs):
            for jobs in ("1", "2"):
                elapsed, done = run(["-j", jobs, *everything], env)
                times[jobs].append(elapsed)
                outputs[jobs] = (done.returncode, done.stdout, done.stderr)
        same = outputs["1"] == outputs["2"]
        json_runs = [run(["-j", j, "--output-format", "json", *everything], env)[1] for j in "12"]
        same_json = json_runs[0].stdout == json_runs[1].stdout
        quarter = [str(c) for c in copies[:12]]
        quarter.append(str(copies[12] / "my_robot_description"))
        quarter_files = sum(len(robot_files(Path(p))) for p in quarter)
        small = peak_rss_mb(["-q", "-j", "1", *quarter], env)
        large = peak_rss_mb(["-q", "-j", "1", *everything], env)
    one, two = min(times["1"]), min(times["2"])
    print(f"corpus: {len(files)} files ({COPIES} copies of examples/), {os.cpu_count()} CPUs")
    print(f"-j 1: {one:6.2f} s  (runs: {', '.join(f'{t:.2f}' for t in times['1'])})")
    print(f"-j 2: {two:6.2f} s  (runs: {', '.join(f'{t:.2f}' for t in times['2'])})")
    share = min(CPU) / one
    print(f"-j 1 CPU: {min(CPU):.2f} s, {share:.2f} of a core over its best wall time")
    verdict = "PASS" if one / two >= SPEED_UP else "FAIL"
    print(f"speed-up -j 2 / -j 1: {one / two:.2f}x  (target >= {SPEED_UP}x)  {verdict}")
    flat = "PASS" if large / small <= FLAT else "FAIL"
    print(f"peak RSS -j 1: {quarter_files} files {small:.1f} MB, {len(files)} files {large:.1f} MB")
    ratio = large / small
    print(f"RSS ratio {len(files)} / {quarter_files} files: {ratio:.2f}  (<= {FLAT}) {flat}")
    print(f"-j 2 output byte-identical to -j 1: full {same}, json {same_json}")
    return 0 if verdict == flat == "PASS" and same and same_json else 1


if __name__ == "__main__":
    sys.exit(main())
