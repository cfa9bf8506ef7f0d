"""analysis.forensics.measure: the deviation between two tensors."""

from __future__ import annotations

import numpy as np
import pytest

from inertia_kit.analysis.forensics.measure import deviation


def test_deviation_is_relative_per_axis_with_a_floor():
    tensor = np.diag([1.0, 2.0, 3.0])
    assert deviation(tensor, tensor) == 0.0
    # twice the tensor: (I) / (I + 5 % of the largest) about the largest axis
    assert deviation(2 * tensor, tensor) == pytest.approx(3.0 / (3.0 + 0.15))
    # a rounding error of a large entry counts against the floor, not a thin axis's moment
    thin = np.diag([1.0, 1.0, 0.001])
    assert deviation(thin + np.diag([0, 0, 0.001]), thin) < 0.05
