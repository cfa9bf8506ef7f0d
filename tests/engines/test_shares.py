"""shares.py: what share of its lumped body a welded link carries, against closed forms."""

from __future__ import annotations

import math

import pytest
from kit.moments import box_moments
from kit.urdf import box, box_inertial, collision, inertial, joint, link, robot

from inertia_kit.analysis.links import analyse
from inertia_kit.description.loader import load
from inertia_kit.engines.shares import NEGLIGIBLE, share

TRUNK = (5.0, (0.4, 0.2, 0.1))  # kg, m: a quadruped's trunk
OFFSET = 0.2  # m, along x: a camera on the trunk's front face


def analysed(tmp_path, *parts):
    path = tmp_path / "robot.urdf"
    path.write_text(robot(*parts))
    return analyse(load(path))


def trunk_with(frame_body: str, *, kind="fixed", world=False, at=OFFSET):
    """World → (revolute or fixed) → trunk → ``kind`` joint at (``at``, 0, 0) → `frame`."""
    return (
        link("world"),
        joint("world", "trunk", "fixed" if world else "revolute"),
        link("trunk", box_inertial(TRUNK[0], TRUNK[1]), collision(box(*TRUNK[1]))),
        joint("trunk", "frame", kind, xyz=(at, 0, 0)),
        link("frame", frame_body),
    )


def closed_form(m: float, moment: float) -> tuple[float, float]:
    """
    The mass share and the largest moment share of an isotropic point-like part (``m`` kg,
    ``moment`` kg·m² about each axis) at x = 0.2 m on the trunk: the lumped COM moves to
    x = m·0.2/(M + m); the axes stay the trunk's; the part adds its own moment plus m·d² about
    y and z, its own moment about x.
    """
    mass, size = TRUNK
    ixx, iyy, izz = box_moments(mass, size)
    total = mass + m
    c = m * OFFSET / total
    d = OFFSET - c
    shares = [
        moment / (ixx + moment),
        (moment + m * d**2) / (iyy + mass * c**2 + moment + m * d**2),
        (moment + m * d**2) / (izz + mass * c**2 + moment + m * d**2),
    ]
    return m / total, max(shares)


def test_a_sensor_frame_on_a_trunk(tmp_path):
    found = share(analysed(tmp_path, *trunk_with(inertial(1e-5, 1e-6))), "frame")
    mass_share, inertia_share = closed_form(1e-5, 1e-6)
    assert found.body == "trunk"
    assert found.body_mass == pytest.approx(TRUNK[0] + 1e-5)
    assert found.mass == pytest.approx(mass_share)
    assert found.inertia == pytest.approx(inertia_share)
    assert found.negligible and not found.massless
    assert "of the mass" in found.text() and "`trunk`" in found.text()


def test_a_big_welded_part_is_not_negligible(tmp_path):
    found = share(analysed(tmp_path, *trunk_with(inertial(1.0, 0.01))), "frame")
    mass_share, inertia_share = closed_form(1.0, 0.01)
    assert found.mass == pytest.approx(mass_share)
    assert found.inertia == pytest.approx(inertia_share)
    assert not found.negligible


def test_the_share_does_not_depend_on_where_the_offset_is_written(tmp_path):
    # the frame's mass 0.2 m out: on the joint's <origin>, or on the <inertial><origin>
    on_joint = share(analysed(tmp_path, *trunk_with(inertial(1e-4, 1e-6))), "frame")
    on_inertial = share(
        analysed(tmp_path, *trunk_with(inertial(1e-4, 1e-6, xyz=(OFFSET, 0, 0)), at=0)), "frame"
    )
    assert on_inertial.mass == pytest.approx(on_joint.mass)
    assert on_inertial.inertia == pytest.approx(on_joint.inertia)


def test_the_trunk_judged_from_the_frame_it_carries(tmp_path):
    # the trunk's share of its own body: all but the frame's
    found = share(analysed(tmp_path, *trunk_with(inertial(1e-5, 1e-6))), "trunk")
    assert found.mass == pytest.approx(TRUNK[0] / (TRUNK[0] + 1e-5))
    assert not found.negligible


def test_a_massless_frame_adds_nothing(tmp_path):
    for body in (inertial(0, 0), ""):
        found = share(analysed(tmp_path, *trunk_with(body)), "frame")
        assert (found.mass, found.inertia) == (0, 0)
        assert found.massless and found.negligible
        assert "adds nothing" in found.text()


@pytest.mark.parametrize(
    "body",
    [
        inertial(0, 1e-6),  # Drake: a 1 kg sphere; PyBullet: the base drifts
        inertial(-1e-5, 1e-6),  # Drake: a 1 kg sphere; PyBullet: the base drifts
        inertial(1e-5, -1e-6),  # MuJoCo refuses ("inertia must have positive eigenvalues")
        inertial(1e-5, 1e-6, 1e-6, 3e-6),  # Drake: no rigid body has it
        inertial("nan", 1e-6),
        '<inertial><mass value="1e-5"/></inertial>',
    ],
    ids=["tensor-on-zero-mass", "negative-mass", "negative-moment", "triangle", "nan", "no-tensor"],
)
def test_values_an_engine_does_not_accept_are_never_negligible(tmp_path, body):
    assert share(analysed(tmp_path, *trunk_with(body)), "frame") is None


def test_no_body_to_judge_by(tmp_path):
    # alone on a moving joint
    assert (
        share(analysed(tmp_path, *trunk_with(inertial(1e-5, 1e-6), kind="revolute")), "frame")
        is None
    )
    # welded to the world: never integrated
    assert share(analysed(tmp_path, *trunk_with(inertial(1e-5, 1e-6), world=True)), "frame") is None
    # the other links of the group carry no mass
    parts = (link("world"), joint("world", "base"), link("base"), joint("base", "frame", "fixed"))
    assert share(analysed(tmp_path, *parts, link("frame", inertial(1e-5, 1e-6))), "frame") is None


def test_a_frame_on_a_body_with_no_moment_about_an_axis(tmp_path):
    # the trunk a point mass: whatever the frame adds about an axis is all of it
    parts = trunk_with(inertial(1e-5, 1e-6))
    parts = (*parts[:2], link("trunk", inertial(5.0, 0)), *parts[3:])
    found = share(analysed(tmp_path, *parts), "frame")
    assert not found.negligible
    assert math.isinf(found.inertia) or found.inertia > NEGLIGIBLE


@pytest.mark.parametrize(
    "body",
    [
        inertial(1e300, 1e300),
        inertial(1e-5, 1e-6, xyz=(1e200, 0, 0)),
        inertial(5e-324, 5e-324),
        inertial(1e-5, 1e-6, xyz=("nan", 0, 0)),
    ],
    ids=["huge", "far", "subnormal", "nan-origin"],
)
def test_values_near_the_float_range_never_crash_nor_warn(tmp_path, body):
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        found = share(analysed(tmp_path, *trunk_with(body)), "frame")
    assert found is None or not found.negligible or found.mass < NEGLIGIBLE


def test_a_massless_frame_welded_to_the_world_is_a_static_frame(tmp_path):
    # Universal Robots' `base`: mass 0, a zero tensor, welded to `base_link`, welded to `world`
    found = share(analysed(tmp_path, *trunk_with(inertial(0, 0), world=True)), "frame")
    assert found.static and found.massless and found.body == "world"
    assert "welded to the world" in found.text()
    # with a tensor on its zero mass it is not a frame (Drake puts a 1 kg sphere there)
    assert share(analysed(tmp_path, *trunk_with(inertial(0, 1e-6), world=True)), "frame") is None
