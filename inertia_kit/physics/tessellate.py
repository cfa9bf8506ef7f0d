"""
Closed triangle meshes of URDF primitives whose volume is exact: each ring of a revolved
profile is widened so its polygon has the circle's area, and the caps of spheres and capsules
are pushed out so each keeps its exact volume. For boolean operations (``unions``), where a
tessellation must stand in for the exact solid.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray


def half_extents(kind: str, dimensions: tuple[float, ...]) -> NDArray[np.float64]:
    if kind == "box":
        return 0.5 * np.array(dimensions)
    if kind == "cylinder":
        radius, length = dimensions
        return np.array([radius, radius, 0.5 * length])
    if kind == "sphere":
        return np.full(3, dimensions[0])
    if kind == "capsule":
        radius, length = dimensions
        return np.array([radius, radius, radius + 0.5 * length])
    return np.array(dimensions)  # ellipsoid


def primitive_mesh(
    kind: str, dimensions: tuple[float, ...], segments: int
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Volume-preserving mesh of a primitive in its own frame."""
    if kind == "box":
        return _box_mesh(np.array(dimensions))
    arc = max(2, segments // 4)
    if kind == "cylinder":
        radius, length = dimensions
        half = 0.5 * length
        profile = np.array([[0.0, -half], [radius, -half], [radius, half], [0.0, half]])
        return _revolved(profile, segments)
    if kind == "capsule":
        radius, length = dimensions
        return _revolved(_capsule_profile(radius, 0.5 * length, arc), segments)
    if kind == "sphere":
        return _revolved(_capsule_profile(dimensions[0], 0.0, arc), segments)
    points, faces = _revolved(_capsule_profile(1.0, 0.0, arc), segments)  # ellipsoid
    return points * np.array(dimensions), faces


def _box_mesh(size: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)
    # vertex index = 4·[x>0] + 2·[y>0] + [z>0]; two outward triangles per face
    # fmt: off
    faces = np.array([
        [0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5],  # -x, +x
        [0, 4, 5], [0, 5, 1], [2, 3, 7], [2, 7, 6],  # -y, +y
        [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3],  # -z, +z
    ])
    # fmt: on
    return 0.5 * signs * size, faces


def _capsule_profile(radius: float, half_length: float, arc: int) -> NDArray[np.float64]:
    """
    (r, z) meridian of a capsule (a sphere when ``half_length`` is 0) from the bottom pole to
    the top pole, ``arc`` segments per quarter circle.

    The arc's interior vertices sit at ``t·radius``, with ``t`` chosen so the polygonal quarter
    disc has the exact first moment about the axis, ``radius³/3``: revolved, each cap then has
    its exact volume (Pappus).
    """
    angles = np.linspace(0.0, 0.5 * np.pi, arc + 1)  # from the equator to the pole
    interior = np.ones(arc + 1, dtype=bool)
    interior[[0, -1]] = False
    # Σ over fan triangles of s_j s_k (s_j cos θ_j + s_k cos θ_k) (k = j + 1) as a polynomial
    # in t, where s = t on interior vertices and 1 at the ends
    coefficients = np.zeros(4)
    j, k = np.arange(arc), np.arange(1, arc + 1)
    np.add.at(coefficients, 2 * interior[j] + interior[k], np.cos(angles[j]))
    np.add.at(coefficients, interior[j] + 2 * interior[k], np.cos(angles[k]))
    target = 2.0 / math.sin(angles[1])  # the exact first moment, in units of sin(Δ) radius³ / 6
    t = 1.0
    powers = np.arange(4)
    for _ in range(50):
        value = coefficients @ t**powers - target
        slope = coefficients[1:] @ (powers[1:] * t ** (powers[1:] - 1))
        step = value / slope
        t -= step
        if abs(step) < 1e-15:
            break
    scale = np.where(interior, t, 1.0) * radius
    r, z = scale * np.cos(angles), scale * np.sin(angles)
    top = np.column_stack([r, half_length + z])
    bottom = np.column_stack([r, -half_length - z])[::-1]
    if half_length == 0.0:
        bottom = bottom[:-1]  # one equator ring for a sphere
    return np.vstack([bottom, top])


def _revolved(
    profile: NDArray[np.float64], segments: int
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """
    Closed mesh of a meridian ``profile`` (p, 2) of (r, z) points revolved about z, from a pole
    (r = 0) to a pole.

    Each ring is a regular polygon whose circumradius is scaled by
    ``sqrt(2π / (n sin(2π/n)))``, so every cross-section has the exact area ``π r²``.
    """
    n = segments
    stretch = math.sqrt(2.0 * math.pi / (n * math.sin(2.0 * math.pi / n)))
    rings = profile[1:-1]
    angle = 2.0 * np.pi * np.arange(n) / n
    radius = stretch * rings[:, :1]
    ring_points = np.stack(
        [radius * np.cos(angle), radius * np.sin(angle), np.repeat(rings[:, 1:], n, axis=1)],
        axis=-1,
    ).reshape(-1, 3)
    top = 1 + len(rings) * n
    points = np.vstack([[0.0, 0.0, profile[0, 1]], ring_points, [0.0, 0.0, profile[-1, 1]]])
    j = np.arange(n)
    nxt = (j + 1) % n
    first = 1 + (np.arange(len(rings) - 1) * n)[:, None]  # start of each ring but the last
    a, b, c, d = first + j, first + nxt, first + n + nxt, first + n + j
    last = 1 + (len(rings) - 1) * n
    faces = np.vstack(
        [
            np.column_stack([np.zeros(n, dtype=np.int64), 1 + nxt, 1 + j]),
            np.stack([a, b, c], axis=-1).reshape(-1, 3),
            np.stack([a, c, d], axis=-1).reshape(-1, 3),
            np.column_stack([np.full(n, top), last + j, last + nxt]),
        ]
    )
    return points, faces
