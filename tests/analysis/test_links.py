"""analysis.links: a link's bases and envelope, and the robot's fixed-joint groups."""

from __future__ import annotations

import pytest


def test_link_bases_envelope_and_missing_meshes(analysed):
    analysis = analysed(
        """<link name="a">
          <visual><geometry><box size="1 1 1"/></geometry></visual>
          <collision><geometry><sphere radius="0.1"/></geometry></collision>
        </link>
        <link name="b">
          <visual><geometry><mesh filename="missing.stl"/></geometry></visual>
          <collision><geometry><sphere radius="0.1"/></geometry></collision>
        </link>""",
    )
    a, b = analysis.links
    assert [g.kind for g in a.bases] == ["collision", "visual"]
    assert a.envelope is not None
    assert a.envelope.support([[1.0, 0.0, 0.0]])[0] == pytest.approx(0.5)
    assert [g.kind for g in b.bases] == ["collision"]
    assert b.envelope is None  # a partial envelope would understate what is possible


def test_mass_share_of_a_fixed_joint_group(analysed):
    analysis = analysed(
        """<link name="base"/>
        <link name="arm"><inertial><mass value="3"/>
          <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
        <link name="tool"><inertial><mass value="1"/>
          <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>""",
        """<joint name="j" type="continuous"><parent link="base"/><child link="arm"/></joint>
        <joint name="f" type="fixed"><parent link="arm"/><child link="tool"/></joint>""",
    )
    assert analysis.by_name["arm"].mass_share == pytest.approx(0.75)
    assert analysis.by_name["tool"].mass_share == pytest.approx(0.25)
    assert analysis.by_name["base"].mass_share == 1.0
