"""engines.gazebo: gz-math's test of a body's inertia."""

from __future__ import annotations

import numpy as np
import pytest

from inertia_kit.engines.gazebo import gz_mass_matrix_valid


@pytest.mark.parametrize(
    ("moments", "valid"),
    [
        ((1.0, 1.0, 1.0), True),
        ((0.0, 0.0, 0.0), True),
        ((1.0, 1.0, 2.0), True),
        ((1.0, 1.0, 2.1), False),
        ((-0.1, 1.0, 1.0), False),
    ],
)
def test_gz_mass_matrix_valid(moments, valid):
    assert gz_mass_matrix_valid(1.0, np.diag(moments)) is valid
