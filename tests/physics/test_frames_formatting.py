"""URDF frames and number formatting."""

import math

import numpy as np
import pytest

from inertia_kit.description.urdf.inertial_xml import inertial_block
from inertia_kit.physics.formatting import fmt, xml_number
from inertia_kit.physics.frames import as_transform, inverse, matrix_rpy, rpy_matrix, transform
from inertia_kit.physics.primitives import cylinder


def elementary(axis: int, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    m = np.eye(3)
    m[i, i] = m[j, j] = c
    m[i, j], m[j, i] = -s, s
    return m


def test_rpy_is_fixed_axis_roll_then_pitch_then_yaw():
    r, p, y = 0.3, -1.1, 2.4
    expected = elementary(2, y) @ elementary(1, p) @ elementary(0, r)
    np.testing.assert_allclose(rpy_matrix((r, p, y)), expected, atol=1e-15)


@pytest.mark.parametrize(
    "rpy", [(0.3, -1.1, 2.4), (0, 0, 0), (-3.0, 1.2, -0.5), (0.2, math.pi / 2, 0.0)]
)
def test_matrix_rpy_round_trip(rpy):
    np.testing.assert_allclose(rpy_matrix(matrix_rpy(rpy_matrix(rpy))), rpy_matrix(rpy), atol=1e-12)


def test_transform_and_inverse():
    t = transform((1, 2, 3), (0.1, 0.2, 0.3))
    np.testing.assert_allclose(inverse(t) @ t, np.eye(4), atol=1e-15)
    np.testing.assert_allclose(t[:3, 3], (1, 2, 3))


def test_as_transform_rejects_non_rigid():
    with pytest.raises(ValueError, match="proper rotation"):
        as_transform(np.diag([1, 1, -1, 1]))
    with pytest.raises(ValueError, match=r"\(4, 4\)"):
        as_transform(np.eye(3))


def test_fmt():
    assert fmt(6.929183) == "6.9292"
    assert fmt(-0.0) == "0"
    assert fmt(1.234e-7) == "1.234e-07"
    assert fmt(float("nan")) == "nan"


@pytest.mark.parametrize(
    ("value", "text"),
    [
        (0.0, "0"),
        (-0.0, "0"),
        (157.6325, "157.6325"),
        (1e-5, "1e-5"),
        (0.00012345678, "0.00012345678"),
        (2.5e9, "2.5e9"),
        (-13.235, "-13.235"),
        (1024.0, "1024"),
        (1 / 3, "0.333333333"),
    ],
)
def test_xml_number(value, text):
    assert xml_number(value) == text


def test_xml_number_is_deterministic_and_round_trips():
    rng = np.random.default_rng(1)
    for value in rng.lognormal(0, 8, 500) * rng.choice([-1, 1], 500):
        text = xml_number(value)
        assert xml_number(float(text)) == text
        assert float(text) == pytest.approx(value, rel=1e-8)


def test_xml_number_refuses_nan():
    with pytest.raises(ValueError, match="cannot write"):
        xml_number(float("nan"))


def test_inertial_block_for_the_mrm_link():
    block = inertial_block(cylinder(0.35, 0.4, density=1024).placed(xyz=(0, 0, 0.2)), level=1)
    m = 1024 * math.pi * 0.35**2 * 0.4
    side, axial = f"{m * (3 * 0.35**2 + 0.4**2) / 12:.6g}", f"{m * 0.35**2 / 2:.6g}"
    assert (f"{m:.6g}", side, axial) == ("157.633", "6.92926", "9.65499")
    assert block.splitlines() == [
        "  <inertial>",
        '    <origin xyz="0 0 0.2" rpy="0 0 0"/>',
        '    <mass value="157.633"/>',
        f'    <inertia ixx="{side}" ixy="0" ixz="0" iyy="{side}" iyz="0" izz="{axial}"/>',
        "  </inertial>",
    ]
