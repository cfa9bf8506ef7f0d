"""
Does ``inertia-fill`` settle? For each mode (``--fix missing|invalid|all``, ``--mass``,
``--total-mass``, ``--density``): fill every robot file of a copy, fill again, and count the
files the second run changed (a fixed point: 0) and those ``--check`` still fails right after
(with no link refused).

    PYTHONPATH=$PWD python benchmarks/fixed_point.py                  # everything (~1 hour)
    PYTHONPATH=$PWD python benchmarks/fixed_point.py --sets examples rules --modes all
    PYTHONPATH=$PWD python benchmarks/fixed_point.py --limit 20 --json out.json

Sets: ``examples`` (examples/), ``rules`` (each rule document's failing example) and the robot
files of the installed PyPI packages (pybullet, rtb-data, example-robot-data, dexmate-urdf,
fourier-robot-descriptions, airo-models, robot_properties_fingers; missing ones are skipped),
each mirrored into a temporary folder (robot files copied, meshes linked): nothing installed
is written.
"""

from __future__ import annotations

import argparse
import json
import site
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "tests"))

from kit.fixed_point import MODES, mirror, robot_files, rule_failing_examples, settle  # noqa: E402


def _site() -> Path:
    return Path(site.getsitepackages()[0])


#: name -> (the package's robot folder, the folder given as --package-path: None for itself)
PACKAGES = {
    "pybullet": (lambda: _site() / "pybullet_data", None),
    "rtb-data": (lambda: _site() / "rtbdata", None),
    "example-robot-data": (lambda: _site() / "cmeel.prefix/share/example-robot-data", None),
    "dexmate-urdf": (lambda: _site() / "dexmate_urdf", None),
    "fourier-robot-descriptions": (lambda: _site() / "fourier_robot_descriptions", None),
    "airo-models": (lambda: _site() / "airo_models", None),
    "robot_properties_fingers": (lambda: _site() / "robot_properties_fingers", "share"),
}


def prepare(name: str, scratch: Path) -> tuple[Path, list[str]] | None:
    """A fresh copy of set ``name`` under ``scratch``: its root and its package paths."""
    if name == "examples":
        root = mirror(REPO / "examples", scratch / "examples")
        return root, [str(root)]
    if name == "rules":
        return rule_failing_examples(REPO / "rules", scratch / "rules"), []
    folder, package_path = PACKAGES[name]
    original = folder()
    if not original.is_dir():
        return None
    root = mirror(original, scratch / name / original.name)
    if package_path == "share":  # its meshes resolve through <prefix>/share (read only)
        return root, [str(_site().parents[2] / "share")]
    return root, [str(root)]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sets", nargs="*", default=["examples", "rules", *PACKAGES])
    parser.add_argument("--modes", nargs="*", default=list(MODES), choices=list(MODES))
    parser.add_argument("--limit", type=int, default=None, help="files per set at most (evenly)")
    parser.add_argument("--json", default=None, help="write the files changed again here")
    args = parser.parse_args()
    report: dict[str, dict[str, dict]] = {}
    totals = dict.fromkeys(args.modes, 0)
    print(
        f"{'set':28} {'mode':11} {'files':>6} {'changed':>8} {'again':>6} {'check':>6} {'crash':>6}"
    )
    for name in args.sets:
        for mode in args.modes:
            with tempfile.TemporaryDirectory(prefix="fixed-point-") as scratch:
                prepared = prepare(name, Path(scratch))
                if prepared is None:
                    print(f"{name:28} not installed")
                    break
                root, package_paths = prepared
                files = robot_files(root)
                if args.limit is not None and len(files) > args.limit:
                    step = len(files) / args.limit
                    files = [files[int(i * step)] for i in range(args.limit)]
                started = time.monotonic()
                result = settle(root, mode, package_paths=package_paths, files=files)
                seconds = time.monotonic() - started
            totals[mode] += len(result.changed_again)
            relative = [str(Path(p).relative_to(root)) for p in result.changed_again]
            report.setdefault(name, {})[mode] = {
                "files": result.files,
                "changed": len(result.changed_first),
                "changed_again": relative,
                "check_failed": [str(Path(p).relative_to(root)) for p in result.check_failed],
                "crashed": [str(Path(p).relative_to(root)) for p in result.crashed],
            }
            print(
                f"{name:28} {mode:11} {result.files:6} {len(result.changed_first):8} "
                f"{len(result.changed_again):6} {len(result.check_failed):6} "
                f"{len(result.crashed):6}  ({seconds:.0f} s)",
                flush=True,
            )
    print("files changed by the second run, per mode:", totals)
    if args.json:
        Path(args.json).write_text(json.dumps(report, indent=1))
    return 0 if not any(totals.values()) else 1


if __name__ == "__main__":
    sys.exit(main())
