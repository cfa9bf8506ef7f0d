"""
Asset libraries: the marginal CPU time of one more small object, against ``python -c pass``.

    python benchmarks/asset_library.py             # median of 3 paired runs
    python benchmarks/asset_library.py --runs 5    # steadier on a busy machine

The corpus is pybullet's 1000 single-link object URDFs (``pybullet_data/random_urdfs``: one
OBJ mesh each, an isotropic placeholder tensor; ``pip install pybullet``). Each run is the
``inertia-lint`` console script next to this Python, ``-j 1``, with the mesh cache off
(``INERTIA_KIT_NO_CACHE=1``: what a fresh CI runner sees), on the first 100 objects and on all
1000; the marginal CPU per file is ``(cpu(1000) - cpu(100)) / 900``, user + system time of the
child. Printed, each measured in this one run (runs alternate, so a busy minute hits all):

- ``python -c pass``'s CPU time (median);
- per output format (``concise``, ``json``): the CPU of 100 and of 1000 files, the marginal CPU
  per file, and its ratio to ``python -c pass`` (issue 23's target: ≤ 0.2);
- whether every run of a format printed the same bytes.
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import resource
import statistics
import subprocess
import sys
from pathlib import Path

TARGET = 0.2
FORMATS = ("concise", "json")


def script() -> str:
    found = Path(sys.executable).with_name("inertia-lint")
    return str(found) if found.exists() else "inertia-lint"


def objects() -> list[Path]:
    spec = importlib.util.find_spec("pybullet_data")
    if spec is None or not spec.submodule_search_locations:
        sys.exit("needs pybullet's data: pip install pybullet")
    root = Path(next(iter(spec.submodule_search_locations))) / "random_urdfs"
    return sorted(root.glob("*/*.urdf"))


def cpu_of(command: list[str], env: dict[str, str]) -> tuple[float, bytes]:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = subprocess.run(command, capture_output=True, env=env, check=False)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode not in (0, 1):
        sys.exit(f"{' '.join(command[:6])} ...: exit {done.returncode}\n{done.stderr.decode()}")
    spent = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return spent, done.stdout


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=3)
    runs = parser.parse_args().runs
    files = [str(p) for p in objects()]
    if len(files) < 1000:
        sys.exit(f"expected pybullet's 1000 objects, found {len(files)}")
    env = {**os.environ, "INERTIA_KIT_NO_CACHE": "1", "OPENBLAS_NUM_THREADS": "1"}
    few, all_ = files[:100], files[:1000]
    base = [sys.executable, "-c", "pass"]
    times: dict[str, list[float]] = {"pass": []}
    outputs: dict[str, set[bytes]] = {}
    for _ in range(runs):
        times["pass"].append(cpu_of(base, env)[0])
        for form in FORMATS:
            for name, chosen in (("few", few), ("all", all_)):
                command = [script(), "-j", "1", "-q", "--exit-zero", "--output-format", form]
                spent, out = cpu_of([*command, *chosen], env)
                times.setdefault(f"{form}-{name}", []).append(spent)
                outputs.setdefault(f"{form}-{name}", set()).add(out)
    python = statistics.median(times["pass"])
    print(f"python -c pass: {python * 1e3:.1f} ms CPU (median of {runs})")
    print(
        f"{'format':10} {'100 files':>10} {'1000 files':>11} {'per file':>9} {'ratio':>7}"
        "  same output"
    )
    for form in FORMATS:
        low = statistics.median(times[f"{form}-few"])
        high = statistics.median(times[f"{form}-all"])
        marginal = (high - low) / 900
        same = all(len(outputs[f"{form}-{n}"]) == 1 for n in ("few", "all"))
        verdict = "PASS" if marginal / python <= TARGET else "over"
        print(
            f"{form:10} {low:9.2f}s {high:10.2f}s {marginal * 1e3:7.2f}ms {marginal / python:7.2f}"
            f"  {same}  ({verdict}: target ≤ {TARGET})"
        )


if __name__ == "__main__":
    main()
