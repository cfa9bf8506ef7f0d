"""The equivalent uniform box against closed forms: a solid box's own tensor gives that box."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from kit.moments import box_tensor, cylinder_moments
from kit.physics import random_rotation

from inertia_kit.physics.mass import MassProperties
from inertia_kit.view.boxes import equivalent_box

sides = st.floats(0.01, 10.0)


@given(
    mass=st.floats(0.01, 1000.0),
    size=st.tuples(sides, sides, sides),
    seed=st.integers(0, 2**32 - 1),
)
def test_a_solid_box_gives_back_its_sides_and_axes(mass, size, seed):
    rotation = random_rotation(np.random.default_rng(seed))
    body = MassProperties(mass, (0.1, -0.2, 0.3), box_tensor(mass, size, rotation))
    box = equivalent_box(body)
    assert box.problem is None
    # the largest side turns about the smallest moment: sides in moment order descend
    order = np.argsort(size)[::-1]
    np.testing.assert_allclose(box.sizes, np.asarray(size)[order], rtol=1e-6)
    # each principal axis is the box's own edge direction of that side (up to its sign), when
    # the sides are distinct enough for the axes to be defined
    ranked = np.sort(size)
    if np.all(np.diff(ranked) > 1e-2 * ranked[-1]):
        for column, edge in zip(box.axes.T, rotation[:, order].T, strict=True):
            assert abs(column @ edge) == pytest.approx(1.0, abs=1e-6)
    assert np.linalg.det(box.axes) == pytest.approx(1.0)


def test_a_cylinder_s_box():
    # a_i² = 6 (I_j + I_k − I_i) / m: along the axis (the smallest moment here) 6 (2 across −
    # along) / m = l², across it 6 along / m = 3 r²
    mass, radius, length = 2.0, 0.05, 0.3
    across, _, along = cylinder_moments(mass, radius, length)
    box = equivalent_box(MassProperties(mass, (0, 0, 0), np.diag([across, across, along])))
    np.testing.assert_allclose(
        box.sizes, [length, np.sqrt(3) * radius, np.sqrt(3) * radius], rtol=1e-12
    )
    assert abs(box.axes[:, 0] @ [0, 0, 1]) == pytest.approx(1.0)


def test_a_flat_plate_keeps_a_zero_thickness():
    mass, x, y = 1.0, 0.4, 0.2
    plate = MassProperties(mass, (0, 0, 0), box_tensor(mass, (x, y, 0.0)))
    box = equivalent_box(plate)
    assert box.problem is None
    np.testing.assert_allclose(box.sizes, [x, y, 0.0], atol=1e-9)


def test_a_broken_tensor_gives_the_problem():
    body = MassProperties(1.0, (0, 0, 0), np.diag([0.1, 0.1, 0.5]))
    box = equivalent_box(body)
    assert box.sizes is None
    assert "triangle inequality" in box.problem
    assert "0.1 + 0.1 < 0.5" in box.problem
    np.testing.assert_allclose(box.moments, [0.1, 0.1, 0.5])


@pytest.mark.parametrize("mass", [0.0, -1.0])
def test_no_box_without_a_positive_mass(mass):
    box = equivalent_box(MassProperties(mass, (0, 0, 0), np.eye(3)))
    assert box.sizes is None
    assert "not positive" in box.problem


def test_no_box_for_values_that_are_not_finite():
    box = equivalent_box(MassProperties(1.0, (0, 0, 0), np.diag([1.0, np.nan, 1.0])))
    assert box.sizes is None
    assert "not finite" in box.problem
