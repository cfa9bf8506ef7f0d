"""
The rules' MJCF meanings (issue 22, item 3): the geometry a body is judged against is what
MuJoCo would weigh (its counted geoms added up, each mesh in its inertia mode), an open mesh
matters only where MuJoCo weighs it, and a tensor far below its geometry's or an isotropic
placeholder far off it is an error, saying what MuJoCo's balanceinertia has to do with it.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import trimesh
from kit.meshes import box_triangles, write_binary_stl
from kit.mjcf import body_mass_properties

from inertia_kit.analysis.links import analyse
from inertia_kit.description.mjcf.reader import load_mjcf
from inertia_kit.lint.findings import Severity
from inertia_kit.lint.runner import Selection, lint_robot

mujoco = pytest.importorskip("mujoco")


def write_model(tmp_path, body: str, *, asset: str = "", welded: bool = False):
    joint = "" if welded else '<joint type="hinge"/>'
    path = tmp_path / "m.xml"
    path.write_text(
        f"<mujoco><asset>{asset}</asset><worldbody>"
        f'<body name="b" pos="0.1 0 0" euler="0 0 20">{joint}{body}</body>'
        "</worldbody></mujoco>"
    )
    return path


def findings(path, code: str):
    return [f for f in lint_robot(load_mjcf(path), Selection((code,))) if f.code == code]


def l_shape(tmp_path):
    bar = trimesh.creation.box((0.3, 0.1, 0.1))
    bar.apply_translation((0.1, 0, 0))
    other = trimesh.creation.box((0.1, 0.3, 0.1))
    other.apply_translation((0, 0.1, 0))
    trimesh.boolean.union([bar, other], engine="manifold").export(tmp_path / "l.stl")
    return '<mesh file="l.stl"/>'


def open_box(tmp_path):
    triangles = box_triangles((0.2, 0.1, 0.05), low=(-0.1, -0.05, -0.025))[:-2]  # a face gone
    write_binary_stl(tmp_path / "open.stl", triangles)
    return '<mesh file="open.stl"/>'


@pytest.mark.parametrize(
    ("geoms", "asset"),
    [
        # overlapping primitives: MuJoCo adds them, the overlap counted twice
        (
            '<geom type="box" size="0.1 0.1 0.1"/><geom type="sphere" size="0.08" pos="0.1 0 0"/>',
            "",
        ),
        # a non-convex mesh in MuJoCo's default legacy mode, over-counted
        ('<geom type="mesh" mesh="l"/>', "l"),
        ('<geom type="mesh" mesh="l" pos="0 0.2 0" euler="0 30 0"/>', "l"),
    ],
)
def test_the_geometry_of_an_mjcf_body_is_what_mujoco_weighs(tmp_path, geoms, asset):
    path = write_model(tmp_path, geoms, asset=l_shape(tmp_path) if asset else "")
    unit = analyse(load_mjcf(path)).by_name["b"].geometry.unit
    mass, com, moments = body_mass_properties(mujoco.MjModel.from_xml_path(str(path)), 1)
    ours = unit.with_mass(unit.mass * 1000.0)  # MuJoCo's default density
    assert ours.mass == pytest.approx(mass, rel=1e-9)
    np.testing.assert_allclose(ours.com, com, rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(ours.principal_moments, moments, rtol=1e-9)


def test_an_open_mesh_matters_where_mujoco_weighs_it(tmp_path):
    asset = open_box(tmp_path)
    inferred = write_model(tmp_path, '<geom type="mesh" mesh="open"/>', asset=asset)
    (finding,) = findings(inferred, "IN032")
    assert finding.message.startswith("body `b`: counted mesh `open.stl` is open: MuJoCo weighs")
    assert "legacy" in finding.detail and 'inertia="convex"' in finding.help
    mujoco.MjModel.from_xml_path(str(inferred))  # MuJoCo compiles it, weighing what it has

    written = '<inertial pos="0 0 0" mass="1" diaginertia="0.001 0.004 0.004"/>'
    explicit = write_model(tmp_path, written + '<geom type="mesh" mesh="open"/>', asset=asset)
    static = write_model(tmp_path, '<geom type="mesh" mesh="open"/>', asset=asset, welded=True)
    convex = asset.replace("/>", ' inertia="convex"/>')
    hull = write_model(tmp_path, '<geom type="mesh" mesh="open"/>', asset=convex)
    for path in (explicit, static, hull):
        assert findings(path, "IN032") == []


def test_a_moment_a_hundred_times_below_its_geometrys_is_an_error(tmp_path):
    box = '<geom type="box" size="0.2 0.1 0.05"/>'
    # the box's moments for 60 kg: 0.25, 0.85, 1.0 kg·m²
    tiny = write_model(
        tmp_path, box + '<inertial pos="0 0 0" mass="60" diaginertia="0.002 0.85 1"/>'
    )
    (finding,) = findings(tiny, "IN020")
    assert finding.severity is Severity.ERROR and "no real part's moment" in finding.detail
    small = write_model(
        tmp_path, box + '<inertial pos="0 0 0" mass="60" diaginertia="0.02 0.85 1"/>'
    )
    (finding,) = findings(small, "IN020")
    assert finding.severity is Severity.WARNING


def test_an_isotropic_placeholder_far_off_is_an_error_and_may_be_balanceinertias(tmp_path):
    box = '<geom type="box" size="0.2 0.1 0.05"/>'
    body = box + '<inertial pos="0 0 0" mass="60" diaginertia="0.001 0.001 0.001"/>'
    (finding,) = findings(write_model(tmp_path, body), "IN013")
    assert finding.severity is Severity.ERROR
    assert "balanceinertia" in finding.detail and "times off about one axis" in finding.detail
    near = box + '<inertial pos="0 0 0" mass="60" diaginertia="0.5 0.5 0.5"/>'
    (finding,) = findings(write_model(tmp_path, near), "IN013")
    assert finding.severity is Severity.WARNING and "times off" not in finding.detail


def test_a_centre_of_mass_a_slip_puts_back_inside_but_far_out_says_so(tmp_path):
    # a 0.4 × 0.1 × 0.1 m bar along x; the COM at z = 0.2 is outside, read with x and z
    # exchanged it is at x = 0.2, inside (the bar's end), but beyond where real parts put it
    body = (
        '<geom type="box" size="0.2 0.05 0.05"/>'
        '<inertial pos="0 0 0.15" mass="1" diaginertia="0.0008 0.0135 0.0135"/>'
    )
    (finding,) = findings(write_model(tmp_path, body), "IN021")
    assert finding.severity is Severity.ERROR
    assert "with x and z exchanged (75% to the edge) it would lie inside" in finding.detail


def test_a_massless_body_welded_to_the_world_is_quiet(tmp_path):
    # MuJoCo accepts a fixed mount with mass="0" and a zero tensor as written
    path = tmp_path / "m.xml"
    path.write_text(
        '<mujoco><worldbody><body name="table">'
        '<inertial pos="0 0 0" mass="0" diaginertia="0 0 0"/><geom type="box" size="0.5 0.5 0.02"/>'
        '<body name="arm" pos="0 0 0.1"><joint axis="0 0 1"/>'
        '<inertial pos="0 0 0" mass="1" diaginertia="0.004 0.004 0.0002"/>'
        '<geom type="capsule" size="0.02 0.1"/></body></body></worldbody></mujoco>'
    )
    mujoco.MjModel.from_xml_path(str(path))
    everything = Selection(("IN",), engines=("mujoco",))
    assert [f for f in lint_robot(load_mjcf(path), everything) if f.link == "table"] == []


MUSCLE = (
    '<tendon><spatial name="t"><site site="a"/><site site="b"/></spatial></tendon>'
    '<actuator><muscle name="m" tendon="t"/></actuator>'
)


def skeleton_model(tmp_path, actuators: str):
    """A forearm whose shape is its bone: 1.2 kg of flesh around a 2 cm rod, MyoSuite-like."""
    path = tmp_path / "m.xml"
    path.write_text(
        '<mujoco><worldbody><body name="humerus"><site name="a"/>'
        '<geom type="capsule" size="0.01 0.1"/>'
        '<inertial pos="0 0 0" mass="2" diaginertia="0.012 0.012 0.002"/>'
        '<body name="forearm" pos="0 0 -0.25"><joint name="elbow" axis="0 1 0"/>'
        '<site name="b" pos="0.03 0 -0.05"/>'
        '<geom type="capsule" size="0.008 0.1"/>'
        '<inertial pos="0 0 -0.08" mass="1.2" diaginertia="0.007 0.007 0.0012"/>'
        f"</body></body></worldbody>{actuators}</mujoco>"
    )
    mujoco.MjModel.from_xml_path(str(path))
    return path


def test_a_musculoskeletal_models_bones_are_not_its_bodies_envelopes(tmp_path):
    everything = Selection(("IN",), engines=("mujoco",))
    robot = load_mjcf(skeleton_model(tmp_path, MUSCLE))
    assert robot.skeleton and lint_robot(robot, everything) == []
    # the same bodies with a motor, not muscles: judged against their shapes
    bare = load_mjcf(
        skeleton_model(
            tmp_path, '<actuator><motor joint="j"/></actuator>'.replace(' joint="j"', ' site="b"')
        )
    )
    codes = {f.code for f in lint_robot(bare, everything)}
    assert not bare.skeleton and {"IN022", "IN023"} & codes


def test_balanceinertia_makes_an_impossible_tensor_a_warning(tmp_path):
    body = '<inertial pos="0 0 0" mass="1" diaginertia="0.001 0.001 0.004"/><geom size="0.05"/>'
    (refused,) = findings(write_model(tmp_path, body), "IN011")
    assert refused.severity is Severity.ERROR and "MuJoCo refuses it" in refused.detail
    balanced = tmp_path / "b.xml"
    balanced.write_text(
        write_model(tmp_path, body)
        .read_text()
        .replace("<mujoco>", '<mujoco><compiler balanceinertia="true"/>')
    )
    (loaded,) = findings(balanced, "IN011")
    assert loaded.severity is Severity.WARNING and "0.002 kg·m², their mean" in loaded.detail


def test_a_static_bodys_unreadable_mesh_is_not_told(tmp_path):
    (tmp_path / "logo.msh").write_bytes(b"\x00" * 64)
    static = write_model(
        tmp_path, '<geom type="mesh" mesh="logo"/>', asset='<mesh file="logo.msh"/>', welded=True
    )
    assert findings(static, "IN034") == []


ALOHA = Path("/work/ext/menagerie/aloha/aloha.xml")  # the snapshot with meshes (SOURCE.md)


@pytest.mark.slow
@pytest.mark.skipif(not ALOHA.is_file(), reason="the Menagerie snapshot with meshes is absent")
def test_contact_spheres_do_not_outvote_a_parts_mesh_on_its_unit():
    # ALOHA's fingers: a 10 cm finger mesh in metres with three 0.6 mm contact spheres on its
    # pad, which (three votes against size and density) called it inches before
    assert findings(ALOHA, "IN031") == []
