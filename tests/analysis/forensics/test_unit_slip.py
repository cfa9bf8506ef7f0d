"""analysis.forensics.unit_slip (IN063): a tensor in another unit, or a mass in grams."""

from __future__ import annotations

import numpy as np
import pytest
from forensic_cases import (
    BOX,
    MASS,
    VOLUME,
    box_case,
    box_tensor,
    case_of,
    props,
    rounded,
    slightly_off,
)

from inertia_kit.analysis.forensics import unit_slip
from inertia_kit.analysis.forensics.diagnosis import diagnose
from inertia_kit.analysis.forensics.measure import Metric


@pytest.mark.parametrize(
    ("factor", "unit"),
    [(1e6, "kg·mm²"), (1e9, "g·mm²"), (1e4, "kg·cm²"), (1e3, "g·m²"), (1 / 2.9263965e-4, "lb·in²")],
)
def test_tensor_in_another_unit(factor, unit):
    right = box_tensor(MASS, *BOX)
    found = box_case(rounded(right * factor))
    assert found is not None and found.code == "IN063"
    data = found.wording.data
    assert data["unit"] == unit and data["factor"] == pytest.approx(factor)
    np.testing.assert_allclose(found.corrected.inertia, right, rtol=1e-3)


def test_tensor_converted_the_wrong_way():
    right = box_tensor(MASS, *BOX)
    found = box_case(right / 1e6)
    assert found is not None and found.code == "IN063"
    assert found.wording.data["factor"] == pytest.approx(1e-6)
    np.testing.assert_allclose(found.corrected.inertia, right)


def test_mass_in_grams():
    """2000 (g) declared: 25 000 kg/m³ would be needed; the tensor is right for 2 kg."""
    right = box_tensor(MASS, *BOX)
    declared = props(1000 * MASS, right)
    expected = props(1000 * MASS, box_tensor(1000 * MASS, *BOX))
    found = diagnose(declared, expected, volume=VOLUME)
    assert found is not None and found.code == "IN063"
    assert found.wording.data["mass_factor"] == 1000 and found.wording.data["factor"] == 1.0
    assert found.corrected.mass == pytest.approx(MASS)
    np.testing.assert_allclose(found.corrected.inertia, right)
    assert "in grams" in found.wording.summary


def test_no_unit_slip_when_the_geometry_scale_is_in_doubt_or_the_value_is_a_placeholder():
    right = box_tensor(MASS, *BOX)
    # a mesh in millimetres: a density of 2.5e-6 kg/m³; the tensor is not to blame
    assert box_case(right * 1e6, volume=VOLUME * 1e9) is None
    # ixx = iyy = izz = 1 on a 1 cm sphere of 0.1 g: exactly 1e9 times 1e-9, a placeholder
    sphere = np.eye(3) * 0.4 * 1e-4 * 0.005**2
    volume = 4 / 3 * np.pi * 0.005**3
    expected = props(0.1, sphere * 1e3)
    assert diagnose(props(0.1, np.eye(3)), expected, volume=volume) is None


@pytest.mark.parametrize(("mass", "factor"), [(MASS, 1e6), (MASS, 1e-4), (1000 * MASS, 1.0)])
def test_search_scores_each_conversion_as_alone_and_keeps_the_fits(mass, factor):
    """Converted and scored all at once, each candidate is what converting it alone gives, bit
    for bit (the declared mass's metric is the case's); with a tolerance, those not above it."""
    right = box_tensor(MASS, *BOX)
    declared = props(mass, slightly_off(right * factor, 7))
    case = case_of(declared, props(mass, box_tensor(mass, *BOX)))
    found = unit_slip.search(case, VOLUME)
    assert len(found) == (15 if mass != MASS else 14)
    for candidate in found:
        alone = declared.inertia / candidate.factor
        metric = Metric(case.expected.inertia / candidate.mass_factor)
        assert np.array_equal(candidate.corrected.inertia, alone)
        assert candidate.corrected.mass == declared.mass / candidate.mass_factor
        assert candidate.residual == float(metric(alone))
    fits = unit_slip.search(case, VOLUME, tolerance=0.02)
    assert [(c.factor, c.unit, c.residual) for c in fits] == [
        (c.factor, c.unit, c.residual) for c in found if c.residual <= 0.02
    ]
    assert len(fits) == 1
