"""
The `full` format on a minified one-line robot: bytes written, wall time and peak memory of
`inertia-lint` as the links (and so the findings, and the line) grow. Each finding shows an
excerpt of at most 120 characters of its source line, so the output grows with the findings,
not with findings × line length.

    python benchmarks/full_output.py            # 500, 1000 and 2000 links
    python benchmarks/full_output.py 4000       # other sizes
"""

from __future__ import annotations

import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def minified(links: int) -> str:
    """A robot on one line: ``links`` links with a negative mass, in a chain of fixed joints."""
    body = "".join(
        f'<link name="l{i}"><inertial><mass value="-1"/><inertia ixx="1" ixy="0" ixz="0" '
        f'iyy="1" iyz="0" izz="1"/></inertial></link>'
        for i in range(links)
    )
    joints = "".join(
        f'<joint name="j{i}" type="fixed"><parent link="l{i}"/><child link="l{i + 1}"/></joint>'
        for i in range(links - 1)
    )
    return f'<robot name="m">{body}{joints}</robot>'


def measure(links: int, folder: Path) -> tuple[int, int, float, float]:
    path = folder / f"minified-{links}.urdf"
    path.write_text(minified(links))
    start = time.monotonic()
    run = subprocess.run(
        [sys.executable, "-m", "inertia_kit", "lint", str(path)],
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        check=False,
    )
    seconds = time.monotonic() - start
    # the children's peak so far: sizes run in increasing order, so it is this run's
    peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    return path.stat().st_size, len(run.stdout), seconds, peak


def main(sizes: list[int]) -> None:
    print(f"{'links':>6} {'file KB':>8} {'stdout KB':>10} {'s':>6} {'peak MB':>8}")
    with tempfile.TemporaryDirectory() as folder:
        for links in sorted(sizes):
            size, out, seconds, peak = measure(links, Path(folder))
            print(f"{links:>6} {size / 1e3:>8.0f} {out / 1e3:>10.0f} {seconds:>6.2f} {peak:>8.0f}")


if __name__ == "__main__":
    main([int(arg) for arg in sys.argv[1:]] or [500, 1000, 2000])
