"""IN063 inertia-unit-slip: a box's tensor in other units, a mass in grams."""

from __future__ import annotations

import pytest
from kit.moments import box_moments
from kit.urdf import box, collision, inertial, moving

from inertia_kit.lint.findings import Severity
from inertia_kit.physics.formatting import fmt

MASS, SIZE = 2.0, (0.4, 0.2, 0.1)


def plate(mass, ixx, iyy, izz):
    """The box, with this mass and these moments written to six significant digits."""
    moments = (f"{m:.6g}" for m in (ixx, iyy, izz))
    return moving(inertial(mass, *moments) + collision(box(*SIZE)), name="plate")


@pytest.mark.parametrize(("factor", "unit"), [(1e6, "kg·mm²"), (1e9, "g·mm²"), (1e7, "g·cm²")])
def test_tensor_in_another_unit(lint, factor, unit):
    moments = box_moments(MASS, SIZE)
    findings = lint(plate(MASS, *(m * factor for m in moments)))
    assert [f.code for f in findings] == ["IN063"]  # IN020 and IN023 replaced
    finding = findings[0]
    assert finding.severity == Severity.ERROR  # as written, beyond the hard bound
    assert finding.message == f"link `plate`: unit slip: inertia in {unit}, not kg·m²"
    assert f"the tensor is in {unit}, not kg·m²" in finding.detail
    assert finding.detail.endswith("as written no mass inside the geometry can have it (IN023)")
    assert finding.expected["factor"] == pytest.approx(factor)
    for name, value in zip(("ixx", "iyy", "izz"), moments, strict=True):
        assert finding.expected[name] == pytest.approx(value, rel=1e-5)


def test_tensor_divided_once_too_often(lint):
    moments = box_moments(MASS, SIZE)
    findings = lint(plate(MASS, *(m / 1e6 for m in moments)))
    assert "IN063" in [f.code for f in findings]
    finding = next(f for f in findings if f.code == "IN063")
    assert finding.expected["factor"] == pytest.approx(1e-6)
    assert finding.expected["izz"] == pytest.approx(moments[2], rel=1e-5)
    assert finding.message == "link `plate`: unit slip: inertia divided by 1e+06 as if in kg·mm²"


def test_the_message_is_one_short_line_and_the_detail_has_the_numbers(lint):
    """The unit in one line; the largest moment against the geometry's, the factor, the value
    converted and the fit in the detail (issue 21, item 5)."""
    moments = box_moments(MASS, SIZE)
    (finding,) = lint(plate(MASS, *(m * 1e6 for m in moments)), "IN063")
    assert len(finding.message) <= 100
    izz = moments[2]
    assert finding.detail.startswith(
        "a unit slip: the tensor is in kg·mm², not kg·m²: "
        f"izz {fmt(izz * 1e6, 5)} is 1e+06 times the {fmt(izz, 4)} the collision box "
        f"(0.4 × 0.2 × 0.1 m) gives; converted it is {fmt(izz, 4)} (all six match within "
    )


def test_mass_in_grams_replaces_the_density_finding(lint):
    """2000 g written as kg: 25 000 kg/m³ over the box; the tensor is right for 2 kg."""
    findings = lint(plate(1000 * MASS, *box_moments(MASS, SIZE)))
    assert [f.code for f in findings] == ["IN063"]  # IN020, IN022 replaced
    finding = findings[0]
    assert finding.message == "link `plate`: unit slip: mass 2000 in grams"
    assert "the mass 2000 is in grams" in finding.detail
    assert finding.expected["mass"] == pytest.approx(MASS)
    assert finding.expected["mass_factor"] == 1000
    assert finding.expected["ixx"] == pytest.approx(box_moments(MASS, SIZE)[0])
    assert "write the mass in kg (2)" in finding.help


def test_a_right_tensor_and_a_tensor_off_by_other_factors_are_not_unit_slips(lint):
    moments = box_moments(MASS, SIZE)
    assert lint(plate(MASS, *moments)) == []
    findings = lint(plate(MASS, *(m * 50 for m in moments)), "IN06")
    assert findings == []
