"""IN064 inertia-attributes-transposed: the written values in the wrong attributes."""

from __future__ import annotations

import math

import pytest
from kit.moments import box_tensor
from kit.urdf import box, collision, inertial, moving

from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.frames import rpy_matrix

MASS, SIZE, YAW = 12.0, (0.4, 0.3, 0.2), math.pi / 6


def turned_box():
    return box_tensor(MASS, SIZE, rpy_matrix([0.0, 0.0, YAW]))


def plate(**values):
    """The turned box with these ``<inertia>`` values written."""
    written = inertial(MASS, **{name: float(v) for name, v in values.items()})
    return moving(written + collision(box(*SIZE), rpy=f"0 0 {YAW!r}"), name="plate")


def test_swapped_products(lint):
    t = turned_box()
    text = plate(ixx=t[0, 0], ixy=0.0, ixz=float(t[0, 1]), iyy=t[1, 1], iyz=0.0, izz=t[2, 2])
    findings = lint(text)
    assert [f.code for f in findings] == ["IN064"]
    finding = findings[0]
    assert finding.message == (
        f"link `plate`: ixy and ixz are swapped (written ixy 0, ixz {fmt(t[0, 1], 3)})"
    )
    assert len(finding.message) <= 100
    # the detail: the values written, reassigned, and how well they fit
    assert finding.detail.startswith(
        f"the six inertia values are in the wrong attributes: ixy and ixz are swapped: "
        f"written ixy 0, ixz {fmt(t[0, 1], 4)}; reassigned, ixy {fmt(t[0, 1], 5)}, ixz 0 match "
        "the collision box (0.4 × 0.3 × 0.2 m) within "
    )
    assert finding.expected["assignment"] == {"ixy": "ixz", "ixz": "ixy"}
    assert finding.expected["ixy"] == pytest.approx(t[0, 1])
    assert finding.expected["ixz"] == 0.0
    assert lint(plate(ixx=t[0, 0], ixy=t[0, 1], ixz=0.0, iyy=t[1, 1], iyz=0.0, izz=t[2, 2])) == []


def test_moments_first_order_read_in_urdf_order_is_named_beside_the_invalid_tensor(lint):
    """Ixx Iyy Izz Ixy Ixz Iyz pasted into ixx ixy ixz iyy iyz izz: not positive definite."""
    t = turned_box()
    listed = [t[0, 0], t[1, 1], t[2, 2], t[0, 1], t[0, 2], t[1, 2]]
    names = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
    findings = lint(plate(**{n: float(v) for n, v in zip(names, listed, strict=True)}))
    codes = {f.code for f in findings}
    assert "IN064" in codes and codes & {"IN010", "IN011"}  # the invalid tensor stays an error
    finding = next(f for f in findings if f.code == "IN064")
    assert finding.message == (
        "link `plate`: inertia values in the wrong attributes: ixy, ixz, iyy, izz"
    )
    assert "ixy's value is in iyy" in finding.detail
    for name, (i, j) in zip(names, ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)), strict=True):
        assert finding.expected[name] == pytest.approx(t[i, j], abs=1e-12)
