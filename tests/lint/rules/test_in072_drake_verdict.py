"""IN072 drake-verdict: edge cases beyond the document's examples (the real Drake judges them
all in ``tests/engines/test_drake_matrix.py``; these run without it)."""

from __future__ import annotations

import pytest
from kit import write
from kit.meshes import box_triangles, obj
from kit.urdf import LIMIT, inertial, robot

from inertia_kit.engines.drake import plausible_sphere

BOX = inertial(1, 0.01)


def run(lint, body):
    return lint(robot(body), select="IN072", engines=("drake",))


def turning(name: str, parent: str, child: str, axis: str) -> str:
    return (
        f'<joint name="{name}" type="revolute"><parent link="{parent}"/><child link="{child}"/>'
        f'<axis xyz="{axis}"/>{LIMIT}</joint>'
    )


def test_loads_unchanged_gives_nothing(lint, tmp_path):
    write(tmp_path / "b.obj", obj(box_triangles((0.1, 0.1, 0.1))))
    body = f"""<link name="a">{BOX}</link>{turning("j", "a", "b", "0 0 1")}
      <link name="b">{BOX}<collision><geometry><mesh filename="b.obj"/></geometry></collision>
      </link>"""
    assert run(lint, body) == []


def test_invalid_tensor_replaced_by_sphere(lint):
    body = """<link name="a"><inertial><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0"
      iyy="0.01" iyz="0" izz="0.05"/></inertial></link>"""
    (finding,) = run(lint, body)
    m, radius, moment = plausible_sphere(2.0)
    assert finding.message == (
        f"link `a`: Drake replaces its inertia: {m:g} kg water sphere, {moment:.4g} kg·m² per axis"
    )
    assert len(finding.message) <= 100
    assert f"radius {radius:.4g} m" in finding.detail
    assert "While parsing inertia matrix" in finding.detail
    assert "[0.01 0 0] [0 0.01 0] [0 0 0.05]" in finding.detail  # Drake's matrix, on one line
    assert "While parsing" not in finding.message
    assert finding.expected["radius"] == pytest.approx(plausible_sphere(2.0)[1])
    assert finding.line == 1  # the <inertial>, as Drake says


def test_massless_moving_link_with_mass_outboard_is_not_flagged(lint):
    body = f"""<link name="a">{BOX}</link>{turning("j", "a", "b", "0 0 1")}<link name="b"/>
      {turning("k", "b", "c", "1 0 0")}<link name="c">{BOX}</link>"""
    assert run(lint, body) == []


def test_massless_link_between_joints_about_one_axis_fails(lint):
    # c turns about z on its own joint: nothing is left to resist j's motion
    body = f"""<link name="a">{BOX}</link>{turning("j", "a", "b", "0 0 1")}<link name="b"/>
      {turning("k", "b", "c", "0 0 1")}<link name="c">{BOX}</link>"""
    (finding,) = run(lint, body)
    assert finding.link == "b" and finding.joint == "j"
    assert finding.message == (
        "link `b`: Drake fails at the first step: no inertia about its joint axis"
    )
    assert "connects body a to body b is not positive-definite" in finding.detail


def test_point_mass_on_the_axis_fails(lint):
    body = f"""<link name="a">{BOX}</link>{turning("j", "a", "b", "0 0 1")}
      <link name="b">{inertial(1, 0, xyz="0 0 0.3")}</link>"""
    (finding,) = run(lint, body)
    assert "has inertia about its axis" in finding.detail
    assert "Since the joint allows rotation, ensure body b" in finding.detail


def test_massless_moving_leaf_fails(lint):
    body = f"""<link name="a">{BOX}</link>
      <joint name="j" type="prismatic"><parent link="a"/><child link="b"/>{LIMIT}</joint>
      <link name="b"/>"""
    (finding,) = run(lint, body)
    assert finding.severity.name == "ERROR" and finding.expected["first"] is True
    assert finding.message.endswith("no mass along its joint axis")
    assert "has mass along its axis" in finding.detail
    assert "Since the joint allows translation, ensure body b" in finding.detail


def test_stl_collision_refused_visual_kept(lint, tmp_path):
    write(tmp_path / "a.stl", b"")
    write(tmp_path / "a.STL", b"")
    body = f"""<link name="a">{BOX}<visual><geometry><mesh filename="a.stl"/></geometry></visual>
      <collision><geometry><mesh filename="a.STL"/></geometry></collision></link>"""
    (finding,) = run(lint, body)
    assert finding.message == (
        "link `a`: Drake refuses the model: .stl collision mesh, not .obj/.vtk/.gltf"
    )
    assert "MakeConvexHull only applies to .obj, .vtk, and .gltf meshes" in finding.detail
    assert finding.expected["mesh"] == str(tmp_path / "a.STL")


def test_missing_package_mesh_refused_without_quoting(lint):
    body = f"""<link name="a">{BOX}<visual><geometry><mesh filename="package://nowhere/a.obj"/>
      </geometry></visual></link>"""
    (finding,) = run(lint, body)
    assert finding.expected["engine_message"] is None
    assert finding.message == "link `a`: Drake refuses the model: visual mesh `a.obj` not found"
    assert "package map" in finding.detail


def test_later_refusals_are_not_first(lint):
    body = f"""<link name="a"><inertial><mass value="abc"/></inertial></link>
      {turning("j", "a", "b", "0 0 0")}<link name="b">{BOX}</link>"""
    number, axis = run(lint, body)
    assert number.expected["first"] and not axis.expected["first"]
    assert number.message == (
        "link `a`: Drake refuses the model: a value in its <inertial> is not one number"
    )
    assert axis.message == "joint `j`: Drake refuses the model: zero axis"
    assert "Expected single value for attribute 'value' got 'abc'" in number.detail
    assert "Joint 'j' axis is zero.  Don't do that." in axis.detail


def test_floating_joint_is_left_out(lint):
    body = f"""<link name="a">{BOX}</link>
      <joint name="f" type="floating"><parent link="a"/><child link="b"/></joint>
      <link name="b">{BOX}</link>"""
    (finding,) = run(lint, body)
    assert finding.severity.name == "WARNING"
    assert finding.message == (
        "link `b`: Drake makes it a free body: its floating joint is left out"
    )
    assert "Leaving 'b' as a free body." in finding.detail
