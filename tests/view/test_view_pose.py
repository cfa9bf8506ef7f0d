"""Each link's world frame in the zero pose, against matrices composed by hand."""

from __future__ import annotations

import math

import numpy as np
from kit import write
from kit.urdf import link, robot

from inertia_kit.description.loader import load
from inertia_kit.view.pose import zero_pose


def _rz(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def _rx(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def _shift(x, y, z):
    m = np.eye(4)
    m[:3, 3] = (x, y, z)
    return m


def _joint(parent, child, xyz, rpy, kind="revolute"):
    return (
        f'<joint name="j_{child}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
        f'<origin xyz="{xyz}" rpy="{rpy}"/><axis xyz="0 0 1"/>'
        '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
    )


def test_a_chain_composes_its_origins(tmp_path):
    text = robot(
        link("base"),
        _joint("base", "a", "0.1 0 0.2", f"0 0 {math.pi / 2}"),
        link("a"),
        # a revolute joint with a non-zero rpy: roll of 0.3 rad, then 0.5 m along its x
        _joint("a", "b", "0.5 0 0", "0.3 0 0"),
        link("b"),
        _joint("b", "c", "0 0.2 0", "0 0 0", kind="fixed"),
        link("c"),
    )
    poses = zero_pose(load(write(tmp_path / "r.urdf", text)))
    a = _shift(0.1, 0, 0.2) @ _rz(math.pi / 2)
    b = a @ _shift(0.5, 0, 0) @ _rx(0.3)
    c = b @ _shift(0, 0.2, 0)
    np.testing.assert_allclose(poses["base"], np.eye(4), atol=1e-15)
    np.testing.assert_allclose(poses["a"], a, atol=1e-12)
    np.testing.assert_allclose(poses["b"], b, atol=1e-12)
    np.testing.assert_allclose(poses["c"], c, atol=1e-12)
    # b's origin in the world: 0.1 + 0 along x, 0.5 along y (a's x is the world's y), 0.2 up
    np.testing.assert_allclose(poses["b"][:3, 3], [0.1, 0.5, 0.2], atol=1e-12)


def test_every_root_of_a_disconnected_robot_is_at_the_identity(tmp_path):
    text = robot(
        link("one"),
        _joint("one", "arm", "1 2 3", "0 0 0"),
        link("arm"),
        link("two"),
        _joint("two", "leg", "0 0 -1", "0 0 0"),
        link("leg"),
    )
    poses = zero_pose(load(write(tmp_path / "r.urdf", text)))
    np.testing.assert_allclose(poses["one"], np.eye(4))
    np.testing.assert_allclose(poses["two"], np.eye(4))
    np.testing.assert_allclose(poses["arm"], _shift(1, 2, 3))
    np.testing.assert_allclose(poses["leg"], _shift(0, 0, -1))


def test_a_cycle_and_an_unknown_parent_give_every_link_a_pose(tmp_path):
    text = robot(
        link("a"),
        link("b"),
        _joint("a", "b", "1 0 0", "0 0 0"),
        _joint("b", "a", "0 1 0", "0 0 0"),
        link("orphan"),
        _joint("nowhere", "orphan", "5 5 5", "0 0 0"),
    )
    poses = zero_pose(load(write(tmp_path / "r.urdf", text)))
    assert set(poses) == {"a", "b", "orphan"}
    np.testing.assert_allclose(poses["a"], np.eye(4))
    np.testing.assert_allclose(poses["b"], _shift(1, 0, 0))
    np.testing.assert_allclose(poses["orphan"], np.eye(4))
