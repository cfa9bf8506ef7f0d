"""analysis.forensics.transposed (IN064): the six values in the wrong attributes."""

from __future__ import annotations

import numpy as np
from forensic_cases import BOX, MASS, box_case, box_tensor, props

from inertia_kit.analysis.forensics.diagnosis import diagnose
from inertia_kit.physics.frames import rpy_matrix


def values_to_tensor(ixx, ixy, ixz, iyy, iyz, izz):
    return np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])


def test_two_products_swapped():
    turned = rpy_matrix([0.0, 0.0, np.pi / 6])
    right = box_tensor(12.0, 0.4, 0.3, 0.2, turned)
    ixx, iyy, izz, ixy = right[0, 0], right[1, 1], right[2, 2], right[0, 1]
    declared = values_to_tensor(ixx, 0.0, ixy, iyy, 0.0, izz)
    found = diagnose(props(12.0, declared), props(12.0, right), volume=0.024)
    assert found is not None and found.code == "IN064"
    assert "ixy and ixz are swapped" in found.wording.summary
    assert found.wording.data["assignment"] == {"ixy": "ixz", "ixz": "ixy"}
    np.testing.assert_allclose(found.corrected.inertia, right)


def test_values_listed_moments_first_read_in_urdf_order():
    """MuJoCo's fullinertia order (Ixx Iyy Izz Ixy Ixz Iyz) pasted into ixx ixy ixz iyy iyz izz."""
    turned = rpy_matrix([0.4, 0.3, 0.5])
    right = box_tensor(MASS, *BOX, turned)
    listed = [right[0, 0], right[1, 1], right[2, 2], right[0, 1], right[0, 2], right[1, 2]]
    declared = values_to_tensor(*listed)  # not even positive definite
    assert np.linalg.eigvalsh(declared)[0] < 0
    found = box_case(declared, rotation=turned)
    assert found is not None and found.code == "IN064"
    np.testing.assert_allclose(found.corrected.inertia, right)
