"""analysis.links: a link's bases and envelope, and the robot's fixed-joint groups."""

from __future__ import annotations

import numpy as np
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


def _mesh_link(visual_scale: str, inertia: str) -> str:
    return f"""<link name="m">
      <inertial><origin xyz="0.1 0.2 0.3"/><mass value="2"/><inertia {inertia}/></inertial>
      <visual><geometry><mesh filename="part.stl" scale="{visual_scale}"/></geometry></visual>
      <collision><geometry><mesh filename="part.stl"/></geometry></collision>
    </link>"""


# the 2 kg box's tensor about the link origin, 0.1, 0.2, 0.3 m from its centre: IN060's slip
ABOUT_ORIGIN = 'ixx="0.2816667" iyy="0.2333333" izz="0.1416667" ixy="-0.04" ixz="-0.06" iyz="-0.12"'


@pytest.mark.parametrize("inertia", [ABOUT_ORIGIN, 'ixx="1" iyy="1" izz="1"'])
def test_a_visual_of_the_collision_mesh_is_judged_once(analysed, tmp_path, monkeypatch, inertia):
    """Visual and collision naming one mesh hold the same solids: the forensics and the
    envelope judge them once, with what judging both gives."""
    from kit.meshes import box_triangles, write_binary_stl

    from inertia_kit.analysis.forensics import links as forensics
    from inertia_kit.analysis.geometry import Geometry

    write_binary_stl(tmp_path / "part.stl", box_triangles((0.4, 0.3, 0.2), (-0.1, 0.05, 0.2)))
    (same,) = analysed(_mesh_link("1 1 1", inertia)).links
    (scaled,) = analysed(_mesh_link("1 1 1.5", inertia)).links
    assert same.visual.same_solids(same.collision)
    assert not scaled.visual.same_solids(scaled.collision)
    assert not Geometry("collision", (), None).same_solids(Geometry("visual", (), None))

    diagnosed = []
    original = forensics._diagnose_basis
    monkeypatch.setattr(
        forensics,
        "_diagnose_basis",
        lambda link, basis, mode: diagnosed.append(basis.kind) or original(link, basis, mode),
    )
    once = forensics.diagnose_link(same)
    assert "visual" not in diagnosed
    envelope = same.envelope
    monkeypatch.setattr(Geometry, "same_solids", lambda self, other: False)
    (both,) = analysed(_mesh_link("1 1 1", inertia)).links
    again = forensics.diagnose_link(both)
    assert (once is None) == (again is None) == (inertia != ABOUT_ORIGIN)
    if once is not None:
        assert (once.code, once.wording, once.basis) == (again.code, again.wording, again.basis)
        assert once.plain_residual == again.plain_residual
        for field in ("mass", "com", "inertia"):
            assert np.array_equal(getattr(once.corrected, field), getattr(again.corrected, field))
    directions = [[1.0, 0.0, 0.0], [0.3, -0.5, 0.8], [0.0, 0.0, -1.0]]
    assert (envelope.support(directions) == both.envelope.support(directions)).all()
