"""
Every command linear in the number of links: each command run on robots of 1000 and of 5000
links, a serial chain and a star, as URDF and as xacro (a macro called once per link), and the
ratio of their CPU times (linear: about 5; quadratic: about 25).

    python benchmarks/scaling.py                       # every command, shape and format
    python benchmarks/scaling.py --commands lint fill   # some of them (names below)
    python benchmarks/scaling.py --sizes 500 2500       # other sizes (the ratio to expect: 5)

The robots (``tests/kit/big.py``; one in three links with a placeholder tensor, one in three
without ``<inertial>``) are generated in a temporary folder, and commands that write run on a
fresh copy. Each case runs the command in a child process (``python -c``, the console entry
point) and reports its user + system CPU time, which a busy machine disturbs less than wall
time; xacro runs use ``--xacro-limit elements=200000`` (15 elements a link: 5000 links pass
the default of 50 000 elements only in a leaner robot).
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
sys.path.insert(0, str(ROOT / "tests"))

from kit.big import SHAPES, XACRO_ELEMENTS, urdf, xacro  # noqa: E402

#: name -> (entry point, arguments before the file, whether it writes the file)
COMMANDS: dict[str, tuple[str, list[str], bool]] = {
    "lint": ("lint_main", ["--output-format", "full"], False),
    "lint-concise": ("lint_main", ["--output-format", "concise"], False),
    "lint-json": ("lint_main", ["--output-format", "json"], False),
    "lint-github": ("lint_main", ["--output-format", "github"], False),
    "lint-sarif": ("lint_main", ["--output-format", "sarif"], False),
    "lint-junit": ("lint_main", ["--output-format", "junit"], False),
    "lint-gitlab": ("lint_main", ["--output-format", "gitlab"], False),
    "lint-statistics": ("lint_main", ["--statistics"], False),
    "lint-engine-all": ("lint_main", ["--engine", "all", "--output-format", "concise"], False),
    "lint-fix": ("lint_main", ["--fix", "--output-format", "concise"], True),
    "lint-unsafe-fixes": ("lint_main", ["--fix", "--unsafe-fixes", "-q"], True),
    "lint-diff": ("lint_main", ["--diff", "--unsafe-fixes"], False),
    "lint-add-noqa": ("lint_main", ["--add-noqa"], True),
    "fill": ("fill_main", ["--fix", "all"], True),
    "fill-diff": ("fill_main", ["--diff"], False),
    "report": ("main", ["report"], False),
    "report-lumped": ("main", ["report", "--lumped"], False),
    "view": ("main", ["view", "-o", "{folder}/page.html"], False),
}


def cpu_seconds(command: list[str], cwd: Path) -> tuple[float, int]:
    """The user + system CPU time of ``command`` run to its end, and its exit code."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    result = subprocess.run(command, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if result.returncode not in (0, 1):
        sys.exit(f"{' '.join(command)} exited {result.returncode}: {result.stderr.decode()}")
    spent = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return spent, result.returncode


def run_case(name: str, robot: Path, folder: Path) -> float:
    entry, arguments, writes = COMMANDS[name]
    target = robot
    if writes:
        target = folder / f"copy-{robot.name}"
        shutil.copyfile(robot, target)
    arguments = [a.format(folder=folder) for a in arguments]
    if robot.suffix == ".xacro":
        arguments += ["--xacro-limit", f"elements={XACRO_ELEMENTS}"]
    code = f"import sys; from inertia_kit.cli import {entry}; sys.exit({entry}())"
    seconds, _ = cpu_seconds([sys.executable, "-c", code, *arguments, str(target)], folder)
    return seconds


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--commands", nargs="+", choices=sorted(COMMANDS), default=list(COMMANDS))
    parser.add_argument("--sizes", nargs=2, type=int, default=[1000, 5000])
    parser.add_argument("--shapes", nargs="+", choices=SHAPES, default=list(SHAPES))
    kinds = ["urdf", "xacro"]
    parser.add_argument("--formats", nargs="+", choices=kinds, default=kinds)
    options = parser.parse_args()
    small, large = options.sizes
    print(f"CPU seconds (user + system) at {small} and {large} links, and their ratio")
    print(f"(linear: {large / small:.3g}); Python {sys.version.split()[0]}, {os.cpu_count()} CPUs")
    print(f"{'command':<20} {'robot':<12} {small:>8} {large:>8} {'ratio':>6}")
    worst = 0.0
    started = time.monotonic()
    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(scratch)
        robots = {}
        for shape in options.shapes:
            for kind in options.formats:
                make = urdf if kind == "urdf" else xacro
                for size in (small, large):
                    path = folder / f"{shape}{size}.{kind}"
                    path.write_text(make(size, shape))
                    robots[shape, kind, size] = path
        for name in options.commands:
            for shape in options.shapes:
                for kind in options.formats:
                    times = [run_case(name, robots[shape, kind, n], folder) for n in (small, large)]
                    ratio = times[1] / times[0]
                    worst = max(worst, ratio)
                    robot = f"{shape} {kind}"
                    print(f"{name:<20} {robot:<12} {times[0]:8.2f} {times[1]:8.2f} {ratio:6.2f}")
                    sys.stdout.flush()
    spent = time.monotonic() - started
    print(f"largest ratio {worst:.2f} (linear: {large / small:.3g}); {spent:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
