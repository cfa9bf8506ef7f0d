"""
The convex hull an open mesh is integrated as gives the same bits whatever order manifold3d
hands its vertices and faces in (it builds hulls in parallel, and the order changes from run to
run): :func:`~inertia_kit.physics.manifolds.canonical_triangles`, which every solid from
manifold3d is integrated through.
"""

from __future__ import annotations

import numpy as np
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st

from inertia_kit.physics.manifolds import canonical_triangles
from inertia_kit.physics.polyhedra import integrate


def _shuffled(vertices, faces, seed):
    """The same mesh with its vertices renumbered, faces reordered and each face's vertices
    turned (the winding kept)."""
    rng = np.random.default_rng(seed)
    renumber = rng.permutation(len(vertices))
    moved = np.empty_like(renumber)
    moved[renumber] = np.arange(len(vertices))
    faces = moved[faces][rng.permutation(len(faces))]
    turn = (rng.integers(0, 3, len(faces))[:, None] + np.arange(3)) % 3
    return vertices[renumber], np.take_along_axis(faces, turn, axis=1)


def _moments_bits(triangles):
    moments = integrate(triangles).moments
    return (moments.volume, *moments.centroid.tolist(), *moments.second.ravel().tolist())


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), subdivisions=st.integers(1, 3))
def test_the_order_a_hull_comes_in_changes_no_bit(seed, subdivisions):
    sphere = trimesh.creation.icosphere(subdivisions=subdivisions, radius=0.37)
    # off the origin and irregular, so that sums in another order round differently
    vertices = sphere.vertices * [1.0, 0.61, 1.9] + [0.123, -4.56, 7.89]
    faces = np.asarray(sphere.faces, dtype=np.intp)
    canonical = canonical_triangles(vertices, faces)
    again = canonical_triangles(*_shuffled(vertices, faces, seed))
    assert np.array_equal(canonical, again)
    assert _moments_bits(canonical) == _moments_bits(again)
    # the same solid: the same triangles, wound the same way (positive volume)
    assert integrate(canonical).moments.volume > 0
    assert sorted(map(tuple, np.sort(canonical.reshape(-1, 9), axis=1))) == sorted(
        map(tuple, np.sort(vertices[faces].reshape(-1, 9), axis=1))
    )


def test_summation_order_does_change_bits_without_it():
    """The case the canonical order exists for: the raw orders give different last bits."""
    sphere = trimesh.creation.icosphere(subdivisions=3, radius=0.37)
    vertices = sphere.vertices * [1.0, 0.61, 1.9] + [0.123, -4.56, 7.89]
    faces = np.asarray(sphere.faces, dtype=np.intp)
    raw = {_moments_bits(v[f]) for v, f in (_shuffled(vertices, faces, s) for s in range(8))}
    assert len(raw) > 1


def test_no_faces():
    empty = canonical_triangles(np.zeros((0, 3)), np.zeros((0, 3), dtype=np.intp))
    assert empty.shape == (0, 3, 3)
