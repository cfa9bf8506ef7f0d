"""IN061 product-signs-flipped: a turned box's products, written with the opposite sign."""

from __future__ import annotations

import math

import numpy as np
import pytest
from kit.moments import box_tensor
from kit.urdf import box, collision, inertial, moving

from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.frames import rpy_matrix

MASS, SIZE = 2.0, (0.4, 0.2, 0.1)


def plate(ixy, ixz, iyz, diag, rpy):
    """The box turned by ``rpy``, its moments ``diag`` and these products written."""
    ixx, iyy, izz, ixy, ixz, iyz = (float(v) for v in (*diag, ixy, ixz, iyz))
    written = inertial(MASS, ixx, iyy, izz, ixy=ixy, ixz=ixz, iyz=iyz)
    return moving(written + collision(box(*SIZE), rpy=rpy), name="plate")


def turned_box(rpy):
    return box_tensor(MASS, SIZE, rpy_matrix(rpy))


@pytest.mark.parametrize(
    ("rpy", "codes"),
    [
        ((0.0, 0.0, math.pi / 6), ["IN061"]),
        # three products flipped: no longer a valid tensor, which stays IN011's error
        ((0.4, 0.3, 0.5), ["IN011", "IN061"]),
    ],
)
def test_flipped_products_fire_with_the_geometry_signs(lint, rpy, codes):
    right = turned_box(rpy)
    diag = tuple(float(v) for v in np.diag(right))
    flipped = plate(-right[0, 1], -right[0, 2], -right[1, 2], diag, rpy)
    findings = lint(flipped)
    assert [f.code for f in findings] == codes
    expected = findings[-1].expected
    for name, (i, j) in {"ixy": (0, 1), "ixz": (0, 2), "iyz": (1, 2), "ixx": (0, 0)}.items():
        assert expected[name] == pytest.approx(right[i, j], abs=1e-12)
    assert "opposite sign" in findings[-1].detail and findings[-1].help == (
        "negate ixy, ixz and iyz"
    )
    assert findings[-1].message.startswith("link `plate`: product signs flipped: ")
    # the same values with URDF's signs: nothing to say
    assert lint(plate(right[0, 1], right[0, 2], right[1, 2], diag, rpy)) == []


def test_small_products_flipped_are_within_the_mismatch_floor(lint):
    """A box turned by 1°: flipping its tiny product changes no moment by 10 %."""
    rpy = (0.0, 0.0, math.radians(1))
    right = turned_box(rpy)
    diag = tuple(float(v) for v in np.diag(right))
    assert lint(plate(-right[0, 1], 0.0, 0.0, diag, rpy)) == []


def test_the_message_names_the_largest_product_and_the_detail_every_one(lint):
    """One line: the largest written product against the geometry's; the detail lists the three
    written and the geometry's, and the convention."""
    rpy = (0.4, 0.3, 0.5)
    right = turned_box(rpy)
    diag = tuple(float(v) for v in np.diag(right))
    (finding,) = lint(plate(-right[0, 1], -right[0, 2], -right[1, 2], diag, rpy), "IN061")
    i, j = max(((0, 1), (0, 2), (1, 2)), key=lambda ij: abs(right[ij]))
    name = "i" + "xyz"[i] + "xyz"[j]
    assert finding.message == (
        f"link `plate`: product signs flipped: {name} {fmt(-right[i, j], 3)}, "
        f"geometry {fmt(right[i, j], 3)}"
    )
    assert len(finding.message) <= 100
    detail = finding.detail
    assert "URDF's convention is ixy = -∫xy dm" in detail
    for n, (a, b) in {"ixy": (0, 1), "ixz": (0, 2), "iyz": (1, 2)}.items():
        assert f"{n} {fmt(-right[a, b], 5)}" in detail.split("; ")[0]  # written
        assert f"{n} {fmt(right[a, b], 5)}" in detail.split("; ")[1]  # the geometry's
    assert "the collision box (0.4 × 0.2 × 0.1 m) gives" in detail
