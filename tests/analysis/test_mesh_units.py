"""analysis.mesh_units: the slip that explains a mesh's size, and when none is named."""

import pytest

from inertia_kit.analysis.mesh_units import density_evidence, size_evidence, suspected_unit


@pytest.mark.parametrize(
    ("extent", "slip", "unit"),
    [
        (150.0, 0.001, "mm"),  # a 15 cm part in mm read as m
        (0.15, None, None),  # in metres already
        (1e38, None, None),  # no slip brings it to a part's size
        (0.00015, 1000.0, None),  # a mm scale on a mesh already in metres: not a unit
    ],
)
def test_size_alone(extent, slip, unit):
    suspicion = suspected_unit([size_evidence(extent)], min_evidence=1)
    assert suspicion.slip == slip
    assert suspicion.unit == unit


def test_one_observation_is_not_enough_when_two_are_asked_for():
    assert suspected_unit([size_evidence(150.0)], min_evidence=2).slip is None


def test_density_backs_the_size():
    """0.6 kg in 0.15 × 0.1 × 0.04 = 0.0006 m³ read in mm: 600 000 m³, 1e-6 kg/m³."""
    volume = 150.0 * 100.0 * 40.0
    evidence = [size_evidence(150.0), density_evidence(0.6, volume)]
    assert evidence[1].value(0.0) == pytest.approx(-6.0)
    assert suspected_unit(evidence, min_evidence=2).slip == 0.001
