"""IN011 inertia-triangle-inequality: the bound, the rounding tolerance, and its options."""

from __future__ import annotations

import numpy as np
import pytest
from kit.moments import box_moments
from kit.urdf import box, collision, inertial, moving

from inertia_kit.lint.rules.in011_inertia_triangle_inequality import half_unit
from inertia_kit.physics.formatting import fmt

PLATE = collision(box(0.3, 0.3, 0.01))


def plate(ixx, iyy, izz, mass="0.9", geometry=PLATE) -> str:
    """A moving link `plate` of ``mass`` with these moments and ``geometry``."""
    return moving(inertial(mass, ixx, iyy, izz) + geometry, name="plate")


def in011(lint, text, **options):
    kw = {"options": {"IN011": options}} if options else {}
    return [f for f in lint(text, "IN011", **kw) if f.code == "IN011"]


def test_violation_with_numbers(lint):
    geometry = collision(box(0.3, 0.3, 0.012))
    (finding,) = in011(lint, plate(0.006, 0.006, 0.0135, geometry=geometry))
    short = (0.0135 - 0.012) / 0.0135
    assert f"{fmt(0.006, 4)} + {fmt(0.006, 4)} = {fmt(0.012, 4)} < {fmt(0.0135, 4)}" in (
        finding.detail
    )
    assert finding.message == (
        f"link `plate`: the principal moments break A + B ≥ C, {fmt(100 * short, 3)} % short"
    )
    assert len(finding.message) <= 100
    # the plate's own tensor: m(b² + c²)/12 and m(a² + b²)/12
    ixx, _, izz = box_moments(0.9, (0.3, 0.3, 0.012))
    assert finding.expected["ixx"] == pytest.approx(ixx)
    assert finding.expected["izz"] == pytest.approx(izz)
    assert f"ixx = {fmt(ixx, 4)}" in finding.detail
    assert "its collision box (0.3 × 0.3 × 0.012 m) with the declared 0.9 kg" in finding.detail


def test_a_disk_sits_on_the_bound(lint):
    r, m = 0.1, 2.0
    a, c = m * r * r / 4, m * r * r / 2
    assert in011(lint, plate(a, a, c, mass=str(m), geometry="")) == []


def test_a_disk_rounded_to_3_digits_passes(lint):
    # true a = 0.0012345, c = 0.002469: rounded, a + b = 0.00246 < c = 0.00247 (0.4 % short)
    text = plate("0.00123", "0.00123", "0.00247", geometry="")
    assert in011(lint, text) == []
    # MuJoCo applies no tolerance: rtol = 0 reports it
    assert len(in011(lint, text, rtol=0.0)) == 1


def test_precise_values_get_no_rounding_excuse(lint):
    # the same 0.4 % shortfall written with 12 digits is not rounding
    text = plate("0.00123000001", "0.00123000002", "0.00247000003", geometry="")
    assert len(in011(lint, text)) == 1
    assert in011(lint, text, digits_aware=False) == []


def test_rtol_caps_the_excuse_for_placeholders(lint):
    # 1-digit placeholders: rounding could explain anything, rtol = 1 % does not
    assert len(in011(lint, plate("0.001", "0.001", "0.01", geometry=""))) == 1
    assert in011(lint, plate("0.001", "0.001", "0.01", geometry=""), rtol=0.9) == []


def test_negative_moment_is_in010s(lint):
    assert in011(lint, plate(-0.001, 0.001, 0.01, geometry="")) == []


def test_products_count(lint):
    # diagonal (0.01, 0.01, 0.019) passes; ixz = 0.004 couples x and z and breaks the bound
    assert in011(lint, plate(0.01, 0.01, 0.019, geometry="")) == []
    text = plate(0.01, 0.01, 0.019, geometry="").replace('ixz="0"', 'ixz="0.004"')
    a, b, c = np.linalg.eigvalsh([[0.01, 0, 0.004], [0, 0.01, 0], [0.004, 0, 0.019]])
    assert a + b < c
    (finding,) = in011(lint, text)
    assert f"({fmt(a, 4)}, {fmt(b, 4)}, {fmt(c, 4)}) kg·m²" in finding.detail


@pytest.mark.parametrize(
    ("value", "half"),
    [(0.00123, 5e-6), (0.0135, 5e-5), (1.0, 0.5), (100.0, 50.0), (0.0, 0.0), (2.5e-7, 5e-9)],
)
def test_half_unit_of_the_last_written_digit(value, half):
    assert half_unit(value) == pytest.approx(half)
