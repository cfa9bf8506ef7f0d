"""engines.drake and engines.drake_reading: how Drake reads a file, without Drake (the real
one judges the predictions in ``test_drake_matrix.py``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from inertia_kit.engines.drake import plausible_sphere
from inertia_kit.engines.drake_reading import (
    could_be_physically_valid,
    fmt_double,
    fmt_eigen_row,
    invalid_inertia_message,
    read_numbers,
)


def test_plausible_sphere_is_water_density():
    mass, radius, moment = plausible_sphere(2.0)
    assert mass == 2.0
    assert 1000 * 4 / 3 * math.pi * radius**3 == pytest.approx(2.0)
    assert moment == pytest.approx(0.4 * 2.0 * radius**2)
    assert plausible_sphere(-1.0)[0] == 1.0


@pytest.mark.parametrize(
    ("text", "numbers"),
    [
        ("2", [2.0]),
        (" 2 ", [2.0]),
        ("+2", [2.0]),
        (".5", [0.5]),
        ("5.", [5.0]),
        ("-.5e1", [-5.0]),
        ("2kg", [2.0]),  # the read stops at `k`
        ("0x10", [0.0]),  # no hexadecimal: 0, then `x` stops it
        ("1,5", [1.0]),
        ("1.2.3", [1.2, 0.3]),
        ("1 2", [1.0, 2.0]),
        ("1e-400", [0.0]),  # an underflow reads
        ("1e-320", [1e-320]),
        ("1e999", []),  # an overflow does not
        ("nan", []),
        ("inf", []),
        ("1e", []),  # strtod would not take all of `1e`
        ("", []),
        ("  ", []),
        ("-", []),
        (".", []),
    ],
)
def test_numbers_read_as_istringstream_reads_them(text, numbers):
    assert read_numbers(text) == numbers


def test_doubles_written_as_fmt_writes_them():
    assert [fmt_double(v) for v in (0.0, 1.0, -0.0, 0.001, 1e-05, 1e16, 0.1 + 0.2)] == [
        "0",
        "1",
        "-0",
        "0.001",
        "1e-05",
        "1e+16",
        "0.30000000000000004",
    ]
    assert fmt_eigen_row((1e-09, 1.0, 1.0)) == "1e-09     1     1"


def test_validity_has_an_absolute_floor():
    # ε = 16·2⁻⁵²·max(1, trace/2): a moment of -1e-16 passes, -4e-15 does not
    assert could_be_physically_valid(np.diag([-1e-16, 0.01, 0.01]))
    assert not could_be_physically_valid(np.diag([-4e-15, 0.001, 0.001]))
    assert could_be_physically_valid(np.diag([0.25, 0.25, 0.5]))
    assert not could_be_physically_valid(np.diag([0.25, 0.25, 0.5000000001]))


def test_invalid_inertia_message_is_drakes():
    assert invalid_inertia_message(np.diag([1.0, 1.0, 3.0])) == (
        "While parsing inertia matrix: MakeFromMomentsAndProductsOfInertia(): The rotational "
        "inertia\n[1  0  0]\n[0  1  0]\n[0  0  3]\ndid not pass the test "
        "CouldBePhysicallyValid().\nThe associated principal moments of inertia:\n1  1  3\n"
        "do not satisfy the triangle inequality."
    )
    negative = invalid_inertia_message(np.diag([-0.01, 0.01, 0.01]))
    assert negative.endswith("-0.01  0.01  0.01\nare invalid since at least one is negative.")
    assert "[-0.01      0      0]" in negative


def test_a_moment_at_the_edge_of_double_precision_warns_nothing(lint):
    """Found by hypothesis: Drake's validity sum overflowed with a numpy warning."""
    import warnings

    body = (
        '<link name="world"/><joint name="j" type="fixed"><parent link="world"/>'
        '<child link="l"/></joint><link name="l"><inertial><mass value="1"/>'
        '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1.7976931348623157e308"/>'
        "</inertial></link>"
    )
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        lint(f'<robot name="r">{body}</robot>', "IN0", engines=("drake",))
