"""
Memory flat in the number of files: the peak memory of ``inertia-lint`` over 2000 files against
200, per output format, as ratios measured in one run (issue 23's target: at most 1.5).

    python benchmarks/output_memory.py                       # every format, 200 and 2000 files
    python benchmarks/output_memory.py --formats json sarif  # some of them
    python benchmarks/output_memory.py --sizes 200 20000     # other sizes

The files are ``tests/kit/assets.py``'s asset library, generated in a temporary folder: small
robots in ten folders, a third with a binary STL mesh, a third with a wrong tensor (a finding
each, with its fix). Each case runs the ``inertia-lint`` console script next to this Python,
``-j 1`` (the parent is what holds a run's results), the mesh cache off, stdout discarded,
inside a small Python wrapper whose ``RUSAGE_CHILDREN`` maximum resident set size is the run's
peak. Printed: each format's peak at each size and their ratio.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from kit.assets import asset_library  # noqa: E402

TARGET = 1.5
FORMATS = ("json", "sarif", "junit", "gitlab", "github", "concise", "full")
#: run in a fresh interpreter: its children's peak is the lint run's alone
PEAK = (
    "import resource, subprocess, sys\n"
    "subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, check=False)\n"
    "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n"
)


def script() -> str:
    found = Path(sys.executable).with_name("inertia-lint")
    return str(found) if found.exists() else "inertia-lint"


def peak_mb(form: str, folder: Path) -> float:
    command = [script(), "-j", "1", "-q", "--exit-zero", "--output-format", form, str(folder)]
    env = {**os.environ, "INERTIA_KIT_NO_CACHE": "1", "OPENBLAS_NUM_THREADS": "1"}
    done = subprocess.run(
        [sys.executable, "-c", PEAK, *command], capture_output=True, text=True, env=env, check=True
    )
    return int(done.stdout.split()[-1]) / 1024  # Linux: kilobytes


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--formats", nargs="+", default=FORMATS, choices=FORMATS)
    parser.add_argument("--sizes", nargs=2, type=int, default=(200, 2000))
    options = parser.parse_args()
    small, large = options.sizes
    with tempfile.TemporaryDirectory() as temporary:
        folders = {n: asset_library(Path(temporary) / str(n), n) for n in (small, large)}
        print(f"{'format':8} {small:>7} files {large:>7} files   ratio")
        for form in options.formats:
            low, high = (peak_mb(form, folders[n]) for n in (small, large))
            verdict = "PASS" if high / low <= TARGET else "over"
            print(
                f"{form:8} {low:10.1f} MB {high:10.1f} MB  {high / low:6.2f}"
                f"  ({verdict}: target ≤ {TARGET})",
                flush=True,
            )


if __name__ == "__main__":
    main()
