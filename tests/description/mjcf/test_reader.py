"""
The MJCF reader on models written here, each read as the real MuJoCo compiles it: every
orientation form under the compiler's angle and eulerseq, frames, default classes and
childclass, includes, mesh reference frames, and the errors MuJoCo would also refuse.
"""

from __future__ import annotations

import os

import numpy as np
import pytest
from kit.mjcf import body_mass_properties, body_pose, written_mass_properties

from inertia_kit.analysis.links import analyse
from inertia_kit.description import model
from inertia_kit.description.mjcf.detect import is_mjcf
from inertia_kit.description.mjcf.reader import load_mjcf
from inertia_kit.errors import InputError
from inertia_kit.physics.frames import transform

mujoco = pytest.importorskip("mujoco")


def write(folder, name: str, text: str):
    path = folder / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


def both(path):
    """Our robot and MuJoCo's compiled model of ``path``."""
    return load_mjcf(path), mujoco.MjModel.from_xml_path(str(path))


def pose_of(robot, name: str) -> np.ndarray:
    origin = robot.parent_joint(name).origin
    return transform(origin.xyz, origin.rpy)


def mujoco_pose(mjmodel, name: str) -> np.ndarray:
    return body_pose(mjmodel, mujoco.mj_name2id(mjmodel, mujoco.mjtObj.mjOBJ_BODY, name))


def assert_inertial_is_mujocos(robot, mjmodel, name: str) -> None:
    inertial = robot.link(name).inertial
    body = mujoco.mj_name2id(mjmodel, mujoco.mjtObj.mjOBJ_BODY, name)
    mass, com, moments = body_mass_properties(mjmodel, body)
    _, _, ours = written_mass_properties(inertial)
    assert inertial.mass == pytest.approx(mass, rel=1e-12)
    np.testing.assert_allclose(inertial.origin.xyz, com, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(ours, moments, rtol=1e-10)


INERTIAL = (
    '<inertial pos="0.01 0.02 0.03" mass="2" fullinertia="0.03 0.02 0.025 0.001 -0.002 0.003"'
)
TURNED = '<inertial pos="0.01 0.02 0.03" mass="2" diaginertia="0.03 0.02 0.025"'


@pytest.mark.parametrize(
    ("compiler", "orientation"),
    [
        ("", 'quat="1 2 3 4"'),
        ("", 'euler="10 20 30"'),
        ('angle="radian"', 'euler="0.1 0.2 0.3"'),
        ('eulerseq="zyx"', 'euler="10 20 30"'),
        ('eulerseq="XYZ"', 'euler="10 -20 30"'),
        ('eulerseq="zXy"', 'euler="40 20 -30"'),
        ("", 'axisangle="1 1 0 45"'),
        ('angle="radian"', 'axisangle="0 0 2 1.5"'),
        ("", 'xyaxes="1 1 0 -1 1 0.2"'),
        ("", 'zaxis="0.2 -1 0.4"'),
        ("", 'zaxis="0 0 -1"'),
    ],
)
def test_every_orientation_form_is_mujocos(tmp_path, compiler, orientation):
    path = write(
        tmp_path,
        "m.xml",
        f"""<mujoco><compiler {compiler}/><worldbody>
          <body name="a" pos="0.1 0.2 0.3" {orientation}>
            <joint type="hinge"/>
            {TURNED} {orientation}/>
            <geom type="box" size="0.1 0.2 0.3" pos="0.05 0 0" {orientation}/>
          </body></worldbody></mujoco>""",
    )
    robot, mjmodel = both(path)
    np.testing.assert_allclose(pose_of(robot, "a"), mujoco_pose(mjmodel, "a"), atol=1e-12)
    assert_inertial_is_mujocos(robot, mjmodel, "a")
    (shape,) = robot.link("a").collisions
    placed = transform(shape.origin.xyz, shape.origin.rpy)
    rotation = np.zeros(9)
    mujoco.mju_quat2Mat(rotation, mjmodel.geom_quat[0])
    np.testing.assert_allclose(placed[:3, :3], rotation.reshape(3, 3), atol=1e-12)
    np.testing.assert_allclose(placed[:3, 3], mjmodel.geom_pos[0], atol=1e-12)


def test_frames_and_default_classes_are_mujocos(tmp_path):
    path = write(
        tmp_path,
        "m.xml",
        """<mujoco>
          <default>
            <geom density="500"/>
            <joint type="slide" axis="1 0 0"/>
            <default class="arm"><geom type="capsule" size="0.02 0.1" group="1"/>
              <default class="light"><geom density="100"/></default>
            </default>
            <default class="visual"><geom group="2" density="0"/></default>
          </default>
          <worldbody>
            <frame pos="0 0 1" euler="0 0 90" childclass="arm">
              <body name="a" pos="1 0 0">
                <joint/>
                <geom/>
                <geom class="light" pos="0 0 0.2"/>
                <geom class="visual" type="sphere" size="0.05"/>
                <frame euler="90 0 0"><body name="b" pos="0 0 0.5"><geom/></body></frame>
              </body>
            </frame>
          </worldbody></mujoco>""",
    )
    robot, mjmodel = both(path)
    for name in ("a", "b"):
        np.testing.assert_allclose(pose_of(robot, name), mujoco_pose(mjmodel, name), atol=1e-12)
    link = robot.link("a")
    assert robot.parent_joint("a").type == "prismatic"
    assert robot.parent_joint("b").type == "fixed"
    assert [(s.density, s.group, type(s.geometry).__name__) for s in link.collisions] == [
        (500.0, 1, "Capsule"),
        (100.0, 1, "Capsule"),
    ]
    (visual,) = link.visuals
    assert (visual.density, visual.group, visual.geometry.radius) == (0.0, 2, 0.05)
    assert [g.geometry.length for g in link.collisions] == [0.2, 0.2]


def test_includes_splice_files_in_place_and_keep_their_lines(tmp_path):
    write(
        tmp_path,
        "parts/arm.xml",
        '<mujoco>\n<body name="arm">\n<include file="parts/hand.xml"/>\n</body>\n</mujoco>',
    )
    write(
        tmp_path,
        "parts/hand.xml",
        '<mujoco>\n\n<body name="hand" pos="0 0 1">\n' + INERTIAL + "/>\n</body>\n</mujoco>",
    )
    path = write(
        tmp_path,
        "robot.xml",
        '<mujoco><worldbody>\n<include file="parts/arm.xml"/>\n</worldbody></mujoco>',
    )
    robot, mjmodel = both(path)
    assert [link.name for link in robot.links] == ["world", "arm", "hand"]
    hand = robot.link("hand")
    assert (hand.source.path, hand.source.line) == (str(tmp_path / "parts/hand.xml"), 3)
    assert hand.inertial.source.line == 4
    assert len(robot.files) == 3 and len(robot.reads) == 3
    assert_inertial_is_mujocos(robot, mjmodel, "hand")


def test_an_include_that_includes_itself_is_refused_where_it_is(tmp_path):
    write(tmp_path, "a.xml", '<mujoco>\n<include file="b.xml"/>\n</mujoco>')
    write(tmp_path, "b.xml", '<mujoco>\n\n<include file="a.xml"/>\n</mujoco>')
    path = write(tmp_path, "m.xml", '<mujoco><include file="a.xml"/></mujoco>')
    with pytest.raises(InputError, match="includes itself") as error:
        load_mjcf(path)
    assert (error.value.path, error.value.line) == (str(tmp_path / "b.xml"), 3)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes here")
def test_an_include_that_is_a_named_pipe_is_refused_as_one_not_as_missing(tmp_path):
    os.mkfifo(tmp_path / "part.xml")
    path = write(tmp_path, "m.xml", '<mujoco><include file="part.xml"/></mujoco>')
    with pytest.raises(InputError, match="is a named pipe, not a regular file") as error:
        load_mjcf(path)
    assert error.value.path == str(tmp_path / "part.xml")


@pytest.mark.parametrize(
    ("text", "message", "line"),
    [
        ('<mujoco>\n<include file="nowhere.xml"/></mujoco>', "no such file", 2),
        (
            '<mujoco><worldbody>\n<body><geom class="nope"/></body></worldbody></mujoco>',
            "unknown default class 'nope'",
            2,
        ),
        (
            '<mujoco><worldbody>\n<body quat="1 0 0 0" euler="0 0 0"/></worldbody></mujoco>',
            "orientation given twice",
            2,
        ),
        ('<mujoco><worldbody>\n<body quat="0 0 0 0"/></worldbody></mujoco>', "zero length", 2),
        ("<robot/>", "not an MJCF model", 1),
        (
            '<mujoco><worldbody><body>\n<inertial pos="0 0 0" mass="1" euler="0 0 1" '
            'fullinertia="1 1 1 0 0 0"/></body></worldbody></mujoco>',
            "MuJoCo refuses an orientation with a full tensor",
            2,
        ),
        ("<mujoco><worldbody>", "not well-formed", 1),
    ],
)
def test_what_mujoco_refuses_is_an_input_error_with_its_place(tmp_path, text, message, line):
    path = write(tmp_path, "m.xml", text)
    with pytest.raises(InputError, match=message) as error:
        load_mjcf(path)
    assert error.value.line == line


def test_a_number_that_is_none_is_recorded_not_raised(tmp_path):
    path = write(
        tmp_path,
        "m.xml",
        '<mujoco><worldbody><body name="a">\n<inertial pos="0 0 0" mass="heavy" '
        'diaginertia="1 1 1"/></body></worldbody></mujoco>',
    )
    robot = load_mjcf(path)
    (invalid,) = robot.invalid
    assert (invalid.text, invalid.attribute, invalid.source.line) == ("heavy", "mass", 2)
    assert robot.link("a").inertial.mass is invalid


def test_a_mesh_is_placed_with_its_reference_frame_and_scale(tmp_path):
    import trimesh

    box = trimesh.creation.box((0.2, 0.1, 0.4))
    box.apply_translation((0.3, -0.1, 0.2))
    (tmp_path / "assets").mkdir()
    box.export(tmp_path / "assets" / "part.stl")
    path = write(
        tmp_path,
        "m.xml",
        """<mujoco><compiler meshdir="assets"/>
          <asset><mesh file="part.stl" scale="2 1 1" refpos="0.1 0 0" refquat="1 0 0 1"
                       inertia="exact"/></asset>
          <worldbody><body name="a"><geom type="mesh" mesh="part" pos="0 0 1" euler="0 30 0"/>
          </body></worldbody></mujoco>""",
    )
    robot, mjmodel = both(path)
    (shape,) = robot.link("a").collisions
    assert isinstance(shape.geometry, model.Mesh)
    assert shape.geometry.inertia == "exact"
    # the file's x, scaled by 2, is the geom's y after the reference turn: the file is read
    # scaled by (1, 2, 1) and turned
    np.testing.assert_allclose(shape.geometry.scale, (1.0, 2.0, 1.0), atol=1e-12)
    centroid = np.array([*(np.array(shape.geometry.scale) * (0.3, -0.1, 0.2)), 1.0])
    placed = transform(shape.origin.xyz, shape.origin.rpy) @ centroid
    np.testing.assert_allclose(placed[:3], mjmodel.geom_pos[0], atol=1e-9)


def test_a_file_without_a_worldbody_is_a_fragment(tmp_path):
    path = write(tmp_path, "actuators.xml", "<mujoco><actuator/></mujoco>")
    assert load_mjcf(path).fragment


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        (b'<?xml version="1.0"?>\n<!-- a robot -->\n<mujoco model="x"/>', True),
        (b"<mujoco>", True),
        (b"<robot name='r'/>", False),
        (b"<!-- <mujoco> -->\n<robot/>", False),
        (b"\xef\xbb\xbf<mujoco/>", True),
    ],
)
def test_mjcf_is_known_by_its_root(text, expected):
    assert is_mjcf(text) is expected


@pytest.mark.parametrize("compiler", ["", '<compiler angle="radian" eulerseq="zyx"/>'])
def test_replicate_copies_are_mujocos_names_order_and_poses(tmp_path, compiler):
    angle = "0 0 1.2" if compiler else "0 10 30"
    path = write(
        tmp_path,
        "m.xml",
        f"<mujoco>{compiler}<worldbody><body name='base' pos='0.1 0 0'>"
        f'<replicate count="2" offset="1 0 0" euler="{angle}">'
        f'<replicate count="11" offset="0 0.2 0" euler="{angle}" sep="-">'
        '<body name="b" pos="0 0 1"><joint axis="0 0 1"/>'
        '<inertial pos="0.1 0 0" mass="1" diaginertia="1 1 1"/></body>'
        "</replicate></replicate></body></worldbody></mujoco>",
    )
    robot, mjmodel = both(path)
    names = [mjmodel.body(i).name for i in range(mjmodel.nbody)]
    assert [link.name for link in robot.links] == names and names[2:4] == ["b-000", "b-010"]
    for name in names[1:]:
        np.testing.assert_allclose(pose_of(robot, name), mujoco_pose(mjmodel, name), atol=1e-12)
    # every copy's <inertial> is the one element written once
    sources = {robot.link(name).inertial.source for name in names[2:]}
    assert len(sources) == 1


def test_a_replicate_that_is_no_count_is_refused_where_it_is(tmp_path):
    path = write(
        tmp_path, "m.xml", '<mujoco><worldbody>\n<replicate count="two"/></worldbody></mujoco>'
    )
    with pytest.raises(InputError, match="not a positive whole number") as raised:
        load_mjcf(path)
    assert raised.value.line == 2


@pytest.mark.parametrize("kind", ["capsule", "cylinder", "box", "ellipsoid", "sphere"])
@pytest.mark.parametrize("extra", ["", ' fitscale="1.5"', ' pos="0.1 0 0" euler="10 20 30"'])
def test_a_primitive_fitted_to_a_mesh_is_mujocos(tmp_path, kind, extra):
    import trimesh

    part = trimesh.creation.box((0.3, 0.1, 0.05))
    part.apply_transform(trimesh.transformations.rotation_matrix(0.4, [0, 0, 1]))
    part.apply_translation((0.1, 0.2, 0))
    part.export(tmp_path / "part.stl")
    path = write(
        tmp_path,
        "m.xml",
        '<mujoco><asset><mesh file="part.stl" scale="1 2 1"/></asset><worldbody>'
        f'<body name="b"><joint/><geom type="{kind}" mesh="part"{extra}/></body>'
        "</worldbody></mujoco>",
    )
    robot, mjmodel = both(path)
    (shape,) = robot.link("b").collisions
    assert not isinstance(shape.geometry, model.Unknown)
    mass, com, moments = body_mass_properties(mjmodel, 1)
    unit = analyse(robot).by_name["b"].geometry.unit
    ours = unit.with_mass(unit.mass * 1000.0)
    assert ours.mass == pytest.approx(mass, rel=1e-9)
    np.testing.assert_allclose(ours.com, com, atol=1e-12)
    np.testing.assert_allclose(ours.principal_moments, moments, rtol=1e-9)


def test_a_model_that_attaches_itself_is_refused_where_it_does(tmp_path):
    # MuJoCo 4.0.0 itself crashes on it (a segmentation fault)
    path = write(
        tmp_path,
        "m.xml",
        '<mujoco><asset><model name="m" file="m.xml"/></asset><worldbody><body name="b">\n'
        '<attach model="m" body="b" prefix="x"/></body></worldbody></mujoco>',
    )
    with pytest.raises(InputError, match="attaches itself") as raised:
        load_mjcf(path)
    assert raised.value.line == 2


def test_a_fromto_of_zero_length_is_refused_as_mujoco_refuses_it(tmp_path):
    path = write(
        tmp_path,
        "m.xml",
        '<mujoco><worldbody><body name="b"><joint/>\n'
        '<geom type="capsule" fromto="1 2 3 1 2 3" size="0.1"/></body></worldbody></mujoco>',
    )
    with pytest.raises(ValueError, match="fromto points too close"):
        mujoco.MjModel.from_xml_path(str(path))
    with pytest.raises(InputError, match="fromto points too close") as raised:
        load_mjcf(path)
    assert raised.value.line == 2


def test_a_mesh_refquat_of_zero_length_is_refused_at_the_mesh(tmp_path):
    path = write(
        tmp_path,
        "m.xml",
        '<mujoco><asset>\n<mesh file="b.stl" refquat="0 0 0 0"/></asset><worldbody>'
        '<body name="b"><joint/><geom type="mesh" mesh="b"/></body></worldbody></mujoco>',
    )
    with pytest.raises(InputError, match=r"refquat.*zero length") as raised:
        load_mjcf(path)
    assert raised.value.line == 2
