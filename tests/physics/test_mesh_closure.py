"""
The convex hull an open mesh is integrated as gives the same bits whatever order manifold3d
hands its vertices and faces in (it builds hulls in parallel, and the order changes from run to
run): :func:`~inertia_kit.physics.manifolds.canonical_triangles`, which every solid from
manifold3d is integrated through.
"""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st

from inertia_kit.physics.manifolds import canonical_triangles
from inertia_kit.physics.mesh_closure import unique_rows
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


# --- welding corners written twice (mesh_closure.WELD_RTOLS) --------------------------------


def _binary_stl(path, triangles) -> None:
    """Triangles as a binary STL: float32 coordinates, as CAD exporters write them."""
    triangles = np.asarray(triangles, dtype=np.float32)
    record = np.zeros(len(triangles), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    record["v"] = triangles
    with open(path, "wb") as file:
        file.write(b"\0" * 80 + np.uint32(len(triangles)).tobytes() + record.tobytes())


def _box_triangles(size=(0.075, 0.038, 0.027), corner=(-0.047, 0.0103, 0.035)):
    box = trimesh.creation.box(extents=size)
    box.apply_translation(np.asarray(corner) + np.asarray(size) / 2)
    return np.asarray(box.triangles, dtype=np.float32), float(np.prod(size))


def _nudged(triangles, steps=1):
    """The first triangle's copies of one corner moved ``steps`` float32 steps along y: the same
    corner written twice, as Fetch's laser_link.STL has it (one step, 9.3e-10 m, of 0.0103)."""
    corner = triangles[0, 0].copy()
    nudged = triangles.copy()
    y = np.float32(corner[1])
    for _ in range(steps):
        y = np.nextafter(y, np.float32(1))
    nudged[0, 0, 1] = y
    return nudged


def test_a_corner_written_twice_one_float32_step_apart_is_welded(tmp_path):
    from inertia_kit.physics.meshes import mesh_solid

    triangles, volume = _box_triangles()
    nudged = _nudged(triangles)
    assert not integrate(nudged).closed  # the exact-bit check sees two corners
    _binary_stl(tmp_path / "box.stl", nudged)
    solid = mesh_solid(tmp_path / "box.stl")
    assert (solid.method, solid.closed) == ("exact", True)
    assert solid.moments.volume == pytest.approx(volume, rel=1e-6)


def test_a_closed_box_with_a_sliver_triangle_pair_is_closed(tmp_path):
    """A stray pair of triangles narrower than the weld tolerance (an open flap, 1e-10 m wide
    on a 0.075 m box) collapses when welded: the box is judged by its closed surface, its
    volume exact, not its convex hull's."""
    from inertia_kit.physics.meshes import mesh_solid

    triangles, volume = _box_triangles()
    a, b = triangles[0, 0], triangles[0, 1]
    step = np.float32(1)  # one float32 step along y, below the weld tolerance (7.5e-9 m)
    flap = np.array(
        [[a, b, np.nextafter(b, step)], [a, np.nextafter(b, step), np.nextafter(a, step)]]
    )
    far = np.array([0.02, 0.005, 0.005], dtype=np.float32)  # outside the box: a hull grows
    sliver = np.array([[far, np.nextafter(far, step), np.nextafter(np.nextafter(far, step), step)]])
    for extra in (flap, sliver):
        assert not integrate(np.concatenate([triangles, extra])).closed
    _binary_stl(tmp_path / "box.stl", np.concatenate([triangles, flap]))
    solid = mesh_solid(tmp_path / "box.stl")
    assert (solid.method, solid.closed) == ("exact", True)
    assert solid.moments.volume == pytest.approx(volume, rel=1e-6)
    # a sliver away from the box is a (degenerate) open shell too: welded away, no hull
    _binary_stl(tmp_path / "far.stl", np.concatenate([triangles, sliver]))
    assert mesh_solid(tmp_path / "far.stl").moments.volume == pytest.approx(volume, rel=1e-6)


def test_a_tiny_closed_shell_beside_the_body_adds_its_volume(tmp_path):
    from inertia_kit.physics.meshes import mesh_solid

    triangles, volume = _box_triangles()
    small, small_volume = _box_triangles(size=(1e-4, 4e-4, 1.6e-3), corner=(0.028, 0.0118, 0.035))
    _binary_stl(tmp_path / "two.stl", np.concatenate([_nudged(triangles), small]))
    solid = mesh_solid(tmp_path / "two.stl")
    assert solid.method == "exact"
    assert solid.moments.volume == pytest.approx(volume + small_volume, rel=1e-6)


def test_a_genuinely_open_mesh_stays_open(tmp_path):
    """A missing face, or a corner moved well beyond the tolerance (1e-6 of the extent), is
    no float noise: the convex hull, as before."""
    from inertia_kit.physics.meshes import mesh_solid

    triangles, _ = _box_triangles()
    _binary_stl(tmp_path / "open.stl", triangles[2:])
    moved = triangles.copy()
    moved[0, 0, 1] += 1e-6 * 0.075
    _binary_stl(tmp_path / "moved.stl", moved)
    for name in ("open.stl", "moved.stl"):
        solid = mesh_solid(tmp_path / name)
        assert (solid.method, solid.closed) == ("convex-hull", False)


def test_weld_uses_a_distance_not_decimal_rounding():
    """Two values either side of a rounding boundary (…5 at the 9th decimal) are 2e-12 apart:
    rounding to 9 digits parts them, a distance tolerance of 1e-9 does not."""
    from inertia_kit.physics.mesh_closure import weld

    points = np.array(
        [[0.1234567895 - 1e-12, 0.0, 0.0], [0.1234567895 + 1e-12, 0.0, 0.0], [0.2, 0.0, 0.0]]
    )
    assert np.round(points[0, 0], 9) != np.round(points[1, 0], 9)
    labels = weld(points, 1e-9)
    assert labels[0] == labels[1] != labels[2]
    # half a cell on every axis always welds; beyond √3 cells never (without a chain)
    rng = np.random.default_rng(7)
    for _ in range(200):
        p = rng.uniform(-1, 1, 3)
        near = weld(np.array([p, p + rng.uniform(-0.49, 0.49, 3) * 1e-3]), 1e-3)
        far = weld(np.array([p, p + rng.normal(size=3) / 10]), 1e-3)
        assert near[0] == near[1] and far[0] != far[1]
    # a chain welds end to end
    chain = np.array([[i * 4e-4, 0.0, 0.0] for i in range(10)])
    assert len(set(weld(chain, 1e-3))) == 1


@settings(max_examples=100, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    count=st.integers(4, 120),
    shape=st.sampled_from(["lattice", "cloud", "sphere"]),
)
def test_the_hull_of_the_corners_first_seen_is_that_of_every_corner(seed, count, shape):
    """A soup of triangles with repeated corners (on a lattice, where hull facets are coplanar;
    in a cloud; on a sphere): ``first_seen`` is the corners without repeats in order, and
    manifold3d's hull of it is the hull of every corner, bit for bit."""
    import manifold3d

    from inertia_kit.physics.manifolds import manifold_moments
    from inertia_kit.physics.mesh_closure import first_seen

    rng = np.random.default_rng(seed)
    points = {
        "lattice": lambda: rng.integers(0, 4, (count, 3)) * 0.25,
        "cloud": lambda: rng.normal(size=(count, 3)),
        "sphere": lambda: rng.normal(size=(count, 3)),
    }[shape]()
    if shape == "sphere":
        points /= np.linalg.norm(points, axis=1)[:, None]
    corners = points[rng.integers(0, count, 9 * count)]
    distinct, index = unique_rows(corners)
    seen = first_seen(distinct, index)
    expected = list(dict.fromkeys(map(tuple, corners)))
    assert [tuple(p) for p in seen] == expected
    every = manifold_moments(manifold3d.Manifold.hull_points(corners))
    once = manifold_moments(manifold3d.Manifold.hull_points(seen))
    assert every.volume == once.volume
    assert np.array_equal(every.first, once.first) and np.array_equal(every.second, once.second)


def _chebyshev_apart(points, distance):
    """No two rows of ``points`` within ``distance`` on every axis, by every pair."""
    gaps = np.abs(points[:, None, :] - points[None, :, :]).max(axis=2)
    np.fill_diagonal(gaps, np.inf)
    return bool((gaps >= distance).all())


@settings(max_examples=300, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    count=st.integers(1, 40),
    lattice=st.booleans(),
    copies=st.lists(st.floats(0.0, 3.0), max_size=6),
    scale=st.sampled_from([1e-6, 1.0, 1e4]),
    offset=st.sampled_from([0.0, 1e3]),
)
def test_weld_without_its_grids_labels_as_they_do(seed, count, lattice, copies, scale, offset):
    """Points far apart on some axis are each their own (``apart``), as the grids find them;
    points near one another, at fractions and multiples of the tolerance, go to the grids. On
    a lattice and off it, far from the origin and near it."""
    from inertia_kit.physics.mesh_closure import apart, grid_weld, unique_rows, weld

    rng = np.random.default_rng(seed)
    tolerance = 1e-3 * scale
    # on a lattice, CAD corners share coordinates
    grid = rng.integers(0, 4, (count, 3)) * 0.25
    points = grid if lattice else rng.uniform(0.0, 1.0, (count, 3))
    near = [
        points[rng.integers(len(points))]
        + factor * rng.choice([-1.0, 1.0], 3) * rng.uniform(0.5, 1.0, 3) * 1e-3
        for factor in copies
    ]
    points = unique_rows(np.vstack([points, *near]) * scale + offset)[0]
    assert np.array_equal(weld(points, tolerance), grid_weld(points, tolerance))
    assert apart(points, 2 * tolerance) == _chebyshev_apart(points, 2 * tolerance)


def test_distinct_corners_as_close_as_the_coarse_tolerance_are_not_pinched(tmp_path):
    """Two cubes 3e-8 of the extent apart (TIAGo's base_ring.stl has distinct corners that
    close), with one shared corner written twice 1e-12 apart: the fine weld closes the surface,
    and the coarse one, which would weld the facing corners into edges of four faces, is not
    tried."""
    from pathlib import Path

    from inertia_kit.physics.mesh_closure import WELD_RTOLS, classify

    first = trimesh.creation.box(extents=(1.0, 1.0, 1.0))
    second = first.copy()
    gap = 3e-8 * 2.0  # the pair is 2 m wide: 3e-8 of its extent
    second.apply_translation((1.0 + gap, 0.0, 0.0))
    triangles = np.concatenate([first.triangles, second.triangles])
    triangles[0, 0] += 1e-12  # one copy of one corner, float64 noise
    assert WELD_RTOLS[0] * 2.0 < gap < WELD_RTOLS[1] * 2.0
    integrator = integrate(triangles)
    assert not integrator.closed
    found = classify(Path("two.stl"), integrator, triangles)
    assert (found.method, found.closed) == ("exact", True)
    assert found.moments.volume == pytest.approx(2.0, rel=1e-9)


def test_inertia_kit_mass_reports_the_welded_solid(tmp_path):
    """`inertia-kit mass mesh` on the box with a corner written twice: exact, the box's volume
    (0.075 × 0.038 × 0.027 m = 7.695e-05 m³), not its convex hull's."""
    from click.testing import CliRunner

    from inertia_kit.cli import main

    triangles, volume = _box_triangles()
    _binary_stl(tmp_path / "box.stl", _nudged(triangles))
    result = CliRunner().invoke(main, ["mass", "mesh", str(tmp_path / "box.stl"), "--density", "1"])
    assert result.exit_code == 0, result.output
    assert "triangles, exact" in result.output
    assert f"(volume {volume:.6g} m³" in result.output


def _cube_faces() -> np.ndarray:
    from kit.meshes import box_triangles

    triangles = box_triangles((1.0, 2.0, 3.0))
    points, faces = np.unique(triangles.reshape(-1, 3), axis=0, return_inverse=True)
    return points, faces.reshape(-1, 3)


@pytest.mark.parametrize(
    "change",
    ["none", "flip one", "drop one", "duplicate one", "flip all", "empty", "doubled surface"],
)
def test_closure_is_trimeshs_judgment(change):
    """closure() answers as trimesh's is_watertight and is_winding_consistent, without it."""
    import trimesh

    from inertia_kit.physics.mesh_closure import closure

    points, faces = _cube_faces()
    if change == "flip one":
        faces[3] = faces[3][::-1]
    elif change == "drop one":
        faces = faces[1:]
    elif change == "duplicate one":
        faces = np.vstack((faces, faces[:1]))
    elif change == "flip all":
        faces = faces[:, ::-1]
    elif change == "empty":
        faces = faces[:0]
    elif change == "doubled surface":
        faces = np.vstack((faces, faces[:, ::-1]))
    mesh = trimesh.Trimesh(vertices=points, faces=faces, process=False)
    assert closure(faces) == (mesh.is_watertight, mesh.is_winding_consistent)


@settings(max_examples=200, deadline=None)
@given(st.lists(st.permutations(range(5)).map(lambda p: p[:3]), min_size=1, max_size=12))
def test_closure_is_trimeshs_judgment_on_any_faces(faces):
    """Faces over five corners in any number and winding: the same two answers as trimesh."""
    from inertia_kit.physics.mesh_closure import closure

    faces = np.array(faces, dtype=np.int64)
    points = np.random.default_rng(0).normal(size=(5, 3))
    mesh = trimesh.Trimesh(vertices=points, faces=faces, process=False)
    assert closure(faces) == (mesh.is_watertight, mesh.is_winding_consistent)


@settings(max_examples=100, deadline=None)
@given(
    st.lists(
        st.tuples(*(st.integers(0, 10**8) for _ in range(3))) | st.just((7, 7, 7)),
        min_size=1,
        max_size=40,
    )
)
def test_cell_ids_group_the_rows_as_numpy_unique_does(rows):
    from inertia_kit.physics.mesh_closure import _cell_ids

    cells = np.array(rows, dtype=np.int64)
    ours = _cell_ids(cells)
    numpys = np.unique(cells, axis=0, return_inverse=True)[1].reshape(-1)
    # the same partition of the rows: each of our ids is one of numpy's, and back
    assert len(set(zip(ours.tolist(), numpys.tolist(), strict=True))) == len(set(ours.tolist()))
    assert len(set(ours.tolist())) == len(set(numpys.tolist()))


@given(
    st.lists(
        st.tuples(*[st.sampled_from([0.0, -1.5, 2.25, 1e-300, 3e12, 0.1])] * 3),
        min_size=0,
        max_size=40,
    )
)
def test_unique_rows_is_numpys_unique_of_rows(rows):
    array = np.array(rows, dtype=np.float64).reshape(-1, 3)
    points, inverse = unique_rows(array)
    expected, expected_inverse = np.unique(array, axis=0, return_inverse=True)
    assert np.array_equal(points, expected)
    assert np.array_equal(inverse, expected_inverse.reshape(-1))
    assert np.array_equal(points[inverse], array)


@given(
    st.lists(st.tuples(*[st.sampled_from([0.0, -0.0, -1.5, 2.25, 1e-300])] * 3), min_size=1),
    st.data(),
)
def test_shared_unique_rows_is_unique_rows_of_the_corners(vertices, data):
    """Found among the vertices the faces use (some vertices unused, some repeated): the same
    points, by value, and corners, as among every corner."""
    from inertia_kit.physics.mesh_closure import shared_unique_rows

    vertices = np.array(vertices, dtype=np.float64)
    index = st.integers(0, len(vertices) - 1)
    faces = np.array(data.draw(st.lists(st.tuples(index, index, index), min_size=1)))
    points, corners = shared_unique_rows(vertices, faces)
    expected, expected_corners = unique_rows(vertices[faces].reshape(-1, 3))
    assert np.array_equal(points, expected)
    assert np.array_equal(corners, expected_corners)


def test_unique_rows_leaves_non_finite_rows_to_numpy():
    array = np.array([[np.nan, 0, 0], [1, 2, 3], [np.nan, 0, 0], [np.inf, 1, 1]])
    points, inverse = unique_rows(array)
    expected, expected_inverse = np.unique(array, axis=0, return_inverse=True)
    assert np.array_equal(points, expected, equal_nan=True)
    assert np.array_equal(inverse, expected_inverse.reshape(-1))


@pytest.mark.parametrize(("gap", "judged", "method"), [(0.0, 1, "convex-hull"), (1e-7, 2, "exact")])
def test_a_surface_is_judged_again_only_when_a_wider_weld_merges_more(
    monkeypatch, tmp_path, gap, judged, method
):
    """An open box is judged once (the wider weld merges nothing more); a corner 1e-7 off,
    welded only by the wider tolerance, is judged twice and found closed."""
    from pathlib import Path

    from kit.meshes import box_triangles

    from inertia_kit.physics import mesh_closure

    triangles = box_triangles((1.0, 2.0, 3.0))
    if gap:
        triangles[0, 0, 0] += gap
    else:
        triangles = triangles[1:]
    calls = []
    real_closure = mesh_closure.closure
    monkeypatch.setattr(mesh_closure, "closure", lambda f: calls.append(1) or real_closure(f))
    result = mesh_closure.classify(Path(tmp_path / "box.stl"), integrate(triangles), triangles)
    assert (len(calls), result.method) == (judged, method)
