"""
Mesh files for fuzz inputs: binary and ASCII STL, OBJ, COLLADA and PLY, written by the test
kit's writers (kit.meshes), and broken ones: empty, truncated, a count that promises more
triangles than the file holds (or 4 billion), NaN and infinite coordinates, open and inverted
surfaces, millimetre-sized parts, garbage, a many-triangle torus.
"""

from __future__ import annotations

import random
import struct

import numpy as np
from kit.meshes import (
    ascii_stl,
    binary_stl,
    box_triangles,
    obj,
    square_triangles,
    textured_collada,
    torus_triangles,
)

from fuzz.tree import Tree

KINDS = (
    "binary", "binary", "ascii", "obj", "dae", "ply", "mm", "open", "inverted", "empty",
    "garbage", "truncated", "huge-count", "nan", "torus", "ascii-broken",
)  # fmt: skip


def _box(rng: random.Random) -> np.ndarray:
    size = [rng.uniform(0.02, 0.5) for _ in range(3)]
    low = [rng.uniform(-0.3, 0.0) for _ in range(3)]
    return box_triangles(size, low)


def mesh_bytes(rng: random.Random, kind: str) -> tuple[str, bytes]:
    """(file suffix, content) of one mesh of ``kind``."""
    triangles = _box(rng)
    with np.errstate(over="ignore", invalid="ignore"):
        if kind == "binary":
            return ".stl", binary_stl(triangles)
        if kind == "ascii":
            return ".stl", ascii_stl(triangles).encode("ascii")
        if kind == "ascii-broken":
            text = ascii_stl(triangles)
            cut = rng.randrange(len(text))
            return ".stl", (
                text[:cut] + rng.choice(["nan", "1e999", "vertex", "\x00", "endsolid"]) + text[cut:]
            ).encode()
        if kind == "obj":
            return ".obj", obj(triangles).encode("ascii")
        if kind == "dae":
            return ".dae", textured_collada(triangles, image="missing.png").encode("utf-8")
        if kind == "ply":
            vertices = triangles.reshape(-1, 3)
            head = (
                f"ply\nformat ascii 1.0\nelement vertex {len(vertices)}\n"
                "property float x\nproperty float y\nproperty float z\n"
                f"element face {len(triangles)}\nproperty list uchar int vertex_indices\n"
                "end_header\n"
            )
            body = "".join(f"{x} {y} {z}\n" for x, y, z in vertices.tolist())
            body += "".join(f"3 {3 * i} {3 * i + 1} {3 * i + 2}\n" for i in range(len(triangles)))
            return ".ply", (head + body).encode("ascii")
        if kind == "mm":
            return ".stl", binary_stl(triangles * 1000)
        if kind == "open":
            return ".stl", binary_stl(square_triangles() * 0.1)
        if kind == "inverted":
            return ".stl", binary_stl(triangles[:, ::-1, :])
        if kind == "empty":
            return rng.choice([".stl", ".obj", ".dae"]), b""
        if kind == "garbage":
            return rng.choice([".stl", ".obj", ".dae", ".ply", ".glb"]), rng.randbytes(
                rng.choice([10, 84, 200, 5000])
            )
        if kind == "truncated":
            data = binary_stl(triangles)
            return ".stl", data[: rng.randrange(80, len(data))]
        if kind == "huge-count":
            data = binary_stl(triangles)
            count = rng.choice([0xFFFFFFFF, 10**8, 13])
            return ".stl", data[:80] + struct.pack("<I", count) + data[84:]
        if kind == "nan":
            broken = triangles.copy()
            broken[rng.randrange(12), rng.randrange(3), rng.randrange(3)] = rng.choice(
                [np.nan, np.inf, -np.inf, 1e38, 3.4e38]
            )
            return ".stl", binary_stl(broken)
        if kind == "torus":
            rings = rng.choice([24, 64, 160])
            return ".stl", binary_stl(torus_triangles(0.1, 0.03, rings, rings // 2))
    raise ValueError(kind)


def add_meshes(rng: random.Random, tree: Tree, folder: str, count: int) -> list[str]:
    """``count`` meshes in ``tree``'s ``folder``; their file names."""
    names = []
    for index in range(count):
        kind = rng.choice(KINDS)
        suffix, data = mesh_bytes(rng, kind)
        if rng.random() < 0.05:
            suffix = suffix.upper()
        name = f"part{index}{suffix}"
        tree.put(f"{folder}/{name}", data)
        names.append(name)
    return names
