"""analysis.forensics.other_axes (IN062): a tensor written in the axes of another frame."""

from __future__ import annotations

import numpy as np
from forensic_cases import BOX, MASS, box_case, box_tensor, cylinder_tensor, props, rounded

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
