"""
The review page of a robot with 1M mesh triangles: page size and time to first frame.

    python benchmarks/view.py             # best of 3 loads
    python benchmarks/view.py --runs 5

The robot: four links in a chain, each a UV sphere of 250 000 triangles (binary STL, written
with numpy) as visual and collision geometry, with its solid-sphere inertial. Its page is made
by ``inertia-kit view`` (the console script next to this Python), whose meshes (four distinct
ones, each carried once) are decimated to the default triangle budget (300 000) for display.
Where the scene builder (inertia_kit.view.scene) is not installed yet, a stand-in
scene with the budget's 300 000 triangles (what the builder hands the page after decimation) is
rendered instead, and the output says so.

Printed: the page's size (target < 10 MB), the command's wall time, and, loading the page in
headless Chromium with the network off (best of N): the time to first frame by the page's own
clock from navigation start (target < 3 s), and the wall time from launching the browser to
the page being ready.
"""

from __future__ import annotations

import argparse
import base64
import importlib.util
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

TRIANGLES = 1_000_000
LINKS = 4
SIZE_MB = 10.0
FIRST_FRAME_S = 3.0


def sphere(triangles: int, radius: float) -> tuple[np.ndarray, np.ndarray]:
    """A UV sphere of about ``triangles`` triangles: (vertices, faces), counter-clockwise."""
    rings = max(int(np.sqrt(triangles / 4)), 3)
    segments = 2 * rings
    theta = np.linspace(0, np.pi, rings + 1)
    phi = np.linspace(0, 2 * np.pi, segments, endpoint=False)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    vertices = radius * np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], -1)
    index = np.arange((rings + 1) * segments).reshape(rings + 1, segments)
    a, b = index[:-1], np.roll(index[:-1], -1, axis=1)
    c, d = index[1:], np.roll(index[1:], -1, axis=1)
    faces = np.concatenate([np.stack([a, c, d], -1), np.stack([a, d, b], -1)]).reshape(-1, 3)
    return vertices.reshape(-1, 3), faces


def write_stl(path: Path, vertices: np.ndarray, faces: np.ndarray) -> None:
    record = np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    data = np.zeros(len(faces), dtype=record)
    data["v"] = vertices[faces]
    path.write_bytes(b"benchmark".ljust(80) + np.uint32(len(faces)).tobytes() + data.tobytes())


def robot(folder: Path) -> tuple[Path, int]:
    """The URDF of the 1M-triangle robot, its meshes beside it."""
    per_link = TRIANGLES // LINKS
    parts = ['<robot name="million">']
    for i in range(LINKS):
        radius = 0.1 + 0.01 * i  # four distinct meshes: the page carries each once
        vertices, faces = sphere(per_link, radius)
        write_stl(folder / f"sphere{i}.stl", vertices, faces)
        mass = 1000 * 4 / 3 * np.pi * radius**3
        inertia = 2 / 5 * mass * radius**2
        geometry = f'<geometry><mesh filename="sphere{i}.stl"/></geometry>'
        parts.append(
            f'<link name="link{i}"><visual>{geometry}</visual><collision>{geometry}</collision>'
            f'<inertial><mass value="{mass:.6f}"/><inertia ixx="{inertia:.8f}" ixy="0" ixz="0" '
            f'iyy="{inertia:.8f}" iyz="0" izz="{inertia:.8f}"/></inertial></link>'
        )
        if i:
            parts.append(
                f'<joint name="j{i}" type="revolute"><parent link="link{i - 1}"/>'
                f'<child link="link{i}"/><origin xyz="0 0 0.25"/><axis xyz="0 1 0"/>'
                '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
            )
    parts.append("</robot>")
    path = folder / "million.urdf"
    path.write_text("".join(parts), encoding="utf-8")
    return path, len(faces) * LINKS


def stand_in_page(folder: Path, budget: int = 300_000) -> Path:
    """The page of a scene with ``budget`` triangles, built by hand (no scene builder yet)."""
    from inertia_kit.view.page import render_page

    sys.path.insert(0, str(ROOT / "tests"))
    from kit.scenes import link, solid_box, translation

    vertices, faces = sphere(budget // LINKS, 0.1)
    mesh = {
        "positions": base64.b64encode(vertices.astype("<f4").tobytes()).decode(),
        "indices": base64.b64encode(faces.astype("<u4").tobytes()).decode(),
        "triangles": len(faces),
        "source_triangles": TRIANGLES // LINKS,
        "name": "sphere.stl",
    }
    links = []
    for i in range(LINKS):
        parent = f"link{i - 1}" if i else None
        declared = solid_box(4.19, (0.16, 0.16, 0.16), (0, 0, 0))
        record = link(f"link{i}", parent, world=translation(0, 0, 0.25 * i), declared=declared)
        record["geometry"] = dict(record["declared"], density=1000.0, basis="stand-in")
        # a mesh of its own, as four mesh files would give, drawn at its size (no scaling)
        record["visuals"][0].update(mesh=i, transform=translation(0, 0, 0))
        links.append(record)
    scene = {"format": 1, "robot": "million", "file": "million.urdf", "links": links,
             "meshes": [dict(mesh, name=f"sphere{i}.stl") for i in range(LINKS)],
             "findings_elsewhere": [],
             "budget": {"triangles": LINKS * len(faces), "decimated": True}}  # fmt: skip
    page = folder / "million.html"
    page.write_text(render_page(scene), encoding="utf-8")
    return page


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument("--runs", type=int, default=3)
    runs = parser.parse_args().runs
    from inertia_kit.view.screenshot import capture, find_chromium

    with tempfile.TemporaryDirectory(prefix="inertia-kit-view-bench-") as scratch:
        folder = Path(scratch)
        urdf, triangles = robot(folder)
        drawn = 0
        page = folder / "million.html"
        if importlib.util.find_spec("inertia_kit.view.scene") is not None:
            command = [str(Path(sys.executable).with_name("inertia-kit")), "view", str(urdf)]
            started = time.perf_counter()
            subprocess.run([*command, "-o", str(page)], check=True)
            made = f"inertia-kit view: {time.perf_counter() - started:.1f} s"
            text = page.read_text(encoding="utf-8")
            data = text[
                text.index('id="scene-data">') + 16 : text.index(
                    "</script>", text.index('id="scene-data">')
                )
            ]
            drawn = json.loads(data)["budget"]["triangles"]
        else:
            page = stand_in_page(folder)
            made = "STAND-IN: inertia_kit.view.scene missing, a hand-built scene"
            drawn = LINKS * len(sphere(300_000 // LINKS, 0.1)[1])
        size = page.stat().st_size / 1e6
        print(f"robot: {LINKS} links, {triangles} mesh triangles, {drawn} drawn; page: {made}")
        print(f"page size: {size:.2f} MB (target < {SIZE_MB:.0f} MB): "
              f"{'ok' if size < SIZE_MB else 'FAIL'}")  # fmt: skip
        if find_chromium() is None:
            print("no Chromium: time to first frame not measured")
            return 1
        frames, walls = [], []
        for _ in range(runs):
            started = time.perf_counter()
            loaded = capture(page, timeout=120)
            walls.append(time.perf_counter() - started)
            frames.append(loaded.first_frame_ms / 1000)
            if loaded.errors:
                print(f"page errors: {loaded.errors}")
                return 1
        first = min(frames)
        print(f"first frame: {first:.2f} s from navigation start, best of {runs} "
              f"({', '.join(f'{f:.2f}' for f in frames)}) (target < {FIRST_FRAME_S:.0f} s): "
              f"{'ok' if first < FIRST_FRAME_S else 'FAIL'}")  # fmt: skip
        print(f"browser launch to ready: {min(walls):.2f} s best of {runs}")
        return 0 if size < SIZE_MB and first < FIRST_FRAME_S else 1


if __name__ == "__main__":
    sys.exit(main())
