"""
Two writers at once on one robot file: for every pair of writers (``inertia-fill``,
``inertia-fill --fix all``, ``inertia-lint --fix``, ``inertia-lint --fix --unsafe-fixes``,
``inertia-lint --add-noqa``; each with itself too), on a URDF robot and on a xacro robot whose
included fragment both edit, N runs as two real processes, the second started at an offset
spread over one writer's run time (so that they overlap in every phase). Prints per pair: runs,
distinct final states, runs where a writer refused (exit 2, "the file changed while it was being
processed"), whether every final state is one the two give run one after the other, and whether
every file parses (:mod:`kit.concurrency` says how the states are judged).

    PYTHONPATH=$PWD python benchmarks/concurrency.py                 # 50 runs per pair
    INERTIA_KIT_CONCURRENCY_RUNS=5 PYTHONPATH=$PWD python benchmarks/concurrency.py
    PYTHONPATH=$PWD python benchmarks/concurrency.py --runs 20 --projects xacro \\
        --writers fill,lint-unsafe
    PYTHONPATH=$PWD python benchmarks/concurrency.py --runs 10 \\
        --real SHARE/example-robot-data/robots/panda_description urdf/panda.urdf \\
        --package-path SHARE

``--real FOLDER ROBOT`` runs on a copy of a real package instead (its robot files copied, the
rest linked; never the original), with the writers that change it.

Exits 1 when a run ended in a state no sequential order gives, or a file that does not parse.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "tests"))

from kit.concurrency import (  # noqa: E402
    HEADER,
    PROJECTS,
    WRITERS,
    PairReport,
    Project,
    changing,
    harness,
)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--runs",
        type=int,
        default=int(os.environ.get("INERTIA_KIT_CONCURRENCY_RUNS") or 50),
        help="runs per pair [default: $INERTIA_KIT_CONCURRENCY_RUNS, else 50]",
    )
    parser.add_argument("--projects", default=",".join(PROJECTS), help="urdf,xacro")
    parser.add_argument("--writers", default=",".join(WRITERS), help=",".join(WRITERS))
    parser.add_argument(
        "--spread", type=float, default=None, help="largest start offset, s [default: one run]"
    )
    parser.add_argument("--seed", type=int, default=19)
    parser.add_argument(
        "--real",
        nargs=2,
        action="append",
        default=[],
        metavar=("FOLDER", "ROBOT"),
        help="a real package and its robot file (relative to it), instead of the projects",
    )
    parser.add_argument("--package-path", action="append", default=[], help="for --real")
    args = parser.parse_args()
    print(f"{args.runs} runs per pair; python {sys.version.split()[0]}; {os.cpu_count()} cores")
    started = time.monotonic()
    failed = False

    def told(report: PairReport) -> None:
        nonlocal failed
        print(report.row(), flush=True)
        for run in report.runs:
            if not (run.sequential and run.parses):
                failed = True
                print(f"    {run.told()}", flush=True)

    writers = args.writers.split(",")
    projects: list = args.projects.split(",")
    if args.real:
        import tempfile

        options = tuple(f"--package-path={Path(p).resolve()}" for p in args.package_path)
        projects = []
        for folder, robot in args.real:
            real = Project.from_folder(Path(folder).resolve(), robot, options)
            with tempfile.TemporaryDirectory() as scratch:
                chosen = changing(real, writers, Path(scratch))
            print(f"{real.name}: {robot}, the writers that change it: {', '.join(chosen)}")
            projects.append(real)
        writers = chosen if len(args.real) == 1 else writers
    print(HEADER, flush=True)
    harness(
        args.runs,
        projects=projects,
        writers=writers,
        spread=args.spread,
        told=told,
        seed=args.seed,
    )
    print(f"{time.monotonic() - started:.0f} s")
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main())
