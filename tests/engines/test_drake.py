"""engines.drake: Drake's substitutes for what it cannot use."""

from __future__ import annotations

import math

import pytest

from inertia_kit.engines.drake import plausible_sphere


def test_plausible_sphere_is_water_density():
    mass, radius, moment = plausible_sphere(2.0)
    assert mass == 2.0
    assert 1000 * 4 / 3 * math.pi * radius**3 == pytest.approx(2.0)
    assert moment == pytest.approx(0.4 * 2.0 * radius**2)
    assert plausible_sphere(-1.0)[0] == 1.0
