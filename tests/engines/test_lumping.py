"""lumping.py: the bodies each engine simulates, checked against closed forms."""

from __future__ import annotations

import numpy as np
import pytest
from kit import REPO
from kit.moments import box_tensor
from kit.urdf import LIMIT, box_inertial

from inertia_kit.analysis.links import analyse
from inertia_kit.description.loader import load
from inertia_kit.engines.lumping import (
    Body,
    EngineBodies,
    preserved_joints,
    sdf_collision_names,
    simulated_bodies,
)
from inertia_kit.engines.vocabulary import ENGINES


def body_of(found: EngineBodies, link: str) -> Body | None:
    """The body ``link`` is part of (``None`` when dropped or unknown)."""
    return next((body for body in found.bodies if link in body.links), None)


def robot(tmp_path, body, name="robot.urdf"):
    path = tmp_path / name
    path.write_text(f'<robot name="r">{body}</robot>')
    return analyse(load(path))


WELDED = f"""
<link name="base">{box_inertial(5.0, (0.5, 0.5, 0.5))}</link>
<joint name="j" type="revolute"><parent link="base"/><child link="a"/>
  <axis xyz="0 0 1"/>{LIMIT}</joint>
<link name="a">{box_inertial(2.0, (0.2, 0.2, 0.2))}
  <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
<joint name="weld" type="fixed"><parent link="a"/><child link="b"/><origin xyz="0 0 0.5"/></joint>
<link name="b">{box_inertial(1.0, (0.1, 0.2, 0.3))}
  <collision><geometry><box size="0.1 0.2 0.3"/></geometry></collision>
  <collision name="tip"><geometry><sphere radius="0.01"/></geometry></collision></link>
<joint name="frame_joint" type="fixed"><parent link="b"/><child link="frame"/></joint>
<link name="frame"/>
"""


def expected_welded():
    mass = 3.0
    com = np.array([0.0, 0.0, 1.0 / 6.0])
    shift_a = 2.0 * (1.0 / 6.0) ** 2
    shift_b = 1.0 * (1.0 / 3.0) ** 2
    tensor = box_tensor(2.0, (0.2, 0.2, 0.2)) + box_tensor(1.0, (0.1, 0.2, 0.3))
    tensor += np.diag([shift_a + shift_b, shift_a + shift_b, 0.0])
    return mass, com, tensor


@pytest.mark.parametrize("engine", ["gazebo", "mujoco"])
def test_two_welded_boxes_are_one_body_by_the_parallel_axis_theorem(tmp_path, engine):
    found = simulated_bodies(robot(tmp_path, WELDED), engine)
    body = body_of(found, "b")
    assert body.name == "a" and body.links == ("a", "b", "frame") and body.joint == "j"
    mass, com, tensor = expected_welded()
    props = body.mass_properties
    assert props.mass == pytest.approx(mass)
    np.testing.assert_allclose(props.com, com, atol=1e-12)
    np.testing.assert_allclose(props.inertia, tensor, rtol=1e-12, atol=1e-15)
    assert found.dropped == ()


@pytest.mark.parametrize("engine", ["drake", "pybullet", "kdl"])
def test_engines_that_do_not_lump_keep_every_link(tmp_path, engine):
    found = simulated_bodies(robot(tmp_path, WELDED), engine)
    assert [b.links for b in found.bodies] == [("base",), ("a",), ("b",), ("frame",)]
    assert body_of(found, "b").joint == "weld"
    assert body_of(found, "b").mass_properties.mass == pytest.approx(1.0)
    frame = body_of(found, "frame").mass_properties
    if engine == "pybullet":  # a link without <inertial> gets 1 kg there (IN073)
        assert frame.mass == 1.0
    else:
        assert frame is None


def test_pybullet_merges_fixed_links_with_the_flag(tmp_path):
    found = simulated_bodies(robot(tmp_path, WELDED), "pybullet", merge_fixed_links=True)
    assert body_of(found, "b").links == ("a", "b", "frame")
    assert body_of(found, "b").mass_properties.mass == pytest.approx(3.0)


def test_mujoco_fuses_the_root_group_into_the_world(tmp_path):
    found = simulated_bodies(robot(tmp_path, WELDED), "mujoco")
    world = body_of(found, "base")
    assert world.name == "world" and world.static and world.joint is None


def test_mujoco_matches_the_installed_mujoco(tmp_path):
    mujoco = pytest.importorskip("mujoco")
    analysis = robot(tmp_path, WELDED)
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "robot.urdf"))
    names = [model.body(i).name for i in range(model.nbody)]
    found = simulated_bodies(analysis, "mujoco")
    assert names == [b.name for b in found.bodies]
    body = body_of(found, "a").mass_properties
    index = names.index("a")
    assert model.body_mass[index] == pytest.approx(body.mass)
    np.testing.assert_allclose(model.body_ipos[index], body.com, atol=1e-9)
    np.testing.assert_allclose(
        np.sort(model.body_inertia[index]), body.principal_moments, rtol=1e-9
    )


def test_kdl_root_segment_carries_no_inertia(tmp_path):
    analysis = robot(tmp_path, f'<link name="base">{box_inertial(5.0, (1, 1, 1))}</link>')
    body = simulated_bodies(analysis, "kdl").bodies[0]
    assert body.static and body.mass_properties is None and "KDL" in body.note


def test_gazebo_drops_a_massless_moving_link_with_its_subtree(tmp_path):
    text = (
        WELDED
        + f"""
<joint name="j2" type="revolute"><parent link="b"/><child link="ghost"/>
  <axis xyz="0 0 1"/>{LIMIT}</joint>
<link name="ghost"/>
<joint name="j3" type="revolute"><parent link="ghost"/><child link="hand"/>
  <axis xyz="0 0 1"/>{LIMIT}</joint>
<link name="hand">{box_inertial(1.0, (0.1, 0.1, 0.1))}</link>
"""
    )
    found = simulated_bodies(robot(tmp_path, text), "gazebo")
    assert [(d.link, d.joint, d.cause, d.reason) for d in found.dropped] == [
        ("ghost", "j2", "ghost", "no-inertial"),
        ("hand", "j3", "ghost", "ancestor"),
    ]
    assert body_of(found, "hand") is None
    # the other engines keep them
    assert body_of(simulated_bodies(robot(tmp_path, text), "drake"), "ghost") is not None


def test_gazebo_massless_fixed_link_is_lumped_not_dropped(tmp_path):
    found = simulated_bodies(robot(tmp_path, WELDED), "gazebo")
    assert "frame" in body_of(found, "a").links and found.dropped_link("frame") is None


def test_gazebo_massless_root_is_dropped_with_the_whole_robot(tmp_path):
    text = f"""<link name="base"/>
<joint name="j" type="revolute"><parent link="base"/><child link="a"/>
  <axis xyz="0 0 1"/>{LIMIT}</joint>
<link name="a">{box_inertial(2.0, (0.2, 0.2, 0.2))}</link>"""
    found = simulated_bodies(robot(tmp_path, text), "gazebo")
    assert found.bodies == () and [d.link for d in found.dropped] == ["base", "a"]


def test_gazebo_preserve_fixed_joint_keeps_the_link(tmp_path):
    text = WELDED + (
        '<gazebo reference="weld"><preserveFixedJoint>true</preserveFixedJoint></gazebo>'
    )
    analysis = robot(tmp_path, text)
    assert preserved_joints(analysis.robot) == {"weld"}
    found = simulated_bodies(analysis, "gazebo")
    assert body_of(found, "a").links == ("a",)
    assert body_of(found, "b").links == ("b", "frame") and body_of(found, "b").joint == "weld"


def test_gazebo_disable_fixed_joint_lumping_keeps_the_link(tmp_path):
    text = WELDED + (
        '<gazebo reference="weld"><disableFixedJointLumping>1</disableFixedJointLumping></gazebo>'
    )
    assert body_of(simulated_bodies(robot(tmp_path, text), "gazebo"), "b").name == "b"


def test_gazebo_does_not_lump_into_world(tmp_path):
    text = f"""<link name="world"/>
<joint name="mount" type="fixed"><parent link="world"/><child link="a"/></joint>
<link name="a">{box_inertial(2.0, (0.2, 0.2, 0.2))}</link>"""
    found = simulated_bodies(robot(tmp_path, text), "gazebo")
    assert [(b.name, b.joint) for b in found.bodies] == [("a", "mount")]


def test_gazebo_collision_names_follow_sdformat(tmp_path):
    analysis = robot(tmp_path, WELDED)
    members = [analysis.by_name[n] for n in ("a", "b", "frame")]
    assert sdf_collision_names("a", members) == (
        "a_collision",
        "a_fixed_joint_lump__b_collision_1",
        "a_fixed_joint_lump__tip_collision_2",
    )
    assert (
        body_of(simulated_bodies(analysis, "gazebo"), "a").collisions[1].endswith("b_collision_1")
    )


def test_unknown_engine_is_an_error(tmp_path):
    with pytest.raises(ValueError, match="unknown engine"):
        simulated_bodies(robot(tmp_path, WELDED), "isaac")


@pytest.mark.parametrize("engine", ENGINES)
def test_seed_examples_load_for_every_engine(engine):

    examples = REPO / "examples"
    for path in sorted(examples.rglob("*.urdf")) + sorted(examples.rglob("*.urdf.xacro")):
        analysis = analyse(load(path))
        found = simulated_bodies(analysis, engine)
        covered = {n for b in found.bodies for n in b.links} | {d.link for d in found.dropped}
        assert covered == {link.name for link in analysis.links}, path
