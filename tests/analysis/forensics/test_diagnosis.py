"""analysis.forensics.diagnosis: the tensors no slip explains (right ones, rounded ones, real-part
deviations, random ones)."""

from __future__ import annotations

import numpy as np
from forensic_cases import (
    BOX,
    MASS,
    VOLUME,
    box_case,
    box_hull,
    box_tensor,
    cylinder_tensor,
    props,
    rounded,
)

from inertia_kit.analysis.bounds import Hull
from inertia_kit.analysis.forensics.diagnosis import diagnose
from inertia_kit.physics.frames import rpy_matrix


def test_the_right_tensor_is_not_diagnosed_exact_or_rounded():
    right = box_tensor(MASS, *BOX)
    assert box_case(right) is None
    assert box_case(rounded(right, 3)) is None
    turned = rpy_matrix([0.4, 0.3, 0.5])
    expected = props(MASS, box_tensor(MASS, *BOX, turned))
    assert diagnose(props(MASS, rounded(expected.inertia, 3)), expected) is None


def test_real_part_deviations_are_not_diagnosed():
    right = box_tensor(MASS, *BOX)
    assert box_case(2 * right) is None  # a hollow-ish part
    assert box_case(right / 3) is None  # a dense core
    assert box_case(right * np.diag([3.0, 1.0, 1.0])) is None  # one moment 3 times
    assert box_case(right * np.diag([1.0, 1.5, 1.0])) is None


def test_a_rod_with_heavy_ends_is_not_a_shifted_point():
    """
    Mass at both ends of a rod adds the same δ to both transverse moments: the signature of a
    tensor about a point on the axis. Inside the rod's Bhatia–Davis bound it is not diagnosed.
    """
    mass, radius, length = 1.0, 0.02, 0.3
    rod = cylinder_tensor(mass, radius, length)
    ends = rod + np.diag([1.0, 1.0, 0.0]) * rod[0, 0]  # transverse ×2
    hull = Hull(np.array([[0, 0, -length / 2], [0, 0, length / 2]]), np.array([radius, radius]))
    assert diagnose(props(mass, ends), props(mass, rod), hull=hull) is None


def test_a_too_large_value_across_a_round_body_is_not_solved_for():
    """
    Across a cylinder the excess of a tensor about a point on its axis is (δ, δ, 0): a wrong
    transverse value written with the body's symmetry fits it whatever it is, even beyond what any
    mass inside allows. Only a named point explains it.
    """
    mass, radius, length = 2.0, 0.05, 0.2
    rod = cylinder_tensor(mass, radius, length)
    declared = rod + np.diag([1.0, 1.0, 0.0]) * 4 * rod[0, 0]  # ×5 across
    hull = Hull(np.array([[0, 0, -length / 2], [0, 0, length / 2]]), np.array([radius, radius]))
    assert diagnose(props(mass, declared), props(mass, rod), hull=hull) is None


def test_random_tensors_are_not_explained():
    """No slip explains tensors drawn at random around the box's (0.3–3 times, any axes)."""
    rng = np.random.default_rng(20240611)
    turned = rpy_matrix([0.4, 0.3, 0.5])
    expected = props(MASS, box_tensor(MASS, *BOX, turned))
    hull = box_hull(*BOX, rotation=turned)
    scale = np.trace(expected.inertia) / 3
    found = []
    for _ in range(300):
        a, b = np.exp(rng.uniform(np.log(0.3), np.log(3.0), 2)) * scale
        c = rng.uniform(abs(a - b), a + b)  # the triangle inequality holds
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        tensor = q @ np.diag([a, b, c]) @ q.T
        points = [("the link origin", rng.uniform(-0.3, 0.3, 3))]
        found.append(
            diagnose(props(MASS, tensor), expected, points=points, hull=hull, volume=VOLUME)
        )
    assert [d.wording.summary for d in found if d is not None] == []
