"""analysis.forensics.other_point (IN060): a tensor about another point than the COM."""

from __future__ import annotations

import numpy as np
import pytest
from forensic_cases import BOX, MASS, box_case, box_tensor, cylinder_tensor, parallel_axis, props

from inertia_kit.analysis.bounds import Hull
from inertia_kit.analysis.forensics.diagnosis import diagnose

DRUM = (157.633, 0.35, 0.4)  # the seed mrm arm's link_01


def test_tensor_about_the_link_origin():
    mass, radius, length = DRUM
    com = np.array([0.0, 0.0, length / 2])
    right = cylinder_tensor(mass, radius, length)
    declared = right + parallel_axis(mass, com)
    found = diagnose(
        props(mass, declared, com),
        props(mass, right, com),
        points=[("the link origin", (0.0, 0.0, 0.0))],
    )
    assert found is not None and found.code == "IN060"
    assert found.wording.data["point"] == [0.0, 0.0, 0.0]
    assert "about the link origin (0, 0, 0), not about the COM (0, 0, 0.2)" in found.wording.summary
    np.testing.assert_allclose(found.corrected.inertia, right, rtol=0, atol=1e-12)
    np.testing.assert_allclose(found.corrected.com, com)
    assert found.corrected.mass == mass
    assert right[0, 0] == pytest.approx(6.929, abs=1e-3)


def test_rounded_values_about_the_origin_are_still_recognised():
    """The mrm values: 13.235 and 9.655 (three decimals), the corrected ixx 13.235 - m d²."""
    mass, radius, length = DRUM
    com = (0.0, 0.0, 0.2)
    declared = np.diag([13.235, 13.235, 9.655])
    found = diagnose(
        props(mass, declared, com),
        props(mass, cylinder_tensor(mass, radius, length), com),
        points=[("the link origin", (0.0, 0.0, 0.0))],
    )
    assert found is not None and found.code == "IN060"
    assert found.corrected.inertia[0, 0] == pytest.approx(13.235 - mass * 0.2**2)
    assert found.corrected.inertia[2, 2] == 9.655
    assert found.residual < 1e-3 and found.plain_residual > 0.5


def test_a_named_joint_origin_is_preferred_and_named():
    mass, radius, length = DRUM
    com = np.array([0.0, 0.0, 0.2])
    joint = np.array([0.0, 0.0, 0.5])
    right = cylinder_tensor(mass, radius, length)
    found = diagnose(
        props(mass, right + parallel_axis(mass, com - joint), com),
        props(mass, right, com),
        points=[("the link origin", (0, 0, 0)), ("the origin of joint `j2`", joint)],
        hull=Hull(np.array([[0, 0, 0], [0, 0, length]]), np.array([radius, radius])),
    )
    assert found is not None and found.code == "IN060"
    assert "about the origin of joint `j2` (0, 0, 0.5)" in found.wording.summary


def test_a_point_outside_what_any_mass_allows_is_solved_for():
    """A CAD part origin at a corner of the box: the tensor about it, no named point."""
    corner = np.array(BOX) / 2
    declared = box_tensor(MASS, *BOX) + parallel_axis(MASS, corner)
    found = box_case(declared, points=[])
    assert found is not None and found.code == "IN060"
    point = np.array(found.wording.data["point"])
    assert np.allclose(point, corner) or np.allclose(point, -corner)
    assert found.wording.data["point_name"] is None
    np.testing.assert_allclose(found.corrected.inertia, box_tensor(MASS, *BOX), atol=1e-12)
    # without a hull nothing is solved for
    assert box_case(declared, points=[], hull=None) is None
