"""
Whole-process wall time of ``inertia-lint FILE``: start-up, and meshes with a cold and a warm
mesh cache, as ratios measured in one run; the modules a run imports; where a cold COLLADA
robot's time goes.

    python benchmarks/lint.py             # best of 7 runs each
    python benchmarks/lint.py --runs 3    # a quicker look
    python benchmarks/lint.py --imports   # also: what one run of each case spends importing
    python benchmarks/lint.py --robot PATH/panda.urdf.xacro   # also a real robot, cold and warm
                                                              # runs in turn; repeatable

Three robots are generated on the first run under ``benchmarks/.data/lint-v1/``: a 20-link
chain of revolute joints with box, cylinder and sphere links, and two 20-link chains whose
links are meshes of 50,000 triangles each (closed tori of different sizes, 1M triangles in
all, referenced by relative paths), one as binary STL, one as COLLADA (the same vertices and
triangles). Every ``<inertial>`` is right for its geometry.

Each case runs the ``inertia-lint`` console script installed next to this Python (not a
pyenv or asdf shim, which adds its own start-up) as a subprocess, with stdout discarded, and
reports the best of N wall times. Exit codes 0 and 1 (findings) count as success. "cold" gives
every run a new, empty ``INERTIA_KIT_CACHE_DIR``; "warm" runs against one populated cache.
Mesh files are in the page cache either way, and every case has one untimed run first, which
also compiles the bytecode (under ``benchmarks/.data/pycache``, whatever
``PYTHONDONTWRITEBYTECODE`` says: installed packages ship compiled).
"""

from __future__ import annotations

import argparse
import itertools
import os
import platform
import re
import shutil
import subprocess
import sys
import tempfile
import time
from collections import defaultdict
from dataclasses import dataclass
from pathlib import Path

import lint_collada  # benchmarks/, this script's folder
import numpy as np
from import_budget import NOT_FOR_PLAIN_URDF, NOT_FOR_WARM_CACHE

try:
    import resource
except ImportError:  # Windows: wall times only
    resource = None  # type: ignore[assignment]

ROOT = Path(__file__).resolve().parents[1]
DATA = Path(__file__).resolve().parent / ".data" / "lint-v1"  # bump with the generator
LINKS = 20
RINGS, SEGMENTS = 250, 100  # 2 * 250 * 100 = 50,000 triangles a mesh
DENSITY = 2700.0  # aluminium, kg/m³

# targets: the primitive robot's a multiple of `python -c pass`, a warm meshed robot's a
# multiple of the primitive robot's (issue 13), the cold meshed robot's in seconds
START_UP_RATIO = 8.0
WARM_RATIO = 2.0
COLD = 0.400

RECORD = np.dtype([("normal", "<f4", (3,)), ("vertices", "<f4", (3, 3)), ("attribute", "<u2")])


# --- the robots ---------------------------------------------------------------------------------


def torus_triangles(index: int) -> np.ndarray:
    """(50000, 3, 3) float32: a closed torus, each link's a little different in size and tilt."""
    points, faces = torus(index)
    return points[faces]


def torus(index: int) -> tuple[np.ndarray, np.ndarray]:
    """The torus' (n, 3) float32 vertices and (50000, 3) triangles, indices into them."""
    grow = 1.0 + 0.04 * index
    _, _, local = torus_surface(RINGS, SEGMENTS, 0.06 * grow, 0.018 * grow)
    tilt = rotation((0.3 + 0.05 * index, -0.2, 0.5))
    # every vertex computed once, in float32, and shared bit for bit: closed, as exporters write
    points = (local @ tilt.T + (0.01, -0.005, 0.1)).astype(np.float32)
    faces = torus_quads(RINGS, SEGMENTS)[:, [0, 1, 2, 0, 2, 3]].reshape(-1, 3)
    return points, faces


def torus_surface(rings: int, segments: int, major: float, minor: float):
    """
    ``(u, v, points)``: the angles round the ring, ``(rings, 1)``, and round the tube,
    ``(1, segments)``, and the ``(rings * segments, 3)`` vertices of an elliptical tube round an
    elliptical ring, centred, untilted (the benchmarks' tori: every product of inertia non-zero
    once tilted).
    """
    u = np.linspace(0.0, 2.0 * np.pi, rings, endpoint=False)[:, None]
    v = np.linspace(0.0, 2.0 * np.pi, segments, endpoint=False)[None, :]
    radial = major + minor * np.cos(v)
    points = np.stack(
        np.broadcast_arrays(radial * np.cos(u), 0.7 * radial * np.sin(u), 1.4 * minor * np.sin(v)),
        axis=-1,
    ).reshape(-1, 3)
    return u, v, points


def torus_quads(rings: int, segments: int) -> np.ndarray:
    """``(rings * segments, 4)`` vertex indices ``(a, b, c, d)`` of each quad of
    :func:`torus_surface`, wound outwards; ``(a, b, c), (a, c, d)`` its two triangles."""
    i = np.arange(rings)[:, None]
    j = np.arange(segments)[None, :]
    a = i * segments + j
    b = (i + 1) % rings * segments + j
    c = (i + 1) % rings * segments + (j + 1) % segments
    d = i * segments + (j + 1) % segments
    return np.stack([a, b, c, d], -1).reshape(-1, 4)


def rotation(rpy) -> np.ndarray:
    """URDF roll-pitch-yaw as a matrix (the benchmarks' own, not the package's)."""
    r, p, y = rpy
    rx = np.array([[1, 0, 0], [0, np.cos(r), -np.sin(r)], [0, np.sin(r), np.cos(r)]])
    ry = np.array([[np.cos(p), 0, np.sin(p)], [0, 1, 0], [-np.sin(p), 0, np.cos(p)]])
    rz = np.array([[np.cos(y), -np.sin(y), 0], [np.sin(y), np.cos(y), 0], [0, 0, 1]])
    return rz @ ry @ rx


def write_stl(path: Path, triangles: np.ndarray) -> None:
    records = np.zeros(len(triangles), dtype=RECORD)
    records["vertices"] = triangles
    edges = triangles[:, 1:] - triangles[:, :1]
    normals = np.cross(edges[:, 0], edges[:, 1])
    records["normal"] = normals / np.linalg.norm(normals, axis=1, keepdims=True)
    partial = path.with_suffix(".partial")
    partial.write_bytes(
        b"inertia-kit lint benchmark".ljust(80, b" ")
        + np.uint32(len(triangles)).tobytes()
        + records.tobytes()
    )
    partial.replace(path)


def robot(name: str, links: list[tuple[str, str]]) -> str:
    """URDF text: ``links`` are ``(geometry xml, inertial xml)``, chained by revolute joints."""
    lines = ['<?xml version="1.0"?>', f'<robot name="{name}">']
    for index, (geometry, inertial) in enumerate(links):
        lines += [
            f'  <link name="link_{index:02d}">',
            inertial,
            "    <visual>",
            f"      <geometry>{geometry}</geometry>",
            "    </visual>",
            "    <collision>",
            f"      <geometry>{geometry}</geometry>",
            "    </collision>",
            "  </link>",
        ]
        if index:
            axis = "0 0 1" if index % 2 else "0 1 0"
            lines += [
                f'  <joint name="joint_{index:02d}" type="revolute">',
                f'    <parent link="link_{index - 1:02d}"/>',
                f'    <child link="link_{index:02d}"/>',
                '    <origin xyz="0 0 0.3" rpy="0 0 0"/>',
                f'    <axis xyz="{axis}"/>',
                '    <limit lower="-2.5" upper="2.5" effort="50" velocity="2"/>',
                "  </joint>",
            ]
    return "\n".join([*lines, "</robot>", ""])


def primitive_robot() -> str:
    from inertia_kit.description.urdf.inertial_xml import inertial_block
    from inertia_kit.physics import primitives

    links = []
    for index in range(LINKS):
        grow = 1.0 + 0.05 * index
        kind = index % 3
        if kind == 0:
            size = (0.12 * grow, 0.08 * grow, 0.25 * grow)
            geometry = f'<box size="{size[0]!r} {size[1]!r} {size[2]!r}"/>'
            properties = primitives.box(size, density=DENSITY)
        elif kind == 1:
            radius, length = 0.04 * grow, 0.25 * grow
            geometry = f'<cylinder radius="{radius!r}" length="{length!r}"/>'
            properties = primitives.cylinder(radius, length, density=DENSITY)
        else:
            radius = 0.06 * grow
            geometry = f'<sphere radius="{radius!r}"/>'
            properties = primitives.sphere(radius, density=DENSITY)
        links.append((geometry, inertial_block(properties, indent="  ", level=2)))
    return robot("benchmark_primitives", links)


def mesh_robot(meshes: list[Path]) -> str:
    from inertia_kit.description.urdf.inertial_xml import inertial_block
    from inertia_kit.physics.meshes import mesh

    links = []
    for path in meshes:
        result = mesh(path, density=DENSITY)
        assert result.method == "exact" and result.closed, f"{path} is not closed"
        geometry = f'<mesh filename="{path.parent.name}/{path.name}"/>'
        links.append((geometry, inertial_block(result.mass_properties, indent="  ", level=2)))
    return robot(f"benchmark_{path.parent.name}", links)


def dataset() -> tuple[Path, Path, list[Path], Path, list[Path]]:
    primitives_urdf, meshes_urdf = DATA / "primitives.urdf", DATA / "meshes.urdf"
    stls = [DATA / "meshes" / f"link_{i:02d}.stl" for i in range(LINKS)]
    collada_urdf = DATA / "collada.urdf"
    daes = [DATA / "collada" / f"link_{i:02d}.dae" for i in range(LINKS)]
    size = 84 + 2 * RINGS * SEGMENTS * RECORD.itemsize
    if not all(p.exists() and p.stat().st_size == size for p in stls):
        print(f"generating {LINKS} meshes of {2 * RINGS * SEGMENTS:,} triangles ...", flush=True)
        (DATA / "meshes").mkdir(parents=True, exist_ok=True)
        for index, path in enumerate(stls):
            write_stl(path, torus_triangles(index))
        meshes_urdf.unlink(missing_ok=True)
    if not meshes_urdf.exists():
        meshes_urdf.write_text(mesh_robot(stls))
    if not primitives_urdf.exists():
        primitives_urdf.write_text(primitive_robot())
    if not all(p.exists() for p in daes):
        print("writing them as COLLADA ...", flush=True)
        (DATA / "collada").mkdir(parents=True, exist_ok=True)
        for index, path in enumerate(daes):
            lint_collada.write_dae(path, *torus(index))
        collada_urdf.unlink(missing_ok=True)
    if not collada_urdf.exists():
        collada_urdf.write_text(mesh_robot(daes))
    for path in stls + daes:
        path.read_bytes()  # into the page cache
    return primitives_urdf, meshes_urdf, stls, collada_urdf, daes


# --- timing -------------------------------------------------------------------------------------


def console_script(name: str) -> str:
    """The script installed with this Python: a shim (pyenv, asdf) would add its own start-up."""
    folder = Path(sys.executable).parent
    for candidate in (folder / name, folder / f"{name}.exe"):
        if candidate.is_file():
            return str(candidate)
    found = shutil.which(name)
    if found is None:
        sys.exit(f"`{name}` is not installed: pip install -e {ROOT}")
    return found


def environment(cache: str | None) -> dict[str, str]:
    """
    The runs' environment: bytecode cached, as in any installed package, under a prefix here
    (an environment with ``PYTHONDONTWRITEBYTECODE`` would compile every module on every run),
    and ``cache`` as the mesh cache, or the cache off for ``None``.
    """
    drop = ("PYTHONPROFILEIMPORTTIME", "PYTHONDONTWRITEBYTECODE", "INERTIA_KIT_NO_CACHE")
    env = {k: v for k, v in os.environ.items() if k not in drop}
    env["PYTHONPYCACHEPREFIX"] = str(DATA.parent / "pycache")
    if cache is None:
        env["INERTIA_KIT_NO_CACHE"] = "1"
    else:
        env["INERTIA_KIT_CACHE_DIR"] = cache
    return env


class Failure(Exception):
    pass


@dataclass
class Timing:
    wall: float  # best wall time, s
    cpu: float | None  # best user + system time of the process, s (None without `resource`)
    codes: set[int]


def _cpu_of_children() -> float | None:
    if resource is None:
        return None
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run_once(
    command: list[str], env: dict[str, str], ok: tuple[int, ...]
) -> tuple[float, float | None, int]:
    cpu = _cpu_of_children()
    start = time.perf_counter()
    done = subprocess.run(command, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    elapsed = time.perf_counter() - start
    after = _cpu_of_children()
    if done.returncode not in ok:
        stderr = done.stderr.decode(errors="replace").strip()
        raise Failure(f"`{' '.join(command)}` exited {done.returncode}: {stderr[-2000:]}")
    return elapsed, None if cpu is None or after is None else after - cpu, done.returncode


def best(command: list[str], runs: int, env_of, ok=(0, 1)) -> Timing:
    """
    Best of ``runs`` runs, after one untimed run (bytecode, page cache); ``env_of(i)`` gives
    each run's environment.
    """
    return alternated(command, runs, [env_of], ok)[0]


def alternated(command: list[str], runs: int, env_ofs: list, ok=(0, 1)) -> list[Timing]:
    """
    The best of ``runs`` runs of ``command`` in each environment of ``env_ofs`` (``env_of(i)``
    gives run ``i``'s; each has one untimed run first), their runs taken in turn (one of each,
    ``runs`` times): a busy machine's slow minutes fall on all of them, so their ratio holds
    where best-of-N taken one after the other drifts by 10-20 %.
    """
    for env_of in env_ofs:
        run_once(command, env_of(-1), ok)
    samples: list[list[tuple[float, float | None, int]]] = [[] for _ in env_ofs]
    for index in range(runs):
        for sample, env_of in zip(samples, env_ofs, strict=True):
            sample.append(run_once(command, env_of(index), ok))
    timings = []
    for sample in samples:
        cpus = [cpu for _, cpu, _ in sample]
        timings.append(
            Timing(
                min(wall for wall, _, _ in sample),
                None if None in cpus else min(cpus),  # type: ignore[type-var]
                {code for _, _, code in sample},
            )
        )
    return timings


def wait_out_racy_window(files: list[Path]) -> None:
    """The cache does not store a file changed in the last 2 s (see physics.mesh_cache)."""
    newest = max(max(p.stat().st_mtime, p.stat().st_ctime) for p in files)
    delay = newest + 2.5 - time.time()
    if delay > 0:
        time.sleep(delay)


def per_mesh(stls: list[Path], cache: str, runs: int) -> tuple[float, float]:
    """Median seconds per mesh: computed (no cache), and a cache hit (this process)."""
    from inertia_kit.physics.mesh_cache import cached_mesh_solid
    from inertia_kit.physics.meshes import mesh_solid

    def median(function) -> float:
        samples = []
        for _ in range(runs):
            start = time.perf_counter()
            for path in stls:
                function(path)
            samples.append((time.perf_counter() - start) / len(stls))
        return float(np.median(samples))

    cold = median(lambda path: mesh_solid(path, (1.0, 1.0, 1.0)))
    warm = median(lambda path: cached_mesh_solid(path, (1.0, 1.0, 1.0), cache_dir=cache))
    return cold, warm


def import_profile(command: list[str], env: dict[str, str], runs: int, top: int = 12) -> str:
    """
    Where a run's import time goes: each module's self time (``-X importtime``), the least of
    ``runs`` runs, summed by package (``inertia_kit`` by module).
    """
    least: dict[str, float] = {}
    for _ in range(runs):
        done = subprocess.run(
            command,
            env={**env, "PYTHONPROFILEIMPORTTIME": "1"},
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
        )
        for line in done.stderr.decode(errors="replace").splitlines():
            match = re.match(r"import time:\s+(\d+) \|\s+\d+ \|\s*(\S+)", line)
            if match is not None:
                name, ms = match.group(2), int(match.group(1)) / 1e3
                least[name] = min(ms, least.get(name, ms))
    by_package: dict[str, float] = defaultdict(float)
    for name, ms in least.items():
        parts = name.split(".")
        by_package[".".join(parts[:2]) if parts[0] == "inertia_kit" else parts[0]] += ms
    ranked = sorted(by_package.items(), key=lambda item: -item[1])[:top]
    total = sum(by_package.values())
    return f"{total:.0f} ms: " + ", ".join(f"{name} {ms:.1f}" for name, ms in ranked)


def cpu_ratio(timing: Timing, base: Timing) -> str:
    """ ", cpu N.Nx": the same ratio in CPU time, steadier on a shared machine."""
    if timing.cpu is None or not base.cpu:
        return ""
    return f", cpu {timing.cpu / base.cpu:.2f}x"


def imported(command: list[str], env: dict[str, str]) -> set[str]:
    """Every module one run of ``command`` imports (``-X importtime``'s names)."""
    done = subprocess.run(
        command,
        env={**env, "PYTHONPROFILEIMPORTTIME": "1"},
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
    )
    names = re.findall(r"^import time:\s+\d+ \|\s+\d+ \|\s*(\S+)", done.stderr.decode(), re.M)
    return set(names)


def forbidden(modules: set[str], packages: tuple[str, ...]) -> list[str]:
    """The ``packages`` (or their submodules) among ``modules``."""
    return sorted(p for p in packages if any(m == p or m.startswith(f"{p}.") for m in modules))


# --- main ---------------------------------------------------------------------------------------


Row = tuple[str, Timing, str, "bool | None"]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=7, help="timed runs per case (best of)")
    parser.add_argument("--imports", action="store_true", help="print import time by package")
    parser.add_argument(
        "--robot",
        type=Path,
        action="append",
        default=[],
        help="also a real robot file (e.g. franka_ros' panda.urdf.xacro); repeatable",
    )
    arguments = parser.parse_args()
    runs = max(1, arguments.runs)

    primitives_urdf, meshes_urdf, stls, collada_urdf, daes = dataset()
    lint = console_script("inertia-lint")
    python = sys.executable
    print(
        f"python {platform.python_version()}, numpy {np.__version__}, {platform.machine()}, "
        f"{os.cpu_count()} CPUs; {lint}; best of {runs}"
    )

    rows: list[Row] = []
    stored = 0
    checks: list[tuple[str, list[str]]] = []
    ok = True
    with tempfile.TemporaryDirectory(prefix="inertia-kit-bench-") as scratch:
        warm_cache = os.path.join(scratch, "warm")

        made = itertools.count()
        robot_caches = [os.path.join(scratch, f"robot-{i}") for i in range(len(arguments.robot))]

        def fresh(index: int) -> dict[str, str]:
            # a new folder each call: another case's runs leave theirs filled
            return environment(os.path.join(scratch, f"cold-{next(made)}"))

        def warm(index: int) -> dict[str, str]:
            return environment(warm_cache)

        try:
            python_run = best([python, "-c", "pass"], runs, lambda i: environment(None), ok=(0,))
            rows.append(("python -c pass", python_run, "", None))
            bare = best([python, "-S", "-c", "pass"], runs, lambda i: environment(None), ok=(0,))
            rows.append(("python -S -c pass (no site)", bare, "", None))

            start_up = best([lint, str(primitives_urdf)], runs, fresh)
            ratio = start_up.wall / python_run.wall
            target = (
                f"<= {START_UP_RATIO:g}x python ({ratio:.1f}x{cpu_ratio(start_up, python_run)})"
            )
            rows.append((f"a: {LINKS} primitive links", start_up, target, ratio <= START_UP_RATIO))
            rows += above_the_floor(python, runs, start_up, python_run, ratio <= START_UP_RATIO)

            wait_out_racy_window(stls + daes)
            timing = best([lint, str(meshes_urdf)], runs, fresh)
            target = f"<= {COLD * 1e3:.0f} ms"
            rows.append(("b: 1M-triangle STL, cold", timing, target, timing.wall <= COLD))

            timing = best([lint, str(meshes_urdf)], runs, warm)  # its untimed run fills the cache
            stored = len(list(Path(warm_cache).glob("meshes-v*/*.json")))
            ratio = timing.wall / start_up.wall
            target = f"<= {WARM_RATIO:g}x a ({ratio:.2f}x{cpu_ratio(timing, start_up)})"
            rows.append(("b: 1M-triangle STL, warm", timing, target, ratio <= WARM_RATIO))

            timing = best([lint, str(meshes_urdf)], runs, lambda i: environment(None))
            rows.append(("b: cache off", timing, "", None))

            timing = best([lint, str(collada_urdf)], min(runs, 3), fresh)
            rows.append(("c: 1M-triangle DAE, cold", timing, "(best of 3 at most)", None))

            for robot, cache in zip(arguments.robot, robot_caches, strict=True):
                rows += real_robot(lint, robot, runs, fresh, cache, start_up)
        except Failure as error:
            print(f"FAIL: {error}")
            ok = False

        header = f"{'case':<30} {'wall ms':>8} {'cpu ms':>7}  {'exit':>4}  {'target':<40} result"
        print(f"{header}\n{'-' * len(header)}")
        for name, timing, target, passed in rows:
            result = "" if passed is None else ("PASS" if passed else "FAIL")
            cpu = f"{timing.cpu * 1e3:7.1f}" if timing.cpu is not None else f"{'-':>7}"
            codes = ",".join(str(c) for c in sorted(timing.codes))
            print(f"{name:<30} {timing.wall * 1e3:8.1f} {cpu}  {codes:>4}  {target:<40} {result}")
            ok &= passed is not False

        checks.append(
            (
                "a imports none of " + ", ".join(NOT_FOR_PLAIN_URDF + NOT_FOR_WARM_CACHE),
                forbidden(
                    imported([lint, str(primitives_urdf)], fresh(99)),
                    NOT_FOR_PLAIN_URDF + NOT_FOR_WARM_CACHE,
                ),
            )
        )
        warm_modules = imported([lint, str(meshes_urdf)], environment(warm_cache))
        checks.append(
            (
                "b warm imports none of " + ", ".join(NOT_FOR_WARM_CACHE),
                forbidden(warm_modules, NOT_FOR_WARM_CACHE),
            )
        )
        for robot, cache in zip(arguments.robot, robot_caches, strict=True):
            checks.append(
                (
                    f"{robot.name} warm imports none of " + ", ".join(NOT_FOR_WARM_CACHE),
                    forbidden(imported([lint, str(robot)], environment(cache)), NOT_FOR_WARM_CACHE),
                )
            )
        print()
        for name, found in checks:
            print(f"{name}: {'PASS' if not found else 'FAIL, imports ' + ', '.join(found)}")
            ok &= not found

        cold, hit = per_mesh(stls, warm_cache, runs)
        print(
            f"\nper 50k-triangle mesh, in process: computed {cold * 1e3:.2f} ms, "
            f"cache hit {hit * 1e3:.3f} ms (b's warm cache: {stored} entries)\n"
        )
        triangles = 2 * RINGS * SEGMENTS
        print("\n".join(lint_collada.report(daes, stls, triangles, min(runs, 3))))
        if arguments.imports:
            print("\nimport time (least self time of each module, by package, ms):")
            for name, command, env in [
                ("a", [lint, str(primitives_urdf)], fresh(100)),
                ("b cold", [lint, str(meshes_urdf)], fresh(101)),
                ("b warm", [lint, str(meshes_urdf)], environment(warm_cache)),
            ]:
                print(f"  {name}: {import_profile(command, env, min(runs, 7))}")
    print(f"\n{'PASS' if ok else 'FAIL'}")
    return 0 if ok else 1


#: what every run imports before any of ours, with the one BLAS thread our commands ask for
#: (``inertia_kit.cli``): issue 23's floor for the start-up target
FLOOR_IMPORTS = (
    "import os; os.environ.setdefault('OPENBLAS_NUM_THREADS', '1'); import numpy, lxml.etree, click"
)


def above_the_floor(
    python: str, runs: int, start_up: Timing, python_run: Timing, met: bool
) -> list[Row]:
    """
    Issue 23's other reading of the start-up target, for when numpy and lxml alone make 8×
    impossible: a within the floor of those imports plus at most 2× ``python -c pass``;
    judged only when the 8× reading (``met``) is not met.
    """
    floor = best([python, "-c", FLOOR_IMPORTS], runs, lambda i: environment(None), ok=(0,))
    ours = (start_up.wall - floor.wall) / python_run.wall
    target = f"<= 2x python ({ours:.1f}x{'; 8x met' if met else ''})"
    return [
        ("  numpy, lxml, click floor", floor, f"{floor.wall / python_run.wall:.1f}x python", None),
        ("  a above the floor", start_up, target, None if met else ours <= 2.0),
    ]


def real_robot(lint: str, path: Path, runs: int, fresh, cache: str, start_up: Timing) -> list[Row]:
    """``path`` linted cold (a new cache each run) and warm (``cache``), warm against ``a``."""
    if not path.is_file():
        raise Failure(f"--robot {path}: no such file")
    cold, warm = alternated([lint, str(path)], runs, [fresh, lambda i: environment(cache)])
    ratio = warm.wall / start_up.wall
    target = f"<= {WARM_RATIO:g}x a ({ratio:.2f}x{cpu_ratio(warm, start_up)})"
    rows: list[Row] = [
        (f"{path.name[:22]}, cold", cold, cold_target(cold, warm), cold.wall <= 2.0 * warm.wall),
        (f"{path.name[:22]}, warm", warm, target, ratio <= WARM_RATIO),
    ]
    # issue 23: warm within 2x the xacro expansion alone; for a plain URDF too (xacro reads
    # and prints it: PR2's generated pr2.urdf is one of the issue's two robots)
    command = [sys.executable, "-c", XACRO_ALONE, str(path)]
    alone = best(command, runs, lambda i: environment(cache))
    versus = warm.wall / alone.wall
    rows.append(
        (
            "  xacro alone",
            alone,
            f"warm <= 2x it ({versus:.2f}x{cpu_ratio(warm, alone)})",
            versus <= 2.0,
        )
    )
    return rows


#: the xacro expansion alone, printed as the ``xacro`` script prints it; ``$(find pkg)`` is the
#: folder ``pkg`` beside the robot's package (the ``xacro`` script needs ROS for it)
XACRO_ALONE = """
import os, sys, xacro
from xacro import substitution_args
def find(package):
    folder = os.path.dirname(os.path.abspath(sys.argv[1]))
    while not os.path.isfile(os.path.join(folder, "package.xml")):
        folder = os.path.dirname(folder)
    return os.path.join(os.path.dirname(folder), package)
substitution_args._eval_find = substitution_args._eval_dict["find"] = find
sys.stdout.write(xacro.process_file(sys.argv[1]).toprettyxml(indent="  "))
"""


def cold_target(cold: Timing, warm: Timing) -> str:
    """Issue 23: a cold run (empty caches) within twice the warm one."""
    return f"<= 2x warm ({cold.wall / warm.wall:.2f}x{cpu_ratio(cold, warm)})"


if __name__ == "__main__":
    sys.exit(main())
