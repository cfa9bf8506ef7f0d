"""IN072 drake-verdict: edge cases beyond the document's examples."""

from __future__ import annotations

import pytest
from kit.urdf import LIMIT, inertial, robot

from inertia_kit.engines.drake import plausible_sphere

BOX = inertial(1, 0.01)


def run(lint, body):
    return lint(robot(body), select="IN072", engines=("drake",))


def test_loads_unchanged_gives_nothing(lint):
    body = f"""<link name="a">{BOX}</link>
      <joint name="j" type="revolute"><parent link="a"/><child link="b"/>{LIMIT}</joint>
      <link name="b">{BOX}<collision><geometry><mesh filename="b.obj"/></geometry></collision>
      </link>"""
    assert run(lint, body) == []


def test_invalid_tensor_replaced_by_sphere(lint):
    body = """<link name="a"><inertial><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0"
      iyy="0.01" iyz="0" izz="0.05"/></inertial></link>"""
    (finding,) = run(lint, body)
    assert "While parsing inertia matrix" in finding.message
    assert finding.expected["radius"] == pytest.approx(plausible_sphere(2.0)[1])


def test_massless_moving_link_with_mass_outboard_is_not_flagged(lint):
    body = f"""<link name="a">{BOX}</link>
      <joint name="j" type="revolute"><parent link="a"/><child link="b"/>{LIMIT}</joint>
      <link name="b"/>
      <joint name="k" type="revolute"><parent link="b"/><child link="c"/>{LIMIT}</joint>
      <link name="c">{BOX}</link>"""
    assert run(lint, body) == []


def test_massless_moving_leaf_fails(lint):
    body = f"""<link name="a">{BOX}</link>
      <joint name="j" type="prismatic"><parent link="a"/><child link="b"/>{LIMIT}</joint>
      <link name="b"/>"""
    (finding,) = run(lint, body)
    assert finding.severity.name == "ERROR" and "singular articulated body" in finding.message


def test_stl_collision_refused(lint):
    body = f"""<link name="a">{BOX}<visual><geometry><mesh filename="a.stl"/></geometry></visual>
      <collision><geometry><mesh filename="a.STL"/></geometry></collision></link>"""
    found = [f for f in run(lint, body) if f.code == "IN072"]
    assert len(found) == 1 and "expect an Obj file" in found[0].message
