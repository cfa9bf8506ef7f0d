"""The numbers mass properties can be computed from (physics/numbers.py)."""

from __future__ import annotations

import math

import pytest

from inertia_kit.physics.numbers import MAX_MAGNITUDE, MIN_NORMAL, unusable, usable


@pytest.mark.parametrize(
    ("value", "why"),
    [
        (math.nan, "not a number"),
        (math.inf, "infinite"),
        (-math.inf, "infinite"),
        (1e51, "beyond ±1e50"),
        (-1e308, "beyond ±1e50"),
        (5e-324, "subnormal: non-zero below 2.2e-308"),
        (-1e-320, "subnormal: non-zero below 2.2e-308"),
    ],
)
def test_unusable(value, why):
    assert unusable(value) == why and not usable(value)


# the edges, and what CAD exports write for zero on real robots (iCub: 2.67e-51, 5.78e-66)
@pytest.mark.parametrize("value", [0.0, -0.0, 1e50, -1e50, MIN_NORMAL, 2.67276e-51, 5.77686e-66])
def test_usable(value):
    assert unusable(value) is None and usable(value)


def test_six_usable_factors_stay_finite_and_normal():
    """The reason for the bound: a moment is a product of up to six input numbers."""
    assert math.isfinite(MAX_MAGNITUDE**6) and (1 / MAX_MAGNITUDE) ** 6 > MIN_NORMAL
    with pytest.raises(OverflowError):
        _ = (MAX_MAGNITUDE * 100) ** 6
