"""analysis.forensics.other_axes (IN062): a tensor written in the axes of another frame."""

from __future__ import annotations

import numpy as np
import pytest
from forensic_cases import (
    BOX,
    MASS,
    box_case,
    box_tensor,
    case_of,
    cylinder_tensor,
    props,
    rounded,
    slightly_off,
)

from inertia_kit.analysis.forensics import other_axes
from inertia_kit.analysis.forensics.diagnosis import diagnose
from inertia_kit.physics.frames import rpy_matrix


def test_cylinder_formula_for_z_on_a_rod_along_x():
    mass, radius, length = 1.0, 0.02, 0.3
    along_z = cylinder_tensor(mass, radius, length)
    turn = rpy_matrix([0.0, np.pi / 2, 0.0])
    along_x = turn @ along_z @ turn.T
    label = "the collision cylinder's own axes"
    found = diagnose(props(mass, along_z), props(mass, along_x), rotations=[(label, turn)])
    assert found is not None and found.code == "IN062"
    assert label in found.wording.summary
    summary = found.wording.summary
    assert "axis of least inertia along z" in summary and "along x" in summary
    np.testing.assert_allclose(found.corrected.inertia, along_x, atol=1e-15)
    np.testing.assert_allclose(rpy_matrix(found.wording.data["rpy"]), turn, atol=1e-12)
    # without the shape's frame, an axis swap says the same
    found = diagnose(props(mass, along_z), props(mass, along_x))
    assert found is not None and found.code == "IN062"
    np.testing.assert_allclose(found.corrected.inertia, along_x, atol=1e-15)


def test_principal_moments_written_without_their_rotation():
    turned = rpy_matrix([0.3, 0.2, 0.1])
    principal = box_tensor(MASS, *BOX)
    assert box_case(rounded(principal)) is None  # for the box as it lies, that tensor is right
    found = box_case(rounded(principal), rotation=turned)
    assert found is not None and found.code == "IN062"
    np.testing.assert_allclose(
        found.corrected.inertia, box_tensor(MASS, *BOX, turned), rtol=0, atol=1e-5
    )


@pytest.mark.parametrize("seed", range(6))
def test_search_scores_each_frame_as_alone_and_keeps_the_fits(seed):
    """Turned and scored all at once, each candidate is what turning it alone gives, bit for bit;
    with a tolerance, the same candidates less those above it."""
    rotation = rpy_matrix(np.random.default_rng(seed).uniform(-3, 3, 3))
    right = box_tensor(MASS, *BOX, rotation)
    swap = other_axes._PERMUTATIONS[seed]
    declared = props(MASS, slightly_off(swap.T @ right @ swap, seed))
    case = case_of(declared, props(MASS, right))
    named = [("a shape's own axes", rotation), ("another", rpy_matrix([0.0, 0.0, 0.5]))]
    found = other_axes.search(case, named)
    assert len(found) == len(named) + 23 + 1
    for candidate in found[:-1]:  # the principal axes' tensor is built, not turned
        turn = candidate.rotation
        alone = turn @ declared.inertia @ turn.T
        assert np.array_equal(candidate.corrected.inertia, alone)
        assert candidate.residual == float(case.metric(alone))
    assert [c.rank for c in found] == [3, 3, *[4] * 23, 7]
    assert found[-1].residual == float(case.metric(found[-1].corrected.inertia))
    fits = other_axes.search(case, named, tolerance=0.02)
    assert [(c.rank, c.residual) for c in fits] == [
        (c.rank, c.residual) for c in found if c.residual <= 0.02
    ]
    assert any(np.array_equal(c.rotation, swap) for c in fits)  # the one that undoes the swap
