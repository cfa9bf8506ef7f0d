"""analysis.forensics.flipped_signs (IN061): products of inertia with the opposite sign."""

from __future__ import annotations

import numpy as np
import pytest
from forensic_cases import BOX, MASS, box_case, box_tensor

from inertia_kit.physics.frames import rpy_matrix


@pytest.mark.parametrize("rpy", [(0.4, 0.3, 0.5), (0.0, 0.0, 0.5236)])
def test_flipped_products(rpy):
    """All three products, or one (then it is also a half turn, but the sign slip is named)."""
    turned = rpy_matrix(rpy)
    right = box_tensor(MASS, *BOX, turned)
    flipped = 2 * np.diag(np.diag(right)) - right
    found = box_case(flipped, rotation=turned)
    assert found is not None and found.code == "IN061"
    np.testing.assert_allclose(found.corrected.inertia, right, atol=1e-12)


def test_flipped_products_in_the_axes_of_inertial_rpy():
    """The written values are in the axes of <inertial><origin rpy>: their products flip."""
    axes = rpy_matrix([0.0, 0.0, 0.3])
    turned = rpy_matrix([0.4, 0.3, 0.5])
    right = box_tensor(MASS, *BOX, turned)
    written = axes.T @ right @ axes
    declared = axes @ (2 * np.diag(np.diag(written)) - written) @ axes.T
    found = box_case(declared, rotation=turned, axes=axes)
    assert found is not None and found.code == "IN061"
    np.testing.assert_allclose(found.corrected.inertia, right, atol=1e-12)
