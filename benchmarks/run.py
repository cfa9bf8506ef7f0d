"""
Binary STL → mass properties throughput, ours against trimesh, on one core.

    python benchmarks/run.py           # ~1M and ~5M triangles
    python benchmarks/run.py --quick   # small files, a sanity run of a few seconds

The files are closed tori (an elliptical tube round an elliptical ring, tilted and moved off
the origin so that every product of inertia is non-zero), generated with numpy on the first
run and cached under ``benchmarks/.data/``. Each is read once before timing, so it is in the
page cache; times are the best of a few runs.
"""

from __future__ import annotations

import os

# one core: set before numpy loads its BLAS
for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_variable] = "1"

import argparse  # noqa: E402
import platform  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
import tracemalloc  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from mass_compare import difference  # noqa: E402  (this folder's)

from inertia_kit.physics.stl import HEADER_BYTES, RECORD, read_stl  # noqa: E402

DATA = Path(__file__).resolve().parent / ".data"
DENSITY = 1000.0
TOLERANCE = 1e-9
TARGET = 20e6  # triangles per second, end to end
VERSION = 1  # of the generator: part of the file names


def torus_stl(path: Path, rings: int, segments: int) -> int:
    """
    Write a closed, consistently wound torus of ``2 * rings * segments`` triangles as binary STL.

    Every vertex is computed once, in float32, and copied into the records of all its
    triangles, so shared vertices are bit-identical, as in any exporter's output.
    """
    u = np.linspace(0.0, 2.0 * np.pi, rings, endpoint=False)[:, None]
    v = np.linspace(0.0, 2.0 * np.pi, segments, endpoint=False)[None, :]
    major, minor = 0.30, 0.08
    radial = major + minor * np.cos(v)
    local = np.stack(
        np.broadcast_arrays(radial * np.cos(u), 0.7 * radial * np.sin(u), 1.4 * minor * np.sin(v)),
        axis=-1,
    ).reshape(-1, 3)
    tilt = _rotation((0.3, -0.2, 0.5))
    points = (local @ tilt.T + (0.12, -0.05, 0.2)).astype(np.float32)

    count = 2 * rings * segments
    path.parent.mkdir(parents=True, exist_ok=True)
    partial = path.with_suffix(".partial")
    with open(partial, "wb") as stream:
        stream.write(b"inertia-kit benchmark torus".ljust(80, b" "))
        stream.write(np.uint32(count).tobytes())
        j = np.arange(segments)
        for i in range(rings):  # one ring of quads, two triangles each, at a time
            a = i * segments + j
            b = (i + 1) % rings * segments + j
            c = (i + 1) % rings * segments + (j + 1) % segments
            d = i * segments + (j + 1) % segments
            faces = np.stack([np.stack([a, b, c], -1), np.stack([a, c, d], -1)], 1).reshape(-1, 3)
            records = np.zeros(len(faces), dtype=RECORD)
            records["vertices"] = points[faces]
            edges = records["vertices"][:, 1:] - records["vertices"][:, :1]
            normals = np.cross(edges[:, 0], edges[:, 1])
            records["normal"] = normals / np.linalg.norm(normals, axis=1, keepdims=True)
            stream.write(records.tobytes())
    assert partial.stat().st_size == HEADER_BYTES + count * RECORD.itemsize
    partial.replace(path)
    return count


def _rotation(rpy) -> np.ndarray:
    r, p, y = rpy
    rx = np.array([[1, 0, 0], [0, np.cos(r), -np.sin(r)], [0, np.sin(r), np.cos(r)]])
    ry = np.array([[np.cos(p), 0, np.sin(p)], [0, 1, 0], [-np.sin(p), 0, np.cos(p)]])
    rz = np.array([[np.cos(y), -np.sin(y), 0], [np.sin(y), np.cos(y), 0], [0, 0, 1]])
    return rz @ ry @ rx


def dataset(rings: int, segments: int) -> tuple[Path, int]:
    count = 2 * rings * segments
    path = DATA / f"torus-v{VERSION}-{rings}x{segments}.stl"
    if not path.exists() or path.stat().st_size != HEADER_BYTES + count * RECORD.itemsize:
        print(f"generating {path.relative_to(ROOT)} ({count:,} triangles) ...", flush=True)
        torus_stl(path, rings, segments)
    path.read_bytes()  # into the page cache
    return path, count


def best_time(function, runs: int):
    best, result = float("inf"), None
    for _ in range(runs):
        start = time.perf_counter()
        result = function()
        best = min(best, time.perf_counter() - start)
    return best, result


def peak_allocated(function) -> int:
    """Peak bytes allocated through Python and numpy while ``function`` runs."""
    tracemalloc.start()
    try:
        function()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def ours(path: Path):
    integrator = read_stl(path)
    return integrator.moments.mass_properties(density=DENSITY), integrator.closed


def theirs(path: Path):
    import trimesh

    properties = trimesh.load(path).mass_properties  # density 1
    return properties.mass * DENSITY, properties.center_mass, properties.inertia * DENSITY


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="small files, for a sanity run")
    parser.add_argument("--runs", type=int, default=None, help="timed runs of ours (best of)")
    arguments = parser.parse_args()
    sizes = [(200, 125), (500, 200)] if arguments.quick else [(1000, 500), (2500, 1000)]
    runs = arguments.runs or (3 if arguments.quick else 7)

    import trimesh

    print(
        f"python {platform.python_version()}, numpy {np.__version__}, trimesh {trimesh.__version__}"
        f", {platform.machine()}, {os.cpu_count()} CPUs (one used)"
    )
    header = (
        f"{'file':<30} {'triangles':>10} {'ours':>10} {'ms':>7} {'peak MB':>8} "
        f"{'trimesh':>10} {'ms':>8} {'speedup':>8} {'max rel diff':>13}  closed"
    )
    rows, ok = [], True
    for rings, segments in sizes:
        path, count = dataset(rings, segments)
        elapsed, (mine, closed) = best_time(lambda path=path: ours(path), runs)
        peak = peak_allocated(lambda path=path: ours(path))
        their_elapsed, reference = best_time(
            lambda path=path: theirs(path), 1 if count > 2e6 else 2
        )
        size = float(np.ptp(read_stl(path).bounds, axis=0).max())
        diff = difference(mine, reference, size)
        rate, their_rate = count / elapsed, count / their_elapsed
        ok &= (arguments.quick or rate >= TARGET) and diff <= TOLERANCE and closed
        rows.append(
            f"{path.name:<30} {count:>10,} {rate / 1e6:>7.1f} M/s {elapsed * 1e3:>6.1f} "
            f"{peak / 2**20:>8.1f} {their_rate / 1e6:>7.2f} M/s {their_elapsed * 1e3:>8.0f} "
            f"{their_elapsed / elapsed:>7.1f}x {diff:>13.1e}  {closed}"
        )
        print(rows[-1] if len(rows) > 1 else f"{header}\n{'-' * len(header)}\n{rows[-1]}")
    print(
        f"\nours: read_stl + moments.mass_properties(density={DENSITY:g}); trimesh: "
        "trimesh.load + mass_properties; peak MB: tracemalloc peak during ours"
    )
    target = "" if arguments.quick else f"ours >= {TARGET / 1e6:g} M triangles/s, "
    print(f"{'PASS' if ok else 'FAIL'}: {target}max rel diff <= {TOLERANCE:g}, closed")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
