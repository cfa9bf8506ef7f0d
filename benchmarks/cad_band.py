"""
How far real CAD links' declared mass properties are from a uniform-density reading of their
geometry: the band a forensic hypothesis's corrected values must land in (issue 20, item 1).

    python benchmarks/cad_band.py                 # every installed robot package
    python benchmarks/cad_band.py --save band.json
    python benchmarks/cad_band.py --load band.json   # the principal axes' table again

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
- ``pairs``: per principal axis (matched by moment order), its log gap ``g`` (the smaller of the
  two tensors' ``min_j |ln λi − ln λj|``) and the angle between the two axes, degrees: printed
  per bin of ``g`` with the scatter each link needs for IN069's limit
  ``½ arctan(SCATTER / g)`` (analysis/principal_axes.py), the better of its bases;
- ``com``: the distance between the declared COM and the geometry's, over the geometry's size
  (its largest radius of gyration);
- ``scale`` and ``shape``: the generalised eigenvalues ``r`` of the declared tensor against the
  geometry's (unfloored) split into a common factor, ``scale = mean(ln r)`` (a tensor ``k``
  times the geometry's has ``ln k``), and what is left, ``shape = max |ln r - scale|``: how far a
  real part's tensor is a uniformly scaled copy of its geometry's (IN068's calibration).
- ``com fraction``: how far the declared COM lies from the centroid of the nearer of the two
  geometries, as a fraction of the way to the edge of its hull (analysis/com_offset.py, what
  IN021 and IN067 measure): the band a centre of mass slip undone must land in.
- ``gains``: per forensic rule (IN060 … IN064), how much closer to the geometry (log distance)
  the rule's best reading of the link brings its tensor, among readings landing within the
  band (analysis.forensics.links.link_gains): on links that are right, what a coincidence
  gains, the margin each hypothesis must beat (analysis/forensics/diagnosis.py).

Printed: quantiles per measure, for mesh links and primitive links, and overall.
"""

from __future__ import annotations

import argparse
import itertools
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


def scale_and_shape(declared, geometry) -> tuple[float, float]:
    """The common log factor of the generalised eigenvalues and the largest departure from it."""
    inverse = np.linalg.inv(np.linalg.cholesky(geometry))
    ratios = np.linalg.eigvalsh(inverse @ declared @ inverse.T)
    if not (ratios > 0).all():
        return float("nan"), float("inf")
    logs = np.log(ratios)
    scale = float(logs.mean())
    return scale, float(np.abs(logs - scale).max())


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
    from inertia_kit.analysis.forensics.links import link_gains
    from inertia_kit.analysis.links import analyse
    from inertia_kit.analysis.principal_axes import compare_axes
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
        bases: dict[str, list] = {}
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
                pairs = [[c.gap, c.angle] for c in compare_axes(declared.inertia, expected.inertia)]
            except (np.linalg.LinAlgError, FloatingPointError, ValueError):
                continue
            scale, shape = scale_and_shape(declared.inertia, expected.inertia)
            row = {
                "scale": scale,
                "shape": shape,
                "package": package,
                "file": os.path.relpath(path, root),
                "link": link.name,
                "basis": basis.kind,
                "mesh": any(isinstance(s.shape.geometry, Mesh) for s in basis.solids),
                "moments": moments,
                "tensor": log_distance(declared.inertia, expected.inertia),
                "axes": max(angles) if angles else None,
                "com": com,
                "pairs": pairs,
            }
            bases[basis.kind] = pairs
            if best is None or row["moments"] < best["moments"]:
                best = row
        if best is not None:
            best["bases"] = bases
            best["com_fraction"] = least_fraction(link.bases, declared.com)
            best["gains"] = link_gains(link)
            rows.append(best)
    return rows


def quantiles(values: list[float]) -> str:
    """The :data:`QUANTILES` of the finite values, and how many are not (a tensor no body has)."""
    finite = [v for v in values if np.isfinite(v)]
    left_out = len(values) - len(finite)
    if not finite:
        return f"- ({left_out} not finite)" if left_out else "-"
    q = np.quantile(finite, QUANTILES)
    text = "  ".join(f"{v:7.3f}" for v in q)
    return text + (f"  ({left_out} not finite, left out)" if left_out else "")


#: bins of the log gap ``g`` of an axis (analysis/principal_axes.py)
GAP_BINS = (0.0, 0.1, 0.2, 0.3, 0.5, 0.8, 1.0, 1.5, 2.0, 3.0, float("inf"))


def needed_scatter(gap: float, angle: float) -> float:
    """The ``SCATTER`` that puts ``angle`` at the limit ``½ arctan(SCATTER / gap)``."""
    return float("inf") if angle >= 45.0 else gap * float(np.tan(np.radians(2.0 * angle)))


def print_axes(rows: list[dict]) -> None:
    """The angle between declared and geometry principal axes against the gap, per bin; and the
    scatter each link needs as the rule judges it (the better of its bases)."""
    from inertia_kit.analysis.principal_axes import MIN_GAP, SCATTER, angle_limit

    pairs = [pair for r in rows for pair in r.get("pairs", [])]
    print(f"principal axis angle (deg) against the gap g, {len(pairs)} axes (better basis)")
    print("  g from   to      axes     50 %    95 %    99 %     max   limit(lo)")
    for lo, hi in itertools.pairwise(GAP_BINS):
        angles = [a for g, a in pairs if lo <= g < hi]
        if not angles:
            continue
        q = np.quantile(angles, (0.5, 0.95, 0.99, 1.0))
        print(
            f"  {lo:5.2f} {hi:5.2f} {len(angles):8d} "
            + " ".join(f"{v:7.1f}" for v in q)
            + f" {angle_limit(lo):7.1f}"
        )
    needs = []
    for r in rows:
        per_basis = [
            max((needed_scatter(g, a) for g, a in found if g >= MIN_GAP), default=0.0)
            for found in r.get("bases", {}).values()
        ]
        if per_basis:
            needs.append((min(per_basis), r["package"], r["file"], r["link"]))
    needs.sort(reverse=True)
    values = [n for n, *_ in needs]
    print(
        f"scatter a link needs (g >= {MIN_GAP}, better basis), {len(values)} links: "
        f"quantiles {QUANTILES} {quantiles(values)}; above SCATTER = {SCATTER}: "
        f"{sum(v > SCATTER for v in values)}"
    )
    for need, package, file, link in needs[:8]:
        print(f"  {need:6.3f} {package} {file} {link}")


def print_gains(rows: list[dict]) -> None:
    """What each forensic rule's best reading gains on these (right) links, and the largest."""
    codes = sorted({code for r in rows for code in r.get("gains", {})})
    print(f"forensic readings' gain in log distance on these links; quantiles {QUANTILES}")
    for code in codes:
        found = sorted(
            (
                (r["gains"][code], r["package"], r["file"], r["link"])
                for r in rows
                if code in r.get("gains", {})
            ),
            reverse=True,
        )
        print(f"  {code} ({len(found)} links read) {quantiles([g for g, *_ in found])}")
        for gain, package, file, link in found[:3]:
            print(f"      {gain:6.3f} {package} {file} {link}")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--save", type=Path)
    parser.add_argument("--only", action="append")
    parser.add_argument("--load", type=Path, help="the rows of an earlier --save, not measured")
    args = parser.parse_args()
    if args.load:
        rows = json.loads(args.load.read_text())
        print_axes(rows)
        print_gains(rows)
        return 0
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
        print(f"  |scale| (ln k)    {quantiles([abs(r['scale']) for r in chosen])}")
        print(f"  shape about k     {quantiles([r['shape'] for r in chosen])}")
        fractions = [r["com_fraction"] for r in chosen if np.isfinite(r["com_fraction"])]
        print(f"  COM fraction      {quantiles(fractions)}")
    print_axes(rows)
    print_gains(rows)
    if args.save:
        args.save.write_text(json.dumps(rows, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
