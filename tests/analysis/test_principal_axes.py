"""analysis.principal_axes: principal axes against the geometry's, judged by their moments' gap."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from kit.moments import box_tensor

from inertia_kit.analysis.principal_axes import (
    MIN_GAP,
    angle_limit,
    axes_mismatch,
    compare_axes,
    gaps,
)
from inertia_kit.physics.frames import rpy_matrix

BOX = (0.4, 0.2, 0.1)


def about_z(degrees: float) -> np.ndarray:
    return rpy_matrix((0.0, 0.0, math.radians(degrees)))


def test_gaps_are_log_distances_to_the_nearest_other_moment():
    assert gaps([1.0, 2.0, 8.0]) == pytest.approx([math.log(2), math.log(2), math.log(4)])


@pytest.mark.parametrize("degrees", [5.0, 30.0, 60.0, 89.0])
def test_a_box_turned_about_z_shows_the_angle(degrees):
    geometry = box_tensor(2.0, BOX)
    declared = box_tensor(2.0, BOX, about_z(degrees))
    by_rank = {c.rank: c for c in compare_axes(declared, geometry)}
    # least inertia along x, middle along y: both turned; the greatest (z) stays
    assert by_rank[0].angle == pytest.approx(degrees, abs=1e-6)
    assert by_rank[2].angle == pytest.approx(0.0, abs=1e-6)
    # the middle axis (iyy 0.0283 near izz 0.0333) is no better defined than that gap says
    assert by_rank[1].gap == pytest.approx(math.log(0.0333333 / 0.0283333), rel=1e-4)


def test_the_limit_falls_with_the_gap_and_is_void_below_the_minimum():
    assert angle_limit(MIN_GAP * 0.99) == 90.0
    limits = [angle_limit(g) for g in (MIN_GAP, 1.0, 2.0, 4.0, 8.0)]
    assert limits == sorted(limits, reverse=True) and limits[0] < 45.0


def test_a_box_turned_beyond_the_limit_is_a_mismatch_within_it_not():
    geometry = box_tensor(2.0, BOX)
    gap = math.log(0.0283333 / 0.0083333)  # the least moment's
    inside, beyond = angle_limit(gap) - 2.0, angle_limit(gap) + 2.0
    assert axes_mismatch(box_tensor(2.0, BOX, about_z(inside)), geometry) is None
    found = axes_mismatch(box_tensor(2.0, BOX, about_z(beyond)), geometry)
    assert found is not None and found.rank == 0
    assert found.angle == pytest.approx(beyond, abs=1e-6)


def test_a_cube_has_no_axes_to_compare():
    cube = box_tensor(1.0, (0.1, 0.1, 0.1))
    turned = box_tensor(1.0, (0.1, 0.1, 0.1), rpy_matrix((0.2, 0.9, 1.2)))
    assert all(c.gap < MIN_GAP for c in compare_axes(turned, cube))
    assert axes_mismatch(turned, cube) is None
    # a square rod: only its long axis is defined, and it is compared
    rod = (0.4, 0.1, 0.1)
    found = axes_mismatch(box_tensor(1.0, rod, about_z(40)), box_tensor(1.0, rod))
    assert found is not None and found.rank == 0 and found.angle == pytest.approx(40.0)


def test_no_positive_moment_no_comparison():
    assert compare_axes(np.diag([1.0, 1.0, -1.0]), np.eye(3)) == []
    assert compare_axes(np.full((3, 3), np.nan), np.eye(3)) == []
    assert axes_mismatch(np.zeros((3, 3)), np.eye(3)) is None


_MOMENTS = st.floats(0.2, 5.0)


@settings(max_examples=60, deadline=None)
@given(
    st.tuples(_MOMENTS, _MOMENTS, _MOMENTS),
    st.tuples(st.floats(0.5, 2.0), st.floats(0.5, 2.0), st.floats(0.5, 2.0)),
    st.lists(st.floats(-math.pi, math.pi), min_size=9, max_size=9),
)
def test_a_common_rotation_leaves_angles_and_gaps_unchanged(principal, scatter, angles):
    """Turning both tensors alike (any frame they are written in) changes nothing."""
    first, second, turn = (rpy_matrix(angles[i : i + 3]) for i in (0, 3, 6))
    geometry = first @ np.diag(principal) @ first.T
    declared = second @ np.diag(np.multiply(principal, scatter)) @ second.T
    before = compare_axes(declared, geometry)
    after = compare_axes(turn @ declared @ turn.T, turn @ geometry @ turn.T)
    for a, b in zip(before, after, strict=True):
        assert b.gap == pytest.approx(a.gap, abs=1e-9)
        if a.gap > 1e-3:  # an axis defined well enough for its direction to be computed
            assert b.angle == pytest.approx(a.angle, abs=1e-4)
