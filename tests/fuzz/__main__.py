"""
``python -m fuzz`` (with ``tests`` on the path: ``PYTHONPATH=.:tests``): a fuzz campaign of
``--inputs`` inputs (default ``$INERTIA_KIT_FUZZ_INPUTS``, else 1000) of ``--seed`` (default
``$INERTIA_KIT_FUZZ_SEED``, else 0) in ``--workers`` processes; the summary on stdout, it and
the reproducers in ``--out``. Exit 1 when a failure outside the known-open classes was found.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from dataclasses import replace
from pathlib import Path

if __package__ in (None, ""):  # `python tests/fuzz`: the harness's own folder is on the path
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
    __package__ = "fuzz"

from fuzz.campaign import CI, LONG, run_campaign
from fuzz.known import known_open
from fuzz.tree import Tree


def _indices(text: str) -> list[int]:
    found = []
    for part in text.split(","):
        low, _, high = part.partition("-")
        found += range(int(low), int(high or low) + 1)
    return found


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m fuzz",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument(
        "--inputs", type=int, default=int(os.environ.get("INERTIA_KIT_FUZZ_INPUTS") or 1000)
    )
    parser.add_argument("--seed", default=os.environ.get("INERTIA_KIT_FUZZ_SEED") or "0")
    parser.add_argument("--first", type=int, default=0, help="the first input's index")
    parser.add_argument("--only", help="these inputs only: 12,40-45")
    parser.add_argument("--workers", type=int, default=len(os.sched_getaffinity(0)))
    parser.add_argument("--profile", choices=["long", "ci"], default="long")
    parser.add_argument("--timeout", type=float, help="seconds a run may take [60]")
    parser.add_argument("--memory-mb", type=int, help="peak memory a run may use [1024]")
    parser.add_argument("--no-shrink", action="store_true")
    parser.add_argument("--out", type=Path, default=Path("fuzz-results"))
    parser.add_argument(
        "--materialise",
        nargs=2,
        metavar=("INPUT_JSON", "FOLDER"),
        help="rebuild a reproducer's tree and exit",
    )
    args = parser.parse_args(argv)
    if args.materialise:
        Tree.from_json(json.loads(Path(args.materialise[0]).read_text())).materialise(
            Path(args.materialise[1])
        )
        return 0
    profile = CI if args.profile == "ci" else LONG
    limits = profile.limits
    if args.timeout:
        limits = replace(limits, seconds=args.timeout)
    if args.memory_mb:
        limits = replace(limits, memory_mb=args.memory_mb)
    profile = replace(
        profile,
        limits=limits,
        shrink_seconds=0.0 if args.no_shrink else profile.shrink_seconds or 60.0,
    )
    indices = (
        _indices(args.only) if args.only else list(range(args.first, args.first + args.inputs))
    )
    summary = run_campaign(
        args.seed, indices, profile, workers=args.workers, out=args.out, progress=True
    )
    print(summary.text(known_open))
    unexpected = [s for s in summary.signatures if not known_open(s)]
    return 1 if unexpected else 0


if __name__ == "__main__":
    sys.exit(main())
