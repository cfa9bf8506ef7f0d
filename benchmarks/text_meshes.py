"""
OBJ and COLLADA (DAE) mass properties against issue 23's targets (item 1), binary STL of the
same mesh as the reference, in one run.

    python benchmarks/text_meshes.py             # 1M and 10k triangles (generated once)
    python benchmarks/text_meshes.py --runs 5    # steadier, slower

The meshes are closed tori (as ``benchmarks/run.py``'s: tilted, off the origin), written once
under ``benchmarks/.data/text-v1/`` (gitignored) in the layouts exporters write:

- ``blender.obj``: Blender's OBJ exporter (``# Blender`` header, ``mtllib``, ``o``, ``v`` with 6
  decimals, ``vn`` with 4, ``vt`` with 6, ``s``, ``usemtl``, ``f v/vt/vn``, faces triangulated);
- ``plain.obj``: ``v`` with 8 decimals (as trimesh exports) and ``f a b c``;
- ``triangles.dae``: positions and normals of 7 significant digits (Blender, SolidWorks),
  ``<triangles>`` with VERTEX and NORMAL inputs at offsets 0 and 1;
- ``polylist.dae``: the same sources, ``<polylist>`` of quads (``<vcount>`` 4), two triangles
  each once fanned;
- ``.stl``: binary STL of the same vertices (float32).

What it prints, each measured in this run:

1. in process, best of ``--runs``: the file's triangles read (``mesh_formats.read_triangles``)
   and its mass properties (``meshes.mesh_solid`` + ``mass_properties``: read, closure,
   integration) in M triangles/s; target: OBJ and DAE mass properties >= 5 M/s at 1M;
2. the console script ``inertia-kit mass mesh FILE --density 1000`` (the one installed next to
   this Python, not a pyenv shim), wall and CPU time (the child's user + system time, from
   ``getrusage(RUSAGE_CHILDREN)``), best of ``--runs`` after one untimed run, at 1M, and each
   text file's time over the STL's; target: <= 3x, on wall time;
3. at 10k triangles, the same command against a plain trimesh script as a whole process
   (``trimesh.load(path)``, ``density = 1000``, ``print(mass_properties)``; a DAE loads as a
   Scene, which has no mass properties: ``force="mesh"`` for it), CPU time, best of 5;
   target: ours faster;
4. ours against trimesh's mass properties (``trimesh.load(path, force="mesh",
   process=False)``, density 1000): the largest of the mass difference relative to the mass,
   the COM difference relative to the body's size and the inertia difference relative to its
   largest entry; target: <= 1e-12.

The code measured is the ``inertia_kit`` this Python imports (printed first): run it with
``PYTHONPATH=CHECKOUT`` to measure another checkout; the child processes inherit the
environment.
"""

from __future__ import annotations

import os

# one core for numpy, here and in the child processes
for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_variable] = "1"
os.environ["INERTIA_KIT_NO_CACHE"] = "1"  # every run reads its mesh

import argparse  # noqa: E402
import platform  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
from lint import (  # noqa: E402  (this folder's)
    Failure,
    best,
    console_script,
    rotation,
    torus_quads,
    torus_surface,
)
from lint import write_stl as write_triangles  # noqa: E402
from mass_compare import difference  # noqa: E402  (this folder's)

ROOT = Path(__file__).resolve().parents[1]
DATA = Path(__file__).resolve().parent / ".data" / "text-v1"  # bump with the generators
DENSITY = 1000.0
SIZES = {"1M": (1000, 500), "10k": (100, 50)}  # rings x segments: 2 * r * s triangles
TEXT_FILES = ("blender.obj", "plain.obj", "triangles.dae", "polylist.dae")

RATE = 5e6  # triangles/s, in process, at 1M (issue 23, item 1)
CLI_RATIO = 3.0  # the CLI on OBJ/DAE over the same on STL, at 1M
TOLERANCE = 1e-12  # relative, against trimesh


# --- the meshes ---------------------------------------------------------------------------------


def torus(rings: int, segments: int):
    """
    (points, normals, uvs, quads, uv_quads): a closed torus as an exporter holds it, its
    quads ``(a, b, c, d)`` wound outwards, each split into ``(a, b, c), (a, c, d)`` as
    triangles; ``uvs`` a grid of ``(rings + 1) * (segments + 1)`` (a seam, as in Blender).
    """
    u, v, local = torus_surface(rings, segments, 0.30, 0.08)
    normal = np.stack(
        np.broadcast_arrays(np.cos(v) * np.cos(u), np.cos(v) * np.sin(u), np.sin(v)), axis=-1
    ).reshape(-1, 3)
    tilt = rotation((0.3, -0.2, 0.5))
    points = local @ tilt.T + (0.12, -0.05, 0.2)
    normals = normal @ tilt.T
    quads = torus_quads(rings, segments)
    i = np.arange(rings)[:, None]
    j = np.arange(segments)[None, :]
    grid = segments + 1
    uv_quads = np.stack(
        np.broadcast_arrays(
            i * grid + j, (i + 1) * grid + j, (i + 1) * grid + j + 1, i * grid + j + 1
        ),
        -1,
    ).reshape(-1, 4)
    uu, vv = np.meshgrid(
        np.linspace(0, 1, rings + 1), np.linspace(0, 1, segments + 1), indexing="ij"
    )
    uvs = np.stack([uu, vv], -1).reshape(-1, 2)
    return points, normals, uvs, quads, uv_quads


def triangles_of(quads: np.ndarray) -> np.ndarray:
    """Each quad's two triangles, ``(a, b, c), (a, c, d)`` (a fan from its first vertex)."""
    return quads[:, [0, 1, 2, 0, 2, 3]].reshape(-1, 3)


def rows(fmt: str, values: np.ndarray) -> str:
    """``fmt % row`` for every row, one a line."""
    return "".join(fmt % row for row in map(tuple, values.tolist()))


def write_blender_obj(path: Path, mesh) -> None:
    points, normals, uvs, quads, uv_quads = mesh
    v, t = triangles_of(quads) + 1, triangles_of(uv_quads) + 1
    corners = np.stack([v, t, v], -1).reshape(-1, 9)  # smooth shading: a normal a vertex
    text = (
        "# Blender 4.1.1\n# www.blender.org\nmtllib torus.mtl\no Torus\n"
        + rows("v %.6f %.6f %.6f\n", points)
        + rows("vn %.4f %.4f %.4f\n", normals)
        + rows("vt %.6f %.6f\n", uvs)
        + "s 1\nusemtl Material\n"
        + rows("f %d/%d/%d %d/%d/%d %d/%d/%d\n", corners)
    )
    _write(path, text)


def write_plain_obj(path: Path, mesh) -> None:
    points, _, _, quads, _ = mesh
    text = rows("v %.8f %.8f %.8f\n", points) + rows("f %d %d %d\n", triangles_of(quads) + 1)
    _write(path, text)


def write_dae(path: Path, mesh, polylist: bool) -> None:
    """Positions and normals, 7 significant digits, as Blender and SolidWorks write them."""
    points, normals, _, quads, _ = mesh
    index = quads if polylist else triangles_of(quads)
    p = " ".join(map(str, np.repeat(index.reshape(-1), 2).tolist()))  # VERTEX, NORMAL
    if polylist:
        vcount = " ".join(["4"] * len(quads))
        primitive = (
            f'<polylist material="Material-material" count="{len(quads)}">\n'
            + _INPUTS
            + f"          <vcount>{vcount}</vcount>\n          <p>{p}</p>\n        </polylist>"
        )
    else:
        primitive = (
            f'<triangles material="Material-material" count="{len(index)}">\n'
            + _INPUTS
            + f"          <p>{p}</p>\n        </triangles>"
        )
    text = f"""<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1" \
xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance">
  <asset>
    <contributor><author>Blender User</author><authoring_tool>Blender 2.93.0</authoring_tool>
    </contributor>
    <created>2024-01-01T00:00:00</created><modified>2024-01-01T00:00:00</modified>
    <unit name="meter" meter="1"/>
    <up_axis>Z_UP</up_axis>
  </asset>
  <library_geometries>
    <geometry id="Torus-mesh" name="Torus">
      <mesh>
{_source("Torus-mesh-positions", points)}
{_source("Torus-mesh-normals", normals)}
        <vertices id="Torus-mesh-vertices">
          <input semantic="POSITION" source="#Torus-mesh-positions"/>
        </vertices>
        {primitive}
      </mesh>
    </geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="Scene" name="Scene">
      <node id="Torus" name="Torus" type="NODE">
        <matrix sid="transform">1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1</matrix>
        <instance_geometry url="#Torus-mesh" name="Torus"/>
      </node>
    </visual_scene>
  </library_visual_scenes>
  <scene>
    <instance_visual_scene url="#Scene"/>
  </scene>
</COLLADA>
"""
    _write(path, text)


_INPUTS = (
    '          <input semantic="VERTEX" source="#Torus-mesh-vertices" offset="0"/>\n'
    '          <input semantic="NORMAL" source="#Torus-mesh-normals" offset="1"/>\n'
)


def _source(ident: str, values: np.ndarray) -> str:
    floats = " ".join(map("{:.7g}".format, values.reshape(-1).tolist()))
    return (
        f'        <source id="{ident}">\n'
        f'          <float_array id="{ident}-array" count="{values.size}">{floats}</float_array>\n'
        f"          <technique_common>\n"
        f'            <accessor source="#{ident}-array" count="{len(values)}" stride="3">\n'
        f'              <param name="X" type="float"/>\n'
        f'              <param name="Y" type="float"/>\n'
        f'              <param name="Z" type="float"/>\n'
        f"            </accessor>\n"
        f"          </technique_common>\n"
        f"        </source>"
    )


def write_stl(path: Path, mesh) -> None:
    points, _, _, quads, _ = mesh
    write_triangles(path, points.astype(np.float32)[triangles_of(quads)])


def _write(path: Path, text: str) -> None:
    partial = path.with_suffix(".partial")
    partial.write_text(text, encoding="ascii")
    partial.replace(path)


def dataset(label: str) -> tuple[dict[str, Path], int]:
    """The files of one size (their suffix and name -> path), generated when missing."""
    rings, segments = SIZES[label]
    base = DATA / f"torus-{rings}x{segments}"
    files = {name: Path(f"{base}-{name}") for name in TEXT_FILES}
    files["stl"] = base.with_suffix(".stl")
    missing = [name for name, path in files.items() if not path.exists()]
    if missing:
        print(f"generating {base.name} ({label} triangles): {', '.join(missing)} ...", flush=True)
        DATA.mkdir(parents=True, exist_ok=True)
        mesh = torus(rings, segments)
        writers = {
            "blender.obj": lambda p: write_blender_obj(p, mesh),
            "plain.obj": lambda p: write_plain_obj(p, mesh),
            "triangles.dae": lambda p: write_dae(p, mesh, polylist=False),
            "polylist.dae": lambda p: write_dae(p, mesh, polylist=True),
            "stl": lambda p: write_stl(p, mesh),
        }
        for name in missing:
            writers[name](files[name])
    for path in files.values():
        path.read_bytes()  # into the page cache
    return files, 2 * rings * segments


# --- in process ---------------------------------------------------------------------------------


def best_time(function, runs: int):
    best, result = float("inf"), None
    for _ in range(runs):
        start = time.perf_counter()
        result = function()
        best = min(best, time.perf_counter() - start)
    return best, result


def in_process(path: Path, runs: int):
    """Best seconds of the triangles read, and of the mass properties; the latter."""
    from inertia_kit.physics.mesh_formats import read_triangles
    from inertia_kit.physics.meshes import mesh_solid

    read, (triangles, _) = best_time(lambda: read_triangles(path), runs)
    count = len(triangles)
    del triangles
    solid, properties = best_time(lambda: mesh_solid(path).mass_properties(density=DENSITY), runs)
    return read, solid, properties, count


def trimesh_properties(path: Path):
    """trimesh's mass, COM and inertia at DENSITY, and the body's size."""
    import trimesh

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mesh = trimesh.load(str(path), force="mesh", process=False)
    mesh.density = DENSITY
    properties = mesh.mass_properties
    size = float(np.ptp(mesh.bounds, axis=0).max())
    return (properties.mass, properties.center_mass, properties.inertia), size


# --- whole processes ----------------------------------------------------------------------------


def best_process(command: list[str], runs: int) -> tuple[float, float | None]:
    """Best wall and best CPU seconds of ``runs`` runs, after an untimed one (lint.py's)."""
    try:
        timing = best(command, runs, lambda _: dict(os.environ), ok=(0,))
    except Failure as failure:
        sys.exit(str(failure))
    return timing.wall, timing.cpu


def trimesh_script(path: Path) -> list[str]:
    force = ', force="mesh"' if path.suffix == ".dae" else ""
    code = (
        f"import trimesh; m = trimesh.load({str(path)!r}{force}); m.density = 1000; "
        "print(m.mass_properties)"
    )
    return [sys.executable, "-c", code]


def _ms(seconds: float | None) -> str:
    return f"{'-':>8}" if seconds is None else f"{seconds * 1e3:8.1f}"


def verdict(ok: bool) -> str:
    return "PASS" if ok else "FAIL"


# --- main ---------------------------------------------------------------------------------------


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=3, help="timed runs per case (best of)")
    arguments = parser.parse_args()
    runs = max(1, arguments.runs)

    import trimesh

    import inertia_kit

    script = console_script("inertia-kit")
    child = subprocess.run(
        [sys.executable, "-c", "import inertia_kit; print(inertia_kit.__file__)"],
        capture_output=True,
        text=True,
    ).stdout.strip()
    print(
        f"python {platform.python_version()}, numpy {np.__version__}, trimesh "
        f"{trimesh.__version__}, {platform.machine()}, {os.cpu_count()} CPUs; best of {runs}\n"
        f"inertia_kit: {Path(inertia_kit.__file__).parent} (children: {Path(child).parent})\n"
        f"CLI: {script}"
    )
    datasets = {label: dataset(label) for label in SIZES}
    names = ("stl", *TEXT_FILES)
    ok = True

    # 1. in process, and 4. against trimesh
    header = (
        f"{'file':<34} {'triangles':>10} {'MB':>6} {'read M/s':>9} {'ms':>7} "
        f"{'mass M/s':>9} {'ms':>7} {'rel diff':>9}  target"
    )
    print(f"\nin process, best of {runs}: read_triangles, and mesh_solid + mass_properties")
    print(f"{header}\n{'-' * len(header)}")
    for label, (files, count) in datasets.items():
        for name in names:
            path = files[name]
            read, solid, properties, found = in_process(path, runs)
            assert found == count, (path, found, count)
            reference, size = trimesh_properties(path)
            diff = difference(properties, reference, size)
            checks = [diff <= TOLERANCE]
            target = f"diff <= {TOLERANCE:g}"
            if label == "1M" and name != "stl":
                checks.append(count / solid >= RATE)
                target = f">= {RATE / 1e6:g} M/s, {target}"
            passed = all(checks)
            ok &= passed
            print(
                f"{path.name:<34} {count:>10,} {path.stat().st_size / 1e6:6.1f} "
                f"{count / read / 1e6:9.2f} {read * 1e3:7.1f} {count / solid / 1e6:9.2f} "
                f"{solid * 1e3:7.1f} {diff:9.1e}  {target}: {verdict(passed)}"
            )

    # 2. the CLI at 1M, against STL
    files, count = datasets["1M"]
    print(f"\n`inertia-kit mass mesh FILE --density 1000`, {count:,} triangles, best of {runs}")
    header = f"{'file':<34} {'wall ms':>8} {'cpu ms':>8}  {'/ STL':>16}  target"
    print(f"{header}\n{'-' * len(header)}")
    stl = None
    for name in names:
        wall, cpu = best_process(
            [script, "mass", "mesh", str(files[name]), "--density", "1000"], runs
        )
        if stl is None:
            stl = (wall, cpu)
            print(f"{files[name].name:<34} {_ms(wall)} {_ms(cpu)}")
            continue
        ratio = wall / stl[0]
        cpu_ratio = f", cpu {cpu / stl[1]:.2f}x" if cpu is not None and stl[1] else ""
        passed = ratio <= CLI_RATIO
        ok &= passed
        print(
            f"{files[name].name:<34} {_ms(wall)} {_ms(cpu)}  {ratio:5.2f}x{cpu_ratio:<11}  "
            f"<= {CLI_RATIO:g}x STL (wall): {verdict(passed)}"
        )

    # 3. the CLI at 10k, against a plain trimesh script
    files, count = datasets["10k"]
    print(f"\n{count:,} triangles, whole processes, best of 5: ours against a trimesh script")
    header = f"{'file':<34} {'ours wall':>9} {'cpu ms':>8} {'trimesh':>9} {'cpu ms':>8}  target"
    print(f"{header}\n{'-' * len(header)}")
    for name in names:
        path = files[name]
        ours = best_process([script, "mass", "mesh", str(path), "--density", "1000"], 5)
        theirs = best_process(trimesh_script(path), 5)
        on = 1 if ours[1] is not None and theirs[1] is not None else 0  # CPU, else wall
        passed = ours[on] < theirs[on]
        target = f"ours faster ({('wall', 'cpu')[on]}, {theirs[on] / ours[on]:.1f}x)"
        if name != "stl":
            ok &= passed
        print(
            f"{path.name:<34} {_ms(ours[0]):>9} {_ms(ours[1])} {_ms(theirs[0]):>9} "
            f"{_ms(theirs[1])}  {target}: {verdict(passed)}"
        )

    print(
        f"\n{verdict(ok)} (all rows above; the targets: OBJ/DAE mass properties >= "
        f"{RATE / 1e6:g} M triangles/s at 1M, in "
        f"process; the CLI on them <= {CLI_RATIO:g}x its time on STL at 1M; faster than trimesh "
        f"at 10k; mass properties within {TOLERANCE:g} of trimesh's)"
    )
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
