"""
How close real links come to IN023's two kinds of hard bound: for every link of the installed
robot packages (``benchmarks/real_robots.py``'s) with a declared tensor and complete geometry,
the worst ratio of a moment about an axis to its bound and of a second moment along a
direction to its bound (:func:`inertia_kit.analysis.bounds.moment_excess`), with the margin
the rule allows (rounding and facets, :mod:`inertia_kit.analysis.firmness`)::

    python benchmarks/bound_ratios.py                 # quantiles, and every link beyond 0.9
    python benchmarks/bound_ratios.py --only rtb-data

Run it with the interpreter that has the packages. The URDF and xacro files are loaded one by
one (a file that does not load is counted and left out).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from inertia_kit.analysis.bounds import BOUND_RTOL, moment_excess
from inertia_kit.analysis.links import analyse
from inertia_kit.description.loader import load

sys.path.insert(0, str(Path(__file__).parent))
from real_robots import PACKAGES, package_folder


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--only", action="append", help="this package only (repeatable)")
    parser.add_argument("--show", type=float, default=0.9, help="list links beyond this ratio")
    args = parser.parse_args()
    rows = []
    failed = 0
    for package in args.only or PACKAGES:
        folder = package_folder(package)
        if folder is None:
            continue
        files = sorted(
            p for p in folder.rglob("*") if p.suffix in (".urdf", ".xacro") and p.is_file()
        )
        for path in files:
            try:
                robot = load(path, package_paths=[folder])
                analysis = analyse(robot)
            except Exception:
                failed += 1
                continue
            for link in analysis.links:
                declared, hull = link.declared, link.envelope
                if declared is None or hull is None or not declared.mass > 0:
                    continue
                about = moment_excess(declared, hull, "about")
                along = moment_excess(declared, hull, "along")
                if about is None:
                    continue
                rows.append((package, path, link, about, along))
    print(f"{len(rows)} links with a tensor and complete geometry ({failed} files not loaded)")
    quiet = [r for r in rows if not r[3].ratio > 1.0 + BOUND_RTOL]
    along = np.array([r[4].ratio for r in quiet if r[4] is not None])
    # the same second moment against m w²/4, the bound with the centre of mass anywhere
    anywhere = np.array(
        [r[4].moment / (r[2].declared.mass * (0.5 * sum(r[4].sides)) ** 2) for r in quiet if r[4]]
    )
    print(
        f"IN023 quiet today (about-axis ratio ≤ {1 + BOUND_RTOL}): {len(quiet)} links, "
        f"{len(along)} with the COM inside the hull and a positive semidefinite Σ"
    )
    for q in (0.5, 0.9, 0.99, 1.0):
        print(f"  along-direction ratio, {q:.0%} quantile: {np.quantile(along, q):.3f}")
    for limit in (0.5, 0.8, 1.0, 1.0 + BOUND_RTOL, 1.5, 2.0):
        print(
            f"  beyond {limit:g}: {(along > limit).sum()} (with the COM anywhere: "
            f"{(anywhere > limit).sum()})"
        )
    print(f"links IN023 is quiet on today beyond {args.show} along a direction:")
    for package, path, link, about, excess in sorted(
        quiet, key=lambda r: -(r[4].ratio if r[4] is not None else 0)
    ):
        if excess is None or not excess.ratio > args.show:
            continue
        firmness = link.firmness
        firm = None if firmness is None else firmness.firm
        axis = np.round(excess.axis, 3)
        print(
            f"  {excess.ratio:7.3f} about {about.ratio:6.3f} firm={firm} {package} "
            f"{path.name} {link.name} along {axis} sides {np.round(excess.sides, 4)} "
            f"m {link.declared.mass:.4g}"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
