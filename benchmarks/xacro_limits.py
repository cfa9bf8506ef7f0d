"""
What xacro expansion needs on the real robots installed, against its default limits, and what the
runaway reproducers cost (README: "Bounded xacro expansion").

    python benchmarks/xacro_limits.py            # real robots, then the reproducers
    python benchmarks/xacro_limits.py --robots   # real robots only

Real robots: every xacro file of rtb-data, example-robot-data and ``examples/`` that needs
expanding, each expanded once in a fresh fork of this process (imports warm, as in the CLI),
in-process inside that fork so that the element meter can be read: CPU and wall seconds, resident
and address-space growth (MB, from /proc), elements counted. Reproducers: ``inertia-lint FILE``
in a fresh process: exit code, wall seconds and peak resident MB of it and its children.
Linux only (/proc, RUSAGE_CHILDREN).
"""

from __future__ import annotations

import json
import os
import site
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))

from kit.runaway_xacro import HUGE_POWER, HUGE_STRING, doubling_chain, expression_robot  # noqa: E402

from inertia_kit.description import xacro_expand  # noqa: E402
from inertia_kit.description.loader import needs_expansion  # noqa: E402
from inertia_kit.description.urdf.packages import PackageResolver  # noqa: E402
from inertia_kit.description.xacro_limits import XacroLimits  # noqa: E402

MEASURE = """
import json, resource, subprocess, sys, time
began = time.monotonic()
done = subprocess.run(sys.argv[1:], capture_output=True, text=True)
peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
print(json.dumps([done.returncode, time.monotonic() - began, peak, done.stderr]))
"""


def _status() -> dict[str, float]:
    values = {}
    with open("/proc/self/status") as stream:
        for line in stream:
            key, _, value = line.partition(":")
            if key in ("VmRSS", "VmHWM", "VmSize", "VmPeak"):
                values[key] = int(value.split()[0]) / 1024
    return values


def _one(path: Path, package: Path | None) -> dict:
    counted = []

    class Counting(xacro_expand._Session):
        def result(self, *args, **kwargs):
            counted.append(self.meter.elements)
            return super().result(*args, **kwargs)

    xacro_expand._Session = Counting
    before = _status()
    wall, cpu = time.perf_counter(), time.process_time()
    resolver = PackageResolver([package] if package else [], start=path)
    limits = XacroLimits(timeout=0, memory=0, elements=0)  # in this fork: the meter is readable
    try:
        expanded = xacro_expand.expand(path, resolver=resolver, limits=limits)
        elements, error = (None if expanded.fragment else len(list(expanded.root.iter()))), None
    except Exception as failure:
        elements, error = None, str(failure)[:120]
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    after = _status()
    return {
        "file": str(path),
        "cpu": cpu,
        "wall": wall,
        "rss": after["VmHWM"] - before["VmRSS"],
        "vm": after["VmPeak"] - before["VmSize"],
        "counted": counted[0] if counted else 0,
        "elements": elements,
        "error": error,
    }


def real_robots() -> None:
    data = Path(site.getsitepackages()[0])
    roots = [
        (data / "rtbdata", data / "rtbdata"),
        (data / "cmeel.prefix/share/example-robot-data",) * 2,
        (ROOT / "examples", None),
    ]
    rows = []
    for root, package in roots:
        for path in sorted(root.rglob("*.xacro")) if root.is_dir() else []:
            if not needs_expansion(path.read_bytes()):
                continue
            read, write = os.pipe()
            pid = os.fork()
            if pid == 0:
                os.close(read)
                os.write(write, json.dumps(_one(path, package)).encode())
                os._exit(0)
            os.close(write)
            with os.fdopen(read, "rb") as stream:
                rows.append(json.loads(stream.read()))
            os.waitpid(pid, 0)
    robots = [r for r in rows if r["elements"] is not None]
    print(
        f"{len(rows)} xacro files expanded, {len(robots)} robots, "
        f"{sum(1 for r in rows if r['error'])} refused (missing packages)"
    )
    default = XacroLimits()
    for key, unit, limit in (
        ("cpu", "s CPU", default.timeout),
        ("wall", "s wall", default.timeout),
        ("rss", "MB resident", default.memory),
        ("vm", "MB address space", default.memory),
        ("counted", "elements counted", default.elements),
    ):
        top = max(robots, key=lambda r: r[key])
        print(
            f"  max {top[key]:9.3f} {unit:17} ({limit / top[key]:6.0f}x under the default "
            f"{limit:g}): {Path(top['file']).relative_to(Path(top['file']).parents[3])}"
        )


def reproducers() -> None:
    exe = str(Path(sys.executable).parent / "inertia-lint")
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    env.pop("INERTIA_KIT_XACRO_LIMITS", None)
    with tempfile.TemporaryDirectory() as folder:
        cases = {
            "string.xacro": expression_robot(HUGE_STRING),
            "power.xacro": expression_robot(HUGE_POWER),
            "chain.xacro": doubling_chain(),
        }
        for name, text in cases.items():
            Path(folder, name).write_text(text)
            done = subprocess.run(
                [sys.executable, "-c", MEASURE, exe, name],
                cwd=folder,
                env=env,
                capture_output=True,
                text=True,
                check=True,
            )
            code, seconds, peak, stderr = json.loads(done.stdout)
            print(f"inertia-lint {name}: exit {code}, {seconds:.2f} s, peak {peak:.0f} MB")
            print(f"  {stderr.splitlines()[0][:160]}...")


if __name__ == "__main__":
    real_robots()
    if "--robots" not in sys.argv:
        reproducers()
