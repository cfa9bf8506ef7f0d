"""
Findings on the real robots of the installed PyPI robot packages, counted per package, rule and
severity; ``--save`` keeps every finding, ``--against`` prints what changed since a saved run::

    python benchmarks/real_robots.py --save before.json          # on the old code
    python benchmarks/real_robots.py --against before.json       # on the new: counts and changes

Each package folder is linted as a user would (``inertia-lint --output-format json -j 2
--package-path FOLDER FOLDER``), with this interpreter: run it with the one that has the
packages (``pip install --no-deps example-robot-data pybullet rtb-data dexmate-urdf
fourier-robot-descriptions airo-models``). A package that is not installed is left out, saying so.
"""

from __future__ import annotations

import argparse
import importlib.metadata
import importlib.util
import json
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

#: name -> (how to find its data folder: a module's folder, or a distribution's relative folder)
PACKAGES = {
    "pybullet": ("module", "pybullet_data"),
    "rtb-data": ("module", "rtbdata"),
    "example-robot-data": ("distribution", "cmeel.prefix/share/example-robot-data"),
    "dexmate-urdf": ("module", "dexmate_urdf"),
    "fourier-robot-descriptions": ("module", "fourier_robot_descriptions"),
    "airo-models": ("module", "airo_models"),
}

_LINT = "import sys; from inertia_kit.cli import lint_main; sys.exit(lint_main())"


def package_folder(package: str) -> Path | None:
    kind, name = PACKAGES[package]
    if kind == "module":
        spec = importlib.util.find_spec(name)
        if spec is None or not spec.submodule_search_locations:
            return None
        return Path(next(iter(spec.submodule_search_locations)))
    distribution = "example-robot-data" if package == "example-robot-data" else package
    try:
        folder = Path(importlib.metadata.distribution(distribution).locate_file(name))
    except importlib.metadata.PackageNotFoundError:
        return None
    return folder if folder.is_dir() else None


def lint(folder: Path, extra: list[str]) -> list[dict]:
    command = [sys.executable, "-c", _LINT, "--output-format", "json", "--exit-zero", "-q"]
    command += ["-j", "2", "--package-path", str(folder), *extra, str(folder)]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode not in (0, 1):
        print(done.stderr[-2000:], file=sys.stderr)
    return json.loads(done.stdout or "[]")


def key(package: str, finding: dict) -> tuple:
    # a finding on no link (a twin pair blaming neither) is told apart by its line
    place = finding["link"] or finding["joint"] or f"line {finding['line']}"
    return (package, finding["file"], place, finding["code"])


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--save", type=Path, help="write every finding to this JSON file")
    parser.add_argument("--against", type=Path, help="a saved run: print what changed")
    parser.add_argument("--only", action="append", help="this package only (repeatable)")
    parser.add_argument("lint_options", nargs="*", help="more inertia-lint options, after --")
    args = parser.parse_args()
    found: dict[str, list[dict]] = {}
    for package in args.only or PACKAGES:
        folder = package_folder(package)
        if folder is None:
            print(f"{package}: not installed, left out", file=sys.stderr)
            continue
        began = time.monotonic()
        found[package] = lint(folder, args.lint_options)
        print(f"{package}: {len(found[package])} findings in {time.monotonic() - began:.0f} s",
              file=sys.stderr)  # fmt: skip
    counts = Counter(
        (package, f["code"], f["severity"]) for package, fs in found.items() for f in fs
    )
    before = json.loads(args.against.read_text()) if args.against else None
    old = (
        Counter((package, f["code"], f["severity"]) for package, fs in before.items() for f in fs)
        if before
        else Counter()
    )
    print(f"{'package':28} {'rule':6} {'severity':8} {'before' if before else '':>7} {'count':>6}")
    for package, code, severity in sorted(counts | old):
        was = f"{old[package, code, severity]}" if before else ""
        print(f"{package:28} {code:6} {severity:8} {was:>7} {counts[package, code, severity]:>6}")
    if before:
        then = {key(p, f): f for p, fs in before.items() if p in found for f in fs}
        now = {key(p, f): f for p, fs in found.items() for f in fs}
        gone, came = then.keys() - now.keys(), now.keys() - then.keys()
        for mark, keys, side in (("-", gone, then), ("+", came, now)):
            for k in sorted(keys):
                f = side[k]
                print(f"{mark} {k[0]}: {f['file']}:{f['line']}: {f['code']} {f['severity']}: "
                      f"{f['message']}")  # fmt: skip
        for k in sorted(then.keys() & now.keys()):
            was, is_ = then[k], now[k]
            if (was["severity"], was["message"]) != (is_["severity"], is_["message"]):
                print(f"~ {k[0]}: {is_['file']}:{is_['line']}: {k[3]} "
                      f"{was['severity']} -> {is_['severity']}: {is_['message']}")  # fmt: skip
    if args.save:
        args.save.write_text(json.dumps(found, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
