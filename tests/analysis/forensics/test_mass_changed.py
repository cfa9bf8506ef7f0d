"""
analysis.forensics.mass_changed (IN068): a tensor kept while the mass changed is k times the
geometry's about every axis; closed forms, rotation invariance, and the real-part scatter that
must not be named.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from forensic_cases import BOX, MASS, box_tensor, props
from hypothesis import given
from hypothesis import strategies as st

from inertia_kit.analysis.forensics.mass_changed import MOST, SCALE, SHAPE, mass_change
from inertia_kit.physics.frames import rpy_matrix

GEOMETRY = box_tensor(MASS, *BOX)


def test_a_tensor_kept_for_three_times_the_mass_is_a_third_of_the_geometrys():
    # the tensor of 2 kg declared with 6 kg: the geometry at 6 kg is three times the tensor
    found = mass_change(props(3 * MASS, GEOMETRY), props(3 * MASS, 3 * GEOMETRY))
    assert found is not None
    assert found.factor == pytest.approx(1 / 3)
    assert found.tensor_mass == pytest.approx(MASS)
    assert found.scaled == pytest.approx(3)
    assert found.shape == pytest.approx(0, abs=1e-12)


def test_the_part_keeps_its_shape_and_the_factor_is_the_geometric_mean():
    # a real part's moments 1.2, 0.9 and 1.1 times its box's along the box's axes, mass x3
    part = np.diag(np.sqrt([1.2, 0.9, 1.1])) @ GEOMETRY @ np.diag(np.sqrt([1.2, 0.9, 1.1]))
    found = mass_change(props(3 * MASS, part), props(3 * MASS, 3 * GEOMETRY))
    logs = np.log(np.array([1.2, 0.9, 1.1]) / 3)
    assert found is not None
    assert math.log(found.factor) == pytest.approx(logs.mean())
    assert found.shape == pytest.approx(np.abs(logs - logs.mean()).max())


@given(st.floats(-3, 3), st.floats(-3, 3), st.floats(-3, 3), st.floats(0.05, 0.4))
def test_rotation_of_both_tensors_changes_nothing(a, b, c, k):
    turn = rpy_matrix([a, b, c])
    plain = mass_change(props(MASS, k * GEOMETRY), props(MASS, GEOMETRY))
    turned = mass_change(
        props(MASS, k * turn @ GEOMETRY @ turn.T), props(MASS, turn @ GEOMETRY @ turn.T)
    )
    assert (plain is None) == (turned is None)
    if plain is not None:
        assert turned.factor == pytest.approx(plain.factor, rel=1e-9)


def test_what_is_not_named():
    geometry = props(MASS, GEOMETRY)
    # within what silent real parts show: a factor of 2
    assert mass_change(props(MASS, GEOMETRY / 2), geometry) is None
    # a unit's factor (IN063's): a thousand
    assert mass_change(props(MASS, GEOMETRY / 1000), geometry) is None
    assert math.exp(MOST) < 1000
    # axes off both ways: no common factor, the shape disagrees
    uneven = np.diag(np.sqrt([8.0, 0.5, 4.0])) @ GEOMETRY @ np.diag(np.sqrt([8.0, 0.5, 4.0]))
    assert mass_change(props(MASS, uneven), geometry) is None
    # a factor beyond SCALE whose shape departs beyond SHAPE
    k = math.exp(-(SCALE + 0.3))
    skew = np.exp(np.array([SHAPE + 0.1, -(SHAPE + 0.1) / 2, -(SHAPE + 0.1) / 2]))
    bent = k * np.diag(np.sqrt(skew)) @ GEOMETRY @ np.diag(np.sqrt(skew))
    assert mass_change(props(MASS, bent), geometry) is None
    # no body: not positive definite
    assert mass_change(props(MASS, -GEOMETRY), geometry) is None


def test_a_factor_of_fifty_is_no_retyped_mass():
    # 50 times the geometry's: a made-up value or a unit, not a mass typed ten times too large
    assert mass_change(props(MASS, 50 * GEOMETRY), props(MASS, GEOMETRY)) is None
    assert mass_change(props(MASS, 10 * GEOMETRY), props(MASS, GEOMETRY)) is not None
