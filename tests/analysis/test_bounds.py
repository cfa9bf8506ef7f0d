"""analysis.bounds: hulls and the hard moment bounds, against closed forms and invariants."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from inertia_kit.analysis.bounds import BOUND_RTOL, RIM_SIDES, Hull, moment_excess
from inertia_kit.analysis.tensors import axis_name
from inertia_kit.physics.frames import rpy_matrix, transform
from inertia_kit.physics.mass import MassProperties, second_moment_from_inertia
from inertia_kit.physics.unions import Part

RIM = 1.0 / math.cos(math.pi / RIM_SIDES)  # how far the cylinder hull's corners overshoot


# --- Hull -------------------------------------------------------------------------------------


def test_box_hull_support_and_reach_to_its_corners():
    size = np.array([0.4, 0.2, 0.1])
    hull = Hull.of_part(Part.box(size, transform((1.0, 0.0, 0.0))))
    assert hull.support(np.eye(3)) == pytest.approx([1.2, 0.1, 0.05])
    assert hull.support(-np.eye(3)) == pytest.approx([-0.8, 0.1, 0.05])
    # from its centre the hull reaches half the diagonal, towards a corner
    corner = size / 2
    reach = hull.half_widths((1.0, 0.0, 0.0), [corner / np.linalg.norm(corner)])[0]
    assert reach == pytest.approx(np.linalg.norm(corner))
    np.testing.assert_allclose(hull.bounds, [[0.8, -0.1, -0.05], [1.2, 0.1, 0.05]])


def test_rotated_box_hull_is_exact_not_its_bounding_box():
    # a 1 × 0.1 × 0.1 box turned 45° about z reaches (0.5 + 0.05)/√2 along x, not 0.55
    hull = Hull.of_part(Part.box((1.0, 0.1, 0.1), transform(rpy=(0, 0, math.pi / 4))))
    assert hull.support([[1.0, 0.0, 0.0]])[0] == pytest.approx(0.55 / math.sqrt(2))


def test_sphere_and_capsule_hulls_are_balls():
    sphere = Hull.of_part(Part.sphere(0.3, transform((0.0, 0.0, 1.0))))
    assert sphere.half_widths((0.0, 0.0, 0.0), [[0.0, 0.0, 1.0]])[0] == pytest.approx(1.3)
    assert sphere.support([[0.0, 0.0, -1.0]])[0] == pytest.approx(-0.7)
    capsule = Hull.of_part(Part.capsule(0.1, 0.4, transform(rpy=(0, math.pi / 2, 0))))
    assert capsule.support(np.eye(3)) == pytest.approx([0.3, 0.1, 0.1])
    assert capsule.farthest_from_axes((0, 0, 0), [[1.0, 0.0, 0.0]])[0] == pytest.approx(0.1)


def test_cylinder_hull_contains_the_rim_and_overshoots_by_the_polygon_only():
    radius, length = 0.05, 0.3
    hull = Hull.of_part(Part.cylinder(radius, length))
    reach = hull.farthest_from_axes((0, 0, 0), [[0.0, 0.0, 1.0]])[0]
    assert radius <= reach <= radius * RIM + 1e-15
    # any direction in the xy-plane: between the circle and the circumscribed polygon
    angles = np.linspace(0, 2 * np.pi, 97)
    directions = np.column_stack((np.cos(angles), np.sin(angles), np.zeros_like(angles)))
    support = hull.support(directions)
    assert (support >= radius - 1e-15).all() and (support <= radius * RIM + 1e-15).all()
    assert hull.support([[0.0, 0.0, 1.0]])[0] == pytest.approx(length / 2)


def test_moment_bound_of_a_centred_box_is_the_corner_distance():
    a, b, c = 0.2, 0.1, 0.05  # half sizes
    hull = Hull.of_part(Part.box((2 * a, 2 * b, 2 * c)))
    bound = hull.moment_bound((0, 0, 0), np.eye(3))
    np.testing.assert_allclose(bound, [b * b + c * c, a * a + c * c, a * a + b * b])


def test_moment_bound_shrinks_with_an_off_centre_com_bhatia_davis():
    a, b, c, d = 0.2, 0.1, 0.05, 0.15  # COM d along x from the centre
    hull = Hull.of_part(Part.box((2 * a, 2 * b, 2 * c)))
    bound = hull.moment_bound((d, 0, 0), np.eye(3))
    # about y: second moments along x ≤ (a - d)(a + d), along z ≤ c²
    assert bound[1] == pytest.approx((a - d) * (a + d) + c * c)
    assert bound[1] < (a + d) ** 2 + c * c  # tighter than the distance to the far corner


@pytest.mark.parametrize("seed", range(5))
def test_moment_bound_holds_for_random_distributions_inside(seed):
    """No distribution inside the geometry has more than the bound about its own COM."""
    rng = np.random.default_rng(seed)
    pose = transform(rng.uniform(-1, 1, 3), rng.uniform(-np.pi, np.pi, 3))
    radius, length = 0.1, 0.5
    hull = Hull.of_part(Part.cylinder(radius, length, pose))
    count = int(rng.integers(2, 6))
    # point masses on the cylinder's rims: the extreme distributions
    angle = rng.uniform(0, 2 * np.pi, count)
    local = np.column_stack(
        (radius * np.cos(angle), radius * np.sin(angle), rng.choice([-0.5, 0.5], count) * length)
    )
    points = local @ pose[:3, :3].T + pose[:3, 3]
    masses = rng.uniform(0.1, 1.0, count)
    body = sum(MassProperties(m, p) for m, p in zip(masses, points, strict=True))
    frames = [np.eye(3), body.principal_axes, rpy_matrix(rng.uniform(-3, 3, 3))]
    for frame in frames:
        bound = body.mass * hull.moment_bound(body.com, frame)
        moments = np.einsum("ji,jk,ki->i", frame, body.inertia, frame)
        assert (moments <= bound * (1 + 1e-12) + 1e-15).all()


def test_distance_outside_is_a_lower_bound_and_zero_inside():
    hull = Hull.of_part(Part.box((1.0, 1.0, 1.0)))
    assert hull.distance_outside((0.2, -0.3, 0.4)) == 0.0
    assert hull.distance_outside((0.8, 0.0, 0.0)) == pytest.approx(0.3)
    true = math.dist((0.8, 0.8, 0.8), (0.5, 0.5, 0.5))
    assert 0.9 * true <= hull.distance_outside((0.8, 0.8, 0.8)) <= true + 1e-12


def test_union_of_hulls_keeps_every_ball():
    left = Hull.of_part(Part.sphere(0.1, transform((-1.0, 0.0, 0.0))))
    right = Hull.of_part(Part.box((0.2, 0.2, 0.2), transform((1.0, 0.0, 0.0))))
    both = Hull.union([left, right])
    assert both.support([[1.0, 0, 0], [-1.0, 0, 0]]) == pytest.approx([1.1, 1.1])
    # the segment between them is inside the convex hull of the union
    assert both.distance_outside((0.0, 0.0, 0.0)) == 0.0


def test_hull_rejects_bad_shapes():
    with pytest.raises(ValueError, match=r"\(k, 3\)"):
        Hull(np.zeros((3, 2)))
    with pytest.raises(ValueError, match="radii"):
        Hull(np.zeros((2, 3)), np.zeros(3))


# --- moment excess ------------------------------------------------------------------------------


def test_moment_excess_reports_the_link_axis_beyond_the_bound():
    hull = Hull.of_part(Part.cylinder(0.05, 0.05))
    declared = MassProperties(1.0, np.zeros(3), np.diag([1.0, 1.0, 1.0]))
    excess = moment_excess(declared, hull)
    assert excess is not None and excess.ratio > 100
    assert axis_name(excess.axis) is not None
    # about a transverse axis the farthest points are the rim corners: r² + (l/2)²
    if axis_name(excess.axis) in "xy":
        assert excess.r_max == pytest.approx(math.hypot(0.05 * RIM, 0.025), rel=1e-9)


def test_moment_excess_of_the_uniform_tensor_is_within_the_bound():
    part = Part.box((0.4, 0.2, 0.1))
    uniform = part.mass_properties(mass=3.0)
    excess = moment_excess(uniform, Hull.of_part(part))
    assert excess is not None
    # a uniform box has a third of the corner bound about each axis: (b² + c²)/3 vs b² + c²
    assert excess.ratio == pytest.approx(1 / 3)


def test_a_negative_moment_is_no_excess_of_a_zero_bound():
    """Found by hypothesis: a ratio of inf sent IN023 to the square root of a negative moment."""
    from inertia_kit.analysis.bounds import MomentExcess

    axis = np.array([0.0, 1.0, 0.0])
    assert MomentExcess(axis, -0.026, 0.0, 0.0).ratio == 0.0
    assert MomentExcess(axis, 0.0, 0.0, 0.0).ratio == 0.0
    assert MomentExcess(axis, 0.01, 0.0, 0.0).ratio == math.inf
    assert MomentExcess(axis, 0.01, 0.02, 1.0).ratio == 0.5


# --- second moments along directions (Bhatia–Davis) -------------------------------------------

_UNIT = st.floats(-1.0, 1.0, allow_nan=False)


def _unit(v):
    v = np.asarray(v, dtype=float)
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    return np.where(n > 1e-6, v / np.where(n > 0, n, 1.0), [1.0, 0.0, 0.0])


@st.composite
def hull_and_masses(draw):
    """A box or a capsule (any pose) or a random convex polytope, and point masses inside."""
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    kind = draw(st.sampled_from(["box", "polytope", "capsule"]))
    pose = transform(rng.uniform(-1, 1, 3), rng.uniform(-np.pi, np.pi, 3))
    if kind == "box":
        hull = Hull.of_part(Part.box(rng.uniform(0.001, 1.0, 3), pose))
    elif kind == "polytope":
        hull = Hull(rng.normal(size=(int(rng.integers(4, 12)), 3)) * rng.uniform(0.01, 1.0, 3))
    else:
        hull = Hull.of_part(Part.capsule(*rng.uniform(0.001, 0.5, 2), pose))
    count = int(rng.integers(1, 7))
    # convex combinations of the ball centres (every point of their hull is one), each moved
    # by less than the balls' radius (a capsule's radius is the same at both ends)
    weights = rng.dirichlet(np.full(len(hull.points), 0.3), size=count)
    offsets = rng.normal(size=(count, 3))
    offsets *= (rng.uniform(0, 1, count) * hull.radii.min() / np.linalg.norm(offsets, axis=1))[
        :, None
    ]
    points = weights @ hull.points + offsets
    masses = rng.uniform(0.01, 2.0, count)
    return hull, points, masses


@settings(max_examples=200, deadline=None)
@given(hull_and_masses(), arrays(np.float64, (5, 3), elements=_UNIT))
def test_no_point_masses_inside_a_hull_break_the_second_moment_bound(case, raw):
    hull, points, masses = case
    body = sum(MassProperties(m, p) for m, p in zip(masses, points, strict=True))
    directions = np.vstack((_unit(raw), np.eye(3), body.principal_axes.T))
    second = second_moment_from_inertia(body.inertia)
    values = np.einsum("ij,jk,ik->i", directions, second, directions)
    bound = body.mass * hull.spread(body.com, directions)
    scale = body.mass * float(np.ptp(hull.points, axis=0).max()) ** 2
    assert (values <= bound + 1e-9 * scale).all()
    # and the search over directions never reports one beyond its bound
    along = moment_excess(body, hull, "along")
    assert along is None or along.moment <= along.bound + 1e-9 * scale


@settings(max_examples=100, deadline=None)
@given(hull_and_masses(), arrays(np.float64, (3,), elements=_UNIT), st.floats(0.05, 0.95))
def test_two_point_masses_at_the_support_points_reach_the_bound(case, raw, share):
    """Equality: all the mass on the two supporting planes (at vertices where u·x is extreme)."""
    hull, _, _ = case
    u = _unit(raw)
    along = hull.points @ u
    first, last = np.argmin(along - hull.radii), np.argmax(along + hull.radii)
    low = hull.points[first] - hull.radii[first] * u
    high = hull.points[last] + hull.radii[last] * u
    along = np.array([low @ u, high @ u])
    body = MassProperties(share, low) + MassProperties(1.0 - share, high)
    value = float(u @ second_moment_from_inertia(body.inertia) @ u)
    bound = body.mass * float(hull.spread(body.com, u[None, :])[0])
    # (b - μ)(μ - a) = share (1 - share) (b - a)² for the two masses: the variance itself
    width = float(along.max() - along.min())
    assert value == pytest.approx(share * (1.0 - share) * width**2, rel=1e-9, abs=1e-15)
    assert value == pytest.approx(bound, rel=1e-9, abs=1e-15)


def test_a_uniform_slab_sits_below_the_bound():
    """∫y² dm = m w²/12 for a uniform slab w thick: a third of the bound m (w/2)²."""
    mass, width = 2.0, 0.02
    part = Part.box((0.3, width, 0.2))
    slab = part.mass_properties(mass=mass)
    assert float(slab.second_moment[1, 1]) == pytest.approx(mass * width**2 / 12)
    excess = moment_excess(slab, Hull.of_part(part), "along")
    assert excess is not None and excess.ratio <= 1 / 3 + 1e-12
    assert float(Hull.of_part(part).spread(slab.com, [[0.0, 1.0, 0.0]])[0]) == pytest.approx(
        (width / 2) ** 2
    )


def test_the_wheel_with_the_axial_formula_on_every_axis_is_found():
    """The issue's wheel: ixx = iyy = izz = ½ m r², r = 0.05 m, 0.02 m wide, axle along y:
    ∫y² dm = (ixx + izz - iyy)/2 = ¼ m r², 6.25 times m (0.01 m)²."""
    mass, radius, width = 1.0, 0.05, 0.02
    hull = Hull.of_part(Part.cylinder(radius, width, transform(rpy=(math.pi / 2, 0, 0))))
    declared = MassProperties(mass, np.zeros(3), np.eye(3) * mass * radius**2 / 2)
    about = moment_excess(declared, hull, "about")
    assert about is not None and about.ratio < 1  # no moment about an axis shows it
    excess = moment_excess(declared, hull)
    assert excess is not None and excess.kind == "along"
    assert axis_name(excess.axis) == "y"
    assert excess.moment == pytest.approx(mass * radius**2 / 4)
    assert excess.bound == pytest.approx(mass * (width / 2) ** 2)
    assert excess.sides == pytest.approx((width / 2, width / 2))
    assert excess.ratio == pytest.approx(6.25)


def test_the_worst_direction_between_the_axes_is_searched_for():
    """A slab turned 30° about z: its thin direction is no link axis, the search finds it."""
    mass, width = 1.0, 0.01
    turn = transform(rpy=(0, 0, math.pi / 6))
    hull = Hull.of_part(Part.box((0.4, width, 0.4), turn))
    declared = MassProperties(mass, np.zeros(3), np.eye(3) * 0.01)  # Σ = 0.005 E
    excess = moment_excess(declared, hull, "along")
    normal = turn[:3, 1]
    assert abs(float(excess.axis @ normal)) == pytest.approx(1.0, abs=1e-6)
    assert excess.bound == pytest.approx(mass * (width / 2) ** 2, rel=1e-6)


def test_no_second_moment_bound_without_a_rigid_body_or_with_the_com_outside():
    hull = Hull.of_part(Part.box((0.2, 0.2, 0.2)))
    broken = MassProperties(1.0, np.zeros(3), np.diag([1.0, 0.1, 0.1]))  # triangle inequality
    assert moment_excess(broken, hull, "along") is None
    outside = MassProperties(1.0, np.array([0.5, 0, 0]), np.eye(3) * 1e-3)
    assert moment_excess(outside, hull, "along") is None
    assert moment_excess(outside, hull, "about") is not None
    # Allegro's finger bases: the COM at the joint, on the end face of the box (a bound of 0)
    on_face = MassProperties(1.0, np.array([0.0, 0.0, 0.1 - 1e-16]), np.eye(3) * 1e-3)
    assert moment_excess(on_face, hull, "along") is None


def test_box_hulls_carry_their_face_normals():
    turn = transform((1.0, 2.0, 3.0), rpy=(0.3, -0.2, 1.1))
    hull = Hull.of_part(Part.box((0.1, 0.2, 0.3), turn))
    np.testing.assert_allclose(np.abs(hull.normals @ turn[:3, :3]), np.eye(3), atol=1e-12)
    both = Hull.union([hull, Hull.of_part(Part.cylinder(0.1, 0.2))])
    assert both.normals.shape == (4, 3)


@pytest.mark.parametrize("mass", [0.01, 1.0, 1000.0])
def test_a_link_axis_is_reported_only_when_beyond_whatever_the_mass(mass):
    """A 45°-turned thin slab: its worst direction is no link axis, and with any mass the link
    axes (within their bounds) must not be preferred to it."""
    width = 0.01
    turn = transform(rpy=(0, 0, math.pi / 4))
    hull = Hull.of_part(Part.box((0.4, width, 0.4), turn))
    declared = MassProperties(mass, np.zeros(3), np.eye(3) * mass * 2e-4)  # Σ = 1e-4 m E
    excess = moment_excess(declared, hull, "along")
    assert axis_name(excess.axis) is None
    assert excess.ratio == pytest.approx(1e-4 / (width / 2) ** 2, rel=1e-6)


@pytest.mark.parametrize(
    "inertia, com",
    [
        (np.diag([1e308] * 3), (0.0, 0.0, 0.0)),  # its trace overflows
        (np.diag([1e308] * 3), (1e300, 0.0, 0.0)),
        (np.eye(3), (1e300, 0.0, 0.0)),  # the COM's distances overflow
        (np.zeros((3, 3)), (0.0, 0.0, 0.0)),
    ],
)
def test_extreme_values_give_no_second_moment_bound_and_no_warning(inertia, com):
    """Found by hand: eigvalsh of a tensor whose trace overflowed raised LinAlgError."""
    import warnings

    hull = Hull.of_part(Part.box((1.0, 1.0, 1.0)))
    declared = MassProperties(1.0, np.array(com), inertia)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        found = moment_excess(declared, hull, "along")
    assert found is None or found.moment == 0.0


@st.composite
def hull_and_declared(draw):
    """A hull and a declared tensor about a COM inside it: second moments of any shape, the
    hull's size squared times a scale, within the bounds and beyond them, either kind worse."""
    hull, points, masses = draw(hull_and_masses())
    scale = draw(st.floats(0.01, 3.0))
    turn = draw(arrays(np.float64, (3, 3), elements=_UNIT))
    spread = draw(arrays(np.float64, (3,), elements=st.floats(0.0, 1.0)))
    body = sum(MassProperties(m, p) for m, p in zip(masses, points, strict=True))
    axes = np.linalg.qr(turn + 3.0 * np.eye(3))[0]
    size = float(np.ptp(hull.points, axis=0).max() + 2.0 * hull.radii.max())
    second = body.mass * scale * size**2 * (axes @ np.diag(spread) @ axes.T)
    return hull, MassProperties(body.mass, body.com, np.trace(second) * np.eye(3) - second)


@settings(max_examples=300, deadline=None)
@given(hull_and_declared())
def test_either_kind_is_the_worse_of_the_two_searched_alone(case):
    """Without a kind, the moment about an axis wins when it is beyond its bound (the search
    along directions is then skipped) or when the second moment comes no closer: the result is
    what the two searches, each run alone, give by that rule."""
    hull, declared = case
    about = moment_excess(declared, hull, "about")
    along = moment_excess(declared, hull, "along")
    expected = (
        about
        if along is None or about.ratio > 1.0 + BOUND_RTOL or not along.ratio > about.ratio
        else along
    )
    found = moment_excess(declared, hull)
    assert (found is None) == (expected is None)
    if found is not None:
        assert (found.kind, found.moment, found.bound) == (
            expected.kind,
            expected.moment,
            expected.bound,
        )
        assert np.array_equal(found.axis, expected.axis)


@settings(max_examples=200, deadline=None)
@given(hull_and_declared())
def test_about_axes_is_the_rule_over_every_axis_checked(case):
    """The moment about an axis: the worst link axis beyond its bound when there is one (the
    other axes then go unchecked), else the worst of the link axes, the principal axes and the
    fixed directions, every one computed."""
    from inertia_kit.analysis.bounds import _DIRECTIONS

    hull, declared = case
    tensor = 0.5 * declared.inertia + 0.5 * declared.inertia.T
    ratios = []
    for frame in (np.eye(3), declared.principal_axes):
        bounds = declared.mass * hull.moment_bound(declared.com, frame)
        ratios += [float(u @ tensor @ u) / b for u, b in zip(frame.T, bounds, strict=True)]
    reach = hull.farthest_from_axes(declared.com, _DIRECTIONS)
    moments = np.einsum("ij,jk,ik->i", _DIRECTIONS, tensor, _DIRECTIONS)
    ratios.append(float(np.max(moments / (declared.mass * reach**2))))
    named = [r for r in ratios[:3] if r > 1.0 + BOUND_RTOL]
    found = moment_excess(declared, hull, "about")
    assert found.ratio == pytest.approx(max(named or ratios), rel=1e-12)
    if named:
        assert np.count_nonzero(found.axis) == 1  # a link axis
