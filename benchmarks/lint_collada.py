"""
COLLADA for ``benchmarks/lint.py``: the generated tori written as DAE, and where reading one
goes, in this process: pycollada's parse, the rest of trimesh's loader, and our code (closure,
integration), from one cProfile run per file; triangles/s of DAE next to the same triangles as
binary STL; and the readers a DAE could go through, timed on the same files.
"""

from __future__ import annotations

import cProfile
import pstats
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

#: pycollada's errors trimesh's loader ignores (trimesh.exchange.dae.load_collada)
_IGNORED = (
    "DaeError",
    "DaeIncompleteError",
    "DaeMalformedError",
    "DaeBrokenRefError",
    "DaeUnsupportedError",
)


def write_dae(path: Path, points: np.ndarray, faces: np.ndarray) -> None:
    """An indexed triangle mesh as COLLADA 1.4.1, in metres: positions only, one node."""
    floats = " ".join(repr(float(v)) for v in points.reshape(-1))
    indices = " ".join(map(str, faces.reshape(-1).tolist()))
    text = f"""<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries>
    <geometry id="part" name="part"><mesh>
      <source id="part-positions">
        <float_array id="part-positions-array" count="{points.size}">{floats}</float_array>
        <technique_common>
          <accessor source="#part-positions-array" count="{len(points)}" stride="3">
            <param name="X" type="float"/><param name="Y" type="float"/>
            <param name="Z" type="float"/>
          </accessor>
        </technique_common>
      </source>
      <vertices id="part-vertices"><input semantic="POSITION" source="#part-positions"/></vertices>
      <triangles count="{len(faces)}">
        <input semantic="VERTEX" source="#part-vertices" offset="0"/>
        <p>{indices}</p>
      </triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="scene"><node id="part-node"><instance_geometry url="#part"/></node>
    </visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
"""
    partial = path.with_suffix(".partial")
    partial.write_text(text)
    partial.replace(path)


# --- the readers ---------------------------------------------------------------------------------


def pycollada_parse(path: Path) -> None:
    """pycollada's document, as trimesh's loader asks for it: the parse alone."""
    import collada

    collada.Collada(str(path), ignore=[getattr(collada.common, name) for name in _IGNORED])


def pycollada_triangles(path: Path) -> np.ndarray:
    """The placed triangles through pycollada's own bound-geometry API, without trimesh."""
    import collada

    document = collada.Collada(
        str(path), ignore=[getattr(collada.common, name) for name in _IGNORED]
    )
    parts = []
    for geometry in document.scene.objects("geometry"):
        for primitive in geometry.primitives():
            if isinstance(primitive, collada.polylist.BoundPolylist):
                primitive = primitive.triangleset()
            if isinstance(primitive, collada.triangleset.BoundTriangleSet):
                parts.append(primitive.vertex[primitive.vertex_index])
    return np.concatenate(parts)


def trimesh_scene(path: Path) -> None:
    """trimesh's loader as ``physics.mesh_formats`` calls it (``process=False``)."""
    import trimesh

    trimesh.load_scene(str(path), file_type="dae", process=False)


def our_read(path: Path) -> None:
    """``physics.mesh_formats``' read: trimesh's scene flattened into placed triangles."""
    from inertia_kit.physics.mesh_formats import _read_scene

    _read_scene(path, ".dae")


def mesh_solid(path: Path) -> None:
    """What lint does with a mesh on a cache miss: read, check closure, integrate."""
    from inertia_kit.physics.meshes import mesh_solid as solid

    solid(path)


def best_seconds(function: Callable[[Path], object], files: list[Path], runs: int) -> float:
    """Best of ``runs`` total seconds for ``function`` over every file."""
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        for path in files:
            function(path)
        times.append(time.perf_counter() - start)
    return min(times)


def where_time_goes(files: list[Path]) -> dict[str, float]:
    """
    Seconds of ``mesh_solid`` over ``files`` under cProfile, split into pycollada's parse
    (``Collada.__init__``), the rest of ``trimesh.load_scene``, and everything else (ours:
    flattening the scene, the closure check and the integration).
    """
    profile = cProfile.Profile()
    profile.enable()
    for path in files:
        mesh_solid(path)
    profile.disable()
    stats = pstats.Stats(profile).stats  # type: ignore[attr-defined]

    def cumulative(file_part: str, name: str) -> float:
        return sum(
            row[3]
            for (file, _, function), row in stats.items()
            if function == name and file_part in file.replace("\\", "/")
        )

    total = cumulative("inertia_kit/physics/meshes.py", "mesh_solid")
    parse = cumulative("collada/__init__.py", "__init__")
    load = cumulative("trimesh/exchange/load.py", "load_scene")
    return {"pycollada parse": parse, "trimesh, rest": load - parse, "ours": total - load}


def report(dae: list[Path], stl: list[Path], triangles: int, runs: int) -> list[str]:
    """The COLLADA section's lines: where the time goes, then triangles/s by reader."""
    for path in dae[:1] + stl[:1]:  # imports and first-call costs out of the timings
        mesh_solid(path)
        pycollada_triangles(path) if path.suffix == ".dae" else None
    split = where_time_goes(dae)
    total = sum(split.values())
    lines = [
        f"cold DAE, in process, {len(dae)} files x {triangles:,} triangles "
        f"(cProfile, {total * 1e3:.0f} ms in all):",
        "  " + ", ".join(f"{name} {s * 1e3:.0f} ms ({s / total:.0%})" for name, s in split.items()),
        "triangles/s, best of " + str(runs) + " (M = million):",
    ]
    count = triangles * len(dae)
    readers = [
        ("binary STL: mesh_solid (ours, no trimesh)", mesh_solid, stl),
        ("DAE: mesh_solid (ours, no trimesh)", mesh_solid, dae),
        ("DAE: read only, trimesh.load_scene(process=False)", trimesh_scene, dae),
        ("DAE: read only, pycollada parse alone", pycollada_parse, dae),
        ("DAE: read only, pycollada bound triangles", pycollada_triangles, dae),
    ]
    for name, function, files in readers:
        seconds = best_seconds(function, files, runs)
        lines.append(f"  {name:<52} {count / seconds / 1e6:6.2f} M/s  {seconds * 1e3:7.0f} ms")
    return lines
