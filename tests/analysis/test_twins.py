"""Twin names: which link names differ only by a left/right marker (analysis/twins)."""

from __future__ import annotations

import numpy as np
import pytest

from inertia_kit.analysis.twins import Plane, name_pairs, reflection, tokens
from inertia_kit.physics.mass import MassProperties


@pytest.mark.parametrize(
    ("name", "words"),
    [
        ("l_hip", ["l", "hip"]),
        ("LHipYaw", ["l", "hip", "yaw"]),
        ("FL_thigh", ["fl", "thigh"]),
        ("hip_R", ["hip", "r"]),
        ("arm_left_1_link", ["arm", "left", "1", "link"]),
        ("LeftShoulderYawLink", ["left", "shoulder", "yaw", "link"]),
    ],
)
def test_tokens(name, words):
    assert tokens(name) == words


@pytest.mark.parametrize(
    ("names", "pairs"),
    [
        (["l_hip", "r_hip"], [("l_hip", "r_hip")]),
        (["LHipYaw", "RHipYaw"], [("LHipYaw", "RHipYaw")]),
        (["arm_left_1_link", "arm_right_1_link"], [("arm_left_1_link", "arm_right_1_link")]),
        (
            ["FL_thigh", "FR_thigh", "RL_thigh", "RR_thigh"],
            [("FL_thigh", "FR_thigh"), ("RL_thigh", "RR_thigh")],
        ),
        (
            ["lf_foot", "rf_foot", "lh_foot", "rh_foot"],
            [("lf_foot", "rf_foot"), ("lh_foot", "rh_foot")],
        ),
        # front/rear and side-less names never pair
        (["FL_thigh", "RL_thigh"], []),
        (["fl_wheel", "bl_wheel"], []),
        (["hip", "knee"], []),
        (["l_hip", "r_knee"], []),
        # two right candidates for one left: ambiguous, no pair
        (["l_hip", "r_hip", "right_hip_x"], [("l_hip", "r_hip")]),
        (["hip_l", "hip_r", "hip_R"], []),
    ],
)
def test_name_pairs(names, pairs):
    assert name_pairs(names) == pairs


def test_reflection_flips_the_products_of_the_normal_axis():
    # across the xz-plane (normal y): ixy and iyz change sign, the rest stays; the COM's y too
    inertia = np.array([[3.0, 0.1, 0.2], [0.1, 4.0, 0.3], [0.2, 0.3, 5.0]])
    image = Plane(np.zeros(3), np.array([0.0, 1.0, 0.0])).mirror(
        MassProperties(2.0, (0.1, 0.2, 0.3), inertia)
    )
    assert image.mass == 2.0
    assert image.com == pytest.approx([0.1, -0.2, 0.3])
    expected = np.array([[3.0, -0.1, 0.2], [-0.1, 4.0, -0.3], [0.2, -0.3, 5.0]])
    assert image.inertia == pytest.approx(expected)
    p = reflection(np.array([0.0, 0.0, 1.0]))
    assert np.linalg.det(p) == pytest.approx(-1.0) and p @ p == pytest.approx(np.eye(3))


def test_mirror_across_an_offset_plane():
    # the plane y = 0.5: a point at y = 0.2 goes to y = 0.8
    image = Plane(np.array([0.0, 0.5, 0.0]), np.array([0.0, 1.0, 0.0])).mirror(
        MassProperties(1.0, (0.0, 0.2, 0.0), np.eye(3))
    )
    assert image.com == pytest.approx([0.0, 0.8, 0.0])
