"""IN031 mesh-units: meshes whose size says mm, cm or inches, and the scale that fixes them."""

from __future__ import annotations

import pytest
import trimesh

from inertia_kit.lint.findings import Severity

LIMIT = '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/>'


def box(path, extents):
    trimesh.creation.box(extents=extents).export(path)


def inertial(mass: float) -> str:
    # values are not judged by IN031; any valid tensor will do
    return (
        f'<inertial><mass value="{mass}"/>'
        '<inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>'
    )


def mesh(kind: str, name: str, scale: str | None = None) -> str:
    attribute = "" if scale is None else f' scale="{scale}"'
    return f'<{kind}><geometry><mesh filename="{name}"{attribute}/></geometry></{kind}>'


def arm(body: str, offset: float = 0.3) -> str:
    """A moving link with a child joint ``offset`` m away."""
    return f"""<robot name="r">
  <link name="base"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/>{LIMIT}</joint>
  <link name="arm">{body}</link>
  <joint name="elbow" type="revolute"><origin xyz="{offset} 0 0"/>
    <parent link="arm"/><child link="forearm"/>{LIMIT}</joint>
  <link name="forearm"/>
</robot>"""


def lone(body: str) -> str:
    return f'<robot name="r"><link name="thing">{body}</link></robot>'


def mounted(body: str) -> str:
    """A massless link welded to a massless base, with no joint offset."""
    return f"""<robot name="r">
  <link name="base"/>
  <joint name="mount" type="fixed"><parent link="base"/><child link="pad"/></joint>
  <link name="pad">{body}</link>
</robot>"""


def test_millimetre_mesh_is_found_with_the_exact_scale(lint, tmp_path):
    box(tmp_path / "arm.stl", (300, 50, 50))  # a 0.3 m arm exported in mm
    body = mesh("visual", "arm.stl") + mesh("collision", "arm.stl") + inertial(2.0)
    findings = lint(arm(body), "IN031")
    assert len(findings) == 2
    for finding in findings:
        assert finding.severity == Severity.WARNING and finding.link == "arm"
        assert "spans 300 m with no scale, as if millimetres were read as metres" in (
            finding.message
        )
        assert "the link's longest joint offset is 0.3 m" in finding.message
        assert 'with scale="0.001 0.001 0.001" it spans 0.3 m' in finding.message
        assert (
            finding.help
            == 'set <mesh ... scale="0.001 0.001 0.001"/>, or re-export the mesh in metres'
        )
        assert finding.expected["scale"] == pytest.approx([0.001] * 3)
        assert finding.expected["factor"] == 0.001
    collision = next(f for f in findings if f.expected["kind"] == "collision")
    # the density settles it: mm, not cm
    assert "2 kg in it is 2.667e-06 kg/m³" in collision.message
    assert "would fit too" not in collision.message
    assert "and 2 kg in it is 2667 kg/m³" in collision.message


def test_right_scale_is_quiet(lint, tmp_path):
    box(tmp_path / "arm.stl", (300, 50, 50))
    body = (
        mesh("visual", "arm.stl", "0.001 0.001 0.001")
        + mesh("collision", "arm.stl", "0.001 0.001 0.001")
        + inertial(2.0)
    )
    assert lint(arm(body), "IN031") == []


def test_millimetre_scale_on_a_metre_mesh(lint, tmp_path):
    box(tmp_path / "arm.stl", (0.3, 0.05, 0.05))
    body = mesh("collision", "arm.stl", "0.001 0.001 0.001") + inertial(2.0)
    findings = lint(arm(body), "IN031")
    assert len(findings) == 1
    assert "as if a millimetre scale were put on a mesh already in metres" in findings[0].message
    assert findings[0].expected["scale"] == pytest.approx([1.0, 1.0, 1.0])


def test_non_uniform_scale_keeps_its_shape(lint, tmp_path):
    box(tmp_path / "arm.stl", (150, 50, 50))
    body = mesh("collision", "arm.stl", "2 1 1") + inertial(2.0)
    (finding,) = lint(arm(body), "IN031")
    assert finding.expected["scale"] == pytest.approx([0.002, 0.001, 0.001])
    assert 'scale="0.002 0.001 0.001"' in finding.message


def test_genuinely_large_part_is_quiet(lint, tmp_path):
    box(tmp_path / "boom.stl", (4.0, 0.3, 0.3))  # an excavator boom, 400 kg
    body = mesh("visual", "boom.stl") + mesh("collision", "boom.stl") + inertial(400.0)
    assert lint(arm(body, offset=4.0), "IN031") == []


def test_genuinely_tiny_part_is_quiet(lint, tmp_path):
    box(tmp_path / "screw.stl", (0.003, 0.003, 0.003))
    body = mesh("collision", "screw.stl") + inertial(0.0002)
    assert lint(arm(body, offset=0.005), "IN031") == []


def test_lone_massless_scene_is_quiet(lint, tmp_path):
    box(tmp_path / "monastery.stl", (120.0, 80.0, 30.0))
    body = mesh("visual", "monastery.stl") + mesh("collision", "monastery.stl")
    assert lint(lone(body), "IN031") == []


def test_visual_in_mm_next_to_a_collision_primitive(lint, tmp_path):
    box(tmp_path / "arm_mm.stl", (300, 50, 50))
    body = (
        mesh("visual", "arm_mm.stl")
        + '<collision><origin xyz="0.15 0 0"/><geometry><box size="0.3 0.05 0.05"/></geometry>'
        "</collision>" + inertial(2.0)
    )
    findings = lint(arm(body), "IN031")
    assert len(findings) == 1 and findings[0].expected["kind"] == "visual"
    assert "its collision box (0.3 × 0.05 × 0.05 m) spans 0.3 m" in findings[0].message


def test_visual_in_mm_told_apart_by_a_collision_mesh_in_metres(lint, tmp_path):
    box(tmp_path / "pad_mm.stl", (20, 20, 5))
    box(tmp_path / "pad.stl", (0.02, 0.02, 0.005))
    # the collision mesh passes on its size and density (1000 kg/m³), so it vouches against
    # the visual one, which on its own is only too large (20 m): one observation
    body = mesh("visual", "pad_mm.stl") + mesh("collision", "pad.stl") + inertial(0.002)
    findings = lint(mounted(body), "IN031")
    assert len(findings) == 1 and findings[0].expected["kind"] == "visual"
    assert "its collision mesh `pad.stl` spans 0.02 m" in findings[0].message


def test_a_mesh_that_passes_on_size_alone_vouches_for_nothing(lint, tmp_path):
    # a tiny visual mesh (2.8 mm, its scale wrong) next to a sound collision mesh whose
    # placeholder mass gives an odd density: neither is blamed on the other's word
    box(tmp_path / "teddy.stl", (2.8, 2.0, 2.0))
    body = (
        mesh("visual", "teddy.stl", "0.001 0.001 0.001") + mesh("collision", "teddy.stl")
    ) + inertial(0.1)
    findings = lint(lone(body), "IN031")
    assert all(f.expected["kind"] == "visual" for f in findings)


def test_min_evidence_option(lint, tmp_path):
    box(tmp_path / "pad_mm.stl", (20, 20, 5))
    text = mounted(mesh("visual", "pad_mm.stl"))
    findings = lint(text, "IN031", options={"IN031": {"min_evidence": 1}})
    assert len(findings) == 1 and findings[0].expected["factor"] == 0.001


def test_size_options(lint, tmp_path):
    box(tmp_path / "arm.stl", (300, 50, 50))
    text = arm(mesh("visual", "arm.stl"), offset=0.3)  # size and joints against it
    assert len(lint(text, "IN031")) == 1
    assert lint(text, "IN031", options={"IN031": {"max_size": 1000.0}}) == []
    box(tmp_path / "tiny.stl", (0.3, 0.05, 0.05))
    text = arm(mesh("visual", "tiny.stl", "0.001 0.001 0.001"))
    assert len(lint(text, "IN031")) == 1
    assert lint(text, "IN031", options={"IN031": {"min_size": 1e-5}}) == []


def test_density_options(lint, tmp_path):
    box(tmp_path / "cube_mm.stl", (100, 100, 100))
    text = lone(mesh("collision", "cube_mm.stl") + inertial(0.5))  # size and density
    assert len(lint(text, "IN031")) == 1
    assert lint(text, "IN031", options={"IN031": {"min_density": 1e-9}}) == []
    box(tmp_path / "cube.stl", (0.1, 0.1, 0.1))
    text = lone(mesh("collision", "cube.stl", "0.001 0.001 0.001") + inertial(0.5))
    assert len(lint(text, "IN031")) == 1
    assert lint(text, "IN031", options={"IN031": {"max_density": 1e13}}) == []


def test_primitives_and_missing_meshes_are_not_judged(lint):
    text = arm('<collision><geometry><box size="300 50 50"/></geometry></collision>')
    assert lint(text, "IN031") == []
    assert lint(arm(mesh("collision", "missing.stl")), "IN031") == []


def test_ambiguous_units_name_the_alternatives(lint, tmp_path):
    box(tmp_path / "arm_cm.stl", (30, 5, 5))  # a 0.3 m arm in cm, without a mass to weigh it
    (finding,) = lint(arm(mesh("visual", "arm_cm.stl")), "IN031")
    assert finding.expected["factor"] == 0.01
    assert finding.expected["alternatives"]
    assert "would fit too" in finding.message and "inches" in finding.message


def test_the_same_file_at_the_same_scale_slips_together(lint, tmp_path):
    # only the collision mesh, where the mass comes from, has a density; the visual shape is
    # the same file at the same scale, so it is reported with it
    box(tmp_path / "cube_mm.stl", (100, 100, 100))
    body = mesh("visual", "cube_mm.stl") + mesh("collision", "cube_mm.stl") + inertial(0.5)
    findings = lint(lone(body), "IN031")
    assert sorted(f.expected["kind"] for f in findings) == ["collision", "visual"]
    assert all(f.expected["factor"] == 0.001 for f in findings)
