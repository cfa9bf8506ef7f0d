"""
How far real CAD links' declared mass properties are from a uniform-density reading of their
geometry: the band a forensic hypothesis's corrected values must land in (issue 20, item 1).

    python benchmarks/cad_band.py                 # every installed robot package
    python benchmarks/cad_band.py --save band.json

Population: every link of every robot file in the installed PyPI robot packages (those of
benchmarks/real_robots.py) with a declared ``<inertial>`` and geometry that gives a volume, on
which the linter gives no error or warning (default rules): links a user would call right. For
each, against its collision geometry and its visual one (the better of the two is kept, as the
rules do), at the declared mass:

- ``moments``: max over the three sorted principal moments of ``|ln(declared / geometry)|``;
- ``axes``: the angle, degrees, between the declared and the geometry's principal axes, for
  each axis whose moment stands apart from both others by ``ANISOTROPY`` in both tensors (an
  axis is only defined when its moment is distinct);
- ``tensor``: the largest ``|ln((nᵀDn + f λ) / (nᵀGn + f λ))|`` over unit axes ``n``, with
  ``λ`` the geometry's largest moment and ``f = FLOOR`` (the forensic measure's floor): moments
  and axes at once, in log space (the generalised eigenvalues of the two floored tensors);
- ``com``: the distance between the declared COM and the geometry's, over the geometry's size
  (its largest radius of gyration);
- ``com fraction``: how far the declared COM lies from the centroid of the nearer of the two
  geometries, as a fraction of the way to the edge of its hull (analysis/com_offset.py, what
  IN021 and IN067 measure): the band a centre of mass slip undone must land in.

Printed: quantiles per measure, for mesh links and primitive links, and overall.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from real_robots import PACKAGES, package_folder

#: a principal axis is compared when its moment differs from each other one by this fraction
ANISOTROPY = 0.2
QUANTILES = (0.5, 0.9, 0.95, 0.99, 1.0)
#: the forensic measure's floor (analysis/forensics/measure.py FLOOR)
FLOOR = 0.05


def log_distance(declared, geometry) -> float:
    """max over unit n of |ln((nᵀDn + fλ) / (nᵀGn + fλ))| (see the module docstring)."""
    floor = FLOOR * float(np.linalg.eigvalsh(geometry).max()) * np.eye(3)
    inverse = np.linalg.inv(np.linalg.cholesky(geometry + floor))
    ratios = np.linalg.eigvalsh(inverse @ (declared + floor) @ inverse.T)
    if not (ratios > 0).all():
        return float("inf")
    return float(np.abs(np.log(ratios)).max())


def axis_angles(declared, geometry) -> list[float]:
    """Angles (degrees) between corresponding well-defined principal axes."""
    angles = []
    ld, ad = np.linalg.eigh(declared)
    lg, ag = np.linalg.eigh(geometry)
    for i in range(3):
        others = [j for j in range(3) if j != i]
        distinct = all(
            abs(ld[i] - ld[j]) > ANISOTROPY * max(ld[i], ld[j])
            and abs(lg[i] - lg[j]) > ANISOTROPY * max(lg[i], lg[j])
            for j in others
        )
        if distinct:
            cosine = min(1.0, abs(float(ad[:, i] @ ag[:, i])))
            angles.append(float(np.degrees(np.arccos(cosine))))
    return angles


def measure_file(args: tuple[str, str, str]) -> list[dict]:
    package, path, root = args
    from inertia_kit.analysis.com_offset import least_fraction
    from inertia_kit.analysis.links import analyse
    from inertia_kit.description.loader import load
    from inertia_kit.description.model import Mesh
    from inertia_kit.lint.findings import Severity
    from inertia_kit.lint.runner import Selection, lint_file

    try:
        result = lint_file(path, Selection(), package_paths=[root])
        if result.error is not None or result.fragment:
            return []
        flagged = {
            f.link
            for f in result.findings
            if f.link and f.severity in (Severity.ERROR, Severity.WARNING)
        }
        analysis = analyse(load(path, package_paths=[root]))
    except Exception:  # a measurement: what cannot be read is left out
        return []
    rows = []
    for link in analysis.links:
        declared = link.declared
        if link.name in flagged or declared is None or not declared.mass > 0:
            continue
        best = None
        for basis in link.bases:
            expected = basis.at_mass(declared.mass)
            if expected is None:
                continue
            try:
                d = np.linalg.eigvalsh(declared.inertia)
                g = np.linalg.eigvalsh(expected.inertia)
                if not (d > 0).all() or not (g > 0).all():
                    continue
                moments = float(np.abs(np.log(d / g)).max())
                size = float(np.sqrt(g.max() / declared.mass))
                com = float(np.linalg.norm(declared.com - expected.com) / size)
                angles = axis_angles(declared.inertia, expected.inertia)
            except (np.linalg.LinAlgError, FloatingPointError, ValueError):
                continue
            row = {
                "package": package,
                "file": os.path.relpath(path, root),
                "link": link.name,
                "basis": basis.kind,
                "mesh": any(isinstance(s.shape.geometry, Mesh) for s in basis.solids),
                "moments": moments,
                "tensor": log_distance(declared.inertia, expected.inertia),
                "axes": max(angles) if angles else None,
                "com": com,
            }
            if best is None or row["moments"] < best["moments"]:
                best = row
        if best is not None:
            best["com_fraction"] = least_fraction(link.bases, declared.com)
            rows.append(best)
    return rows


def quantiles(values: list[float]) -> str:
    if not values:
        return "-"
    q = np.quantile(values, QUANTILES)
    return "  ".join(f"{v:7.3f}" for v in q)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--save", type=Path)
    parser.add_argument("--only", action="append")
    args = parser.parse_args()
    from inertia_kit.lint.discovery import expand_paths

    jobs = []
    for package in args.only or PACKAGES:
        folder = package_folder(package)
        if folder is None:
            continue
        jobs += [(package, str(p), str(folder)) for p in expand_paths([folder])]
    with ProcessPoolExecutor(max_workers=2) as pool:
        rows = [row for found in pool.map(measure_file, jobs, chunksize=4) for row in found]
    print(f"{len(rows)} links from {len(jobs)} files; quantiles {QUANTILES}")
    for label, chosen in (
        ("mesh", [r for r in rows if r["mesh"]]),
        ("primitive", [r for r in rows if not r["mesh"]]),
        ("all", rows),
    ):
        print(f"{label} ({len(chosen)} links)")
        print(f"  |ln moment ratio| {quantiles([r['moments'] for r in chosen])}")
        print(f"  tensor log dist.  {quantiles([r['tensor'] for r in chosen])}")
        angles = [r["axes"] for r in chosen if r["axes"] is not None]
        print(f"  axis angle, deg   {quantiles(angles)}")
        print(f"  COM offset/size   {quantiles([r['com'] for r in chosen])}")
        fractions = [r["com_fraction"] for r in chosen if np.isfinite(r["com_fraction"])]
        print(f"  COM fraction      {quantiles(fractions)}")
    if args.save:
        args.save.write_text(json.dumps(rows, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
