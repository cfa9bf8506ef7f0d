"""
Volume integrals of triangle soups against closed forms and invariants, and the closure
fingerprint against surfaces known to be closed or open.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import trimesh
from kit.meshes import box_triangles
from kit.moments import box_tensor
from kit.physics import assert_mass_close, random_rotation, sphere_triangles

from inertia_kit.physics import polyhedra
from inertia_kit.physics.polyhedra import SurfaceIntegrator, integrate

RNG = np.random.default_rng(20261121)
DENSITY = 1000.0


# --- volume integrals --------------------------------------------------------------------


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_box_matches_the_closed_form(dtype):
    size, low = (0.5, 0.25, 2.0), (0.25, -0.5, 1.0)  # dyadic: exact in float32
    properties = integrate(box_triangles(size, low).astype(dtype)).moments.mass_properties(
        density=DENSITY
    )
    mass = DENSITY * math.prod(size)
    assert properties.mass == pytest.approx(mass, rel=1e-12)
    np.testing.assert_allclose(properties.com, np.add(low, np.multiply(size, 0.5)), atol=1e-12)
    np.testing.assert_allclose(properties.inertia, box_tensor(mass, size), atol=1e-12 * mass)


def test_sphere_is_within_its_tessellation_error_of_the_ball():
    radius = 0.3
    triangles = sphere_triangles(4, radius)
    properties = integrate(triangles).moments.mass_properties(density=DENSITY)
    # the inscribed polyhedron lies between the ball of radius r and the ball touching its faces
    normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    inner = np.min(
        np.einsum("ij,ij->i", triangles[:, 0], normals) / np.linalg.norm(normals, axis=1)
    )
    assert 0.99 * radius < inner < radius
    volume = properties.mass / DENSITY
    assert 4 / 3 * math.pi * inner**3 < volume < 4 / 3 * math.pi * radius**3
    np.testing.assert_allclose(properties.com, 0.0, atol=1e-15)
    moments = np.diag(properties.inertia)
    assert (0.4 * DENSITY * 4 / 3 * math.pi * inner**5 < moments).all()
    assert (moments < 0.4 * DENSITY * 4 / 3 * math.pi * radius**5).all()
    off_diagonal = properties.inertia - np.diag(moments)
    assert np.abs(off_diagonal).max() < 1e-12 * moments.max()


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_matches_trimesh_on_the_same_triangles(dtype):
    # an off-centre, tilted, squashed sphere: every product of inertia is non-zero
    triangles = sphere_triangles(5) * (1.0, 0.6, 0.3) @ random_rotation(RNG).T + (0.2, -0.1, 0.4)
    triangles = triangles.astype(dtype)
    mine = integrate(triangles).moments.mass_properties(density=DENSITY)
    reference = trimesh.Trimesh(**trimesh.triangles.to_kwargs(triangles.astype(np.float64)))
    reference = reference.mass_properties
    size = np.ptp(triangles.reshape(-1, 3), axis=0).max()
    assert mine.mass == pytest.approx(DENSITY * reference.volume, rel=1e-9)
    np.testing.assert_allclose(mine.com, reference.center_mass, rtol=0, atol=1e-9 * size)
    inertia = DENSITY * reference.inertia
    np.testing.assert_allclose(mine.inertia, inertia, rtol=0, atol=1e-9 * np.abs(inertia).max())


def test_moving_the_mesh_moves_the_com_and_rotates_the_inertia():
    triangles = sphere_triangles(3) * (1.0, 0.5, 0.25)
    rotation, shift = random_rotation(RNG), np.array([3.0, -2.0, 5.0])
    still = integrate(triangles).moments.mass_properties(density=DENSITY)
    moved = integrate(triangles @ rotation.T + shift).moments.mass_properties(density=DENSITY)
    assert moved.mass == pytest.approx(still.mass, rel=1e-12)
    np.testing.assert_allclose(moved.com, rotation @ still.com + shift, rtol=0, atol=1e-12)
    scale = np.abs(still.inertia).max()
    np.testing.assert_allclose(
        moved.inertia, rotation @ still.inertia @ rotation.T, rtol=0, atol=1e-12 * scale
    )


def test_the_reference_point_changes_nothing():
    triangles = sphere_triangles(3) + np.array([1.0, 2.0, 3.0])
    reference = integrate(triangles).moments.mass_properties(density=DENSITY)
    # about a point d away the second moment is ~ (d / r)² larger than the central one, and
    # that many more digits cancel: 1e-10 allows for d / r ~ 25
    for origin in [(0.0, 0.0, 0.0), (1.0, 2.0, 3.0), (-4.0, 5.0, 0.5)]:
        moments = integrate(triangles, origin).moments
        np.testing.assert_array_equal(moments.origin, origin)
        assert_mass_close(moments.mass_properties(density=DENSITY), reference, rtol=1e-10)
        moved = moments.about((0.5, 0.5, 0.5)).mass_properties(density=DENSITY)
        assert_mass_close(moved, reference, rtol=1e-10)


def test_far_from_the_coordinate_origin_the_central_moments_keep_their_precision():
    size, low = (0.5, 0.25, 2.0), (1000.25, -2000.5, 500.0)  # exact in float64
    properties = integrate(box_triangles(size, low)).moments.mass_properties(density=DENSITY)
    mass = DENSITY * math.prod(size)
    np.testing.assert_allclose(properties.inertia, box_tensor(mass, size), atol=1e-12 * mass)


def test_reversed_winding_gives_negative_volume_and_stays_closed():
    triangles = sphere_triangles(3)
    forward, backward = integrate(triangles), integrate(triangles[:, ::-1])
    assert forward.closed and backward.closed
    assert forward.moments.volume > 0
    assert backward.moments.volume == pytest.approx(-forward.moments.volume, rel=1e-12)
    flipped = backward.moments.negated().mass_properties(density=DENSITY)
    assert_mass_close(flipped, forward.moments.mass_properties(density=DENSITY))
    with pytest.raises(ValueError, match="no positive volume"):
        backward.moments.mass_properties(density=DENSITY)


def test_bounds_and_count():
    triangles = box_triangles((0.5, 0.25, 2.0), (0.25, -0.5, 1.0))
    integrator = integrate(triangles)
    assert integrator.count == 12
    np.testing.assert_array_equal(integrator.bounds, [[0.25, -0.5, 1.0], [0.75, -0.25, 3.0]])


def test_no_triangles():
    integrator = integrate(np.zeros((0, 3, 3)))
    assert integrator.count == 0
    assert not integrator.closed
    assert integrator.moments.volume == 0.0


def test_shapes_and_origins_are_checked():
    with pytest.raises(ValueError, match=r"\(n, 3, 3\)"):
        integrate(np.zeros((4, 3)))
    with pytest.raises(ValueError, match="origin"):
        SurfaceIntegrator((0.0, np.inf, 0.0))


# --- chunks ------------------------------------------------------------------------------


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_chunk_boundaries_change_nothing(monkeypatch, dtype):
    triangles = (sphere_triangles(3) @ random_rotation(RNG).T + (0.1, 0.2, 0.3)).astype(dtype)
    whole = integrate(triangles)
    monkeypatch.setattr(polyhedra, "CHUNK", 7)  # 1280 triangles: 182 chunks and a remainder
    chunked = SurfaceIntegrator(whole.origin)
    for start in range(0, len(triangles), 100):  # several add() calls, each split in chunks
        chunked.add(triangles[start : start + 100])
    assert chunked.count == whole.count == len(triangles)
    assert chunked.closed and whole.closed
    np.testing.assert_array_equal(chunked.bounds, whole.bounds)
    assert chunked.moments.volume == pytest.approx(whole.moments.volume, rel=1e-13)
    assert_mass_close(
        chunked.moments.mass_properties(density=DENSITY),
        whole.moments.mass_properties(density=DENSITY),
        rtol=1e-13,
    )


def test_adding_after_reading_the_results_goes_on_adding():
    triangles = sphere_triangles(3)
    integrator = SurfaceIntegrator((0.0, 0.0, 0.0))
    integrator.add(triangles[:700])
    assert not integrator.closed
    partial = integrator.moments.volume
    integrator.add(triangles[700:])
    assert integrator.closed
    assert integrator.count == len(triangles)
    whole = integrate(triangles, (0.0, 0.0, 0.0)).moments.volume
    assert integrator.moments.volume == pytest.approx(whole, rel=1e-13)
    assert partial < whole


def test_float32_and_float64_chunks_of_one_surface_match():
    triangles = sphere_triangles(3).astype(np.float32)
    integrator = SurfaceIntegrator((0.0, 0.0, 0.0))
    integrator.add(triangles[:500])
    integrator.add(triangles[500:].astype(np.float64))  # the same values, as float64
    assert integrator.closed


def test_any_strides_are_accepted():
    triangles = sphere_triangles(2)
    padded = np.zeros((len(triangles), 4, 5))
    padded[:, :3, 1:4] = triangles
    view = padded[:, :3, 1:4]
    assert not view.flags.c_contiguous
    a, b = integrate(view).moments, integrate(triangles).moments
    assert a.volume == b.volume
    np.testing.assert_array_equal(a.second, b.second)


# --- closure -----------------------------------------------------------------------------


def grid_surface(n=6) -> np.ndarray:
    """A closed cube surface of 12 n² triangles with small-integer vertex coordinates (float32
    words ending in many zero bits, the case naive hashes collapse on)."""
    i = np.arange(n)
    u, v = np.meshgrid(i, i, indexing="ij")
    u, v = u.ravel(), v.ravel()
    quads = np.stack(
        [np.stack([u, v], -1), np.stack([u + 1, v], -1), np.stack([u + 1, v + 1], -1)], 1
    )
    quads = np.concatenate([quads, np.stack([quads[:, 0], quads[:, 2], quads[:, 0]], 1)])
    quads[len(u) :, 2] = np.stack([u, v + 1], -1)
    faces = []
    for axis in range(3):
        for side in (0, n):
            other = [a for a in range(3) if a != axis]
            face = np.zeros((*quads.shape[:2], 3))
            face[..., other] = quads
            face[..., axis] = side
            # counter-clockwise seen from outside: flip where the (u, v) order faces inwards
            outward = (side == n) == (axis != 1)
            faces.append(face if outward else face[:, ::-1])
    return np.concatenate(faces)


def test_grid_surface_is_closed_and_encloses_its_cube():
    triangles = grid_surface(6)
    integrator = integrate(triangles.astype(np.float32))
    assert integrator.closed
    assert integrator.moments.volume == pytest.approx(216.0, rel=1e-12)


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_a_missing_or_flipped_face_is_noticed(dtype):
    for triangles in (sphere_triangles(3), grid_surface(6)):
        triangles = triangles.astype(dtype)
        assert integrate(triangles).closed
        for k in RNG.choice(len(triangles), 20, replace=False):
            assert not integrate(np.delete(triangles, k, axis=0)).closed
            flipped = triangles.copy()
            flipped[k] = flipped[k, ::-1]
            assert not integrate(flipped).closed


def test_a_crack_is_noticed():
    # the lower half's copies of the vertices round the waist are one bit off the upper half's
    triangles = grid_surface(4).astype(np.float32)
    z = triangles[..., 2]
    lower = (z.max(axis=1) <= 2)[:, None] & (z == 2)
    assert lower.any()
    z[lower] = np.nextafter(np.float32(2), np.float32(3))
    assert not integrate(triangles).closed
    assert integrate(triangles).moments.volume == pytest.approx(64.0, rel=1e-6)


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_signed_zeros_are_one_vertex(dtype):
    triangles = box_triangles((1.0, 2.0, 4.0), (-1.0, 0.0, -2.0)).astype(dtype)
    assert (triangles == 0).any()
    mixed = triangles.copy()
    zeros = mixed == 0
    zeros[::2] = False  # half the triangles write their zeros as -0.0
    mixed[zeros] = -0.0
    assert np.signbit(mixed[mixed == 0]).any() and not np.signbit(mixed[mixed == 0]).all()
    integrator = integrate(mixed)
    assert integrator.closed
    assert integrator.moments.volume == pytest.approx(8.0, rel=1e-12)


def test_the_fingerprint_does_not_depend_on_chunking_or_order():
    triangles = sphere_triangles(3)
    shuffled = triangles[RNG.permutation(len(triangles))]
    rolled = np.roll(shuffled, 1, axis=1)  # each triangle starts at another vertex
    assert integrate(rolled).closed
