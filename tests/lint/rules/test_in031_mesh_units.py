"""IN031 mesh-units: meshes whose size says mm, cm or inches, and the scale that fixes them."""

from __future__ import annotations

import pytest
from kit.meshes import write_box_stl
from kit.urdf import box, collision, inertial, joint, link, mesh, robot, visual

from inertia_kit.lint.findings import Severity


def arm(body: str, offset: float = 0.3) -> str:
    """A moving link `arm` holding ``body``, with a child joint ``offset`` m away."""
    return robot(
        link("base"),
        joint("base", "arm", name="shoulder"),
        link("arm", body),
        joint("arm", "forearm", name="elbow", xyz=f"{offset} 0 0"),
        link("forearm"),
    )


def lone(body: str) -> str:
    return robot(link("thing", body))


def mounted(body: str) -> str:
    """A massless link welded to a massless base, with no joint offset."""
    return robot(link("base"), joint("base", "pad", "fixed", name="mount"), link("pad", body))


def test_millimetre_mesh_is_found_with_the_exact_scale(lint, tmp_path):
    write_box_stl(tmp_path / "arm.stl", (300, 50, 50))  # a 0.3 m arm exported in mm
    body = visual(mesh("arm.stl")) + collision(mesh("arm.stl")) + inertial(2.0, 0.001)
    findings = lint(arm(body), "IN031")
    assert len(findings) == 2
    for finding in findings:
        assert finding.severity == Severity.WARNING and finding.link == "arm"
        assert finding.message.endswith("mesh `arm.stl` spans 300 m, as if in mm")
        assert len(finding.message) <= 100
        assert "spans 300 m with no scale, as if millimetres were read as metres" in (
            finding.detail
        )
        assert "the link's longest joint offset is 0.3 m" in finding.detail
        assert 'with scale="0.001 0.001 0.001" it spans 0.3 m' in finding.detail
        assert (
            finding.help
            == 'set <mesh ... scale="0.001 0.001 0.001"/>, or re-export the mesh in metres'
        )
        assert finding.expected["scale"] == pytest.approx([0.001] * 3)
        assert finding.expected["factor"] == 0.001
    in_collision = next(f for f in findings if f.expected["kind"] == "collision")
    # the density settles it: mm, not cm
    assert "2 kg in it is 2.667e-06 kg/m³" in in_collision.detail
    assert "would fit too" not in in_collision.detail
    assert "and 2 kg in it is 2667 kg/m³" in in_collision.detail


def test_right_scale_is_quiet(lint, tmp_path):
    write_box_stl(tmp_path / "arm.stl", (300, 50, 50))
    body = (
        visual(mesh("arm.stl", scale="0.001 0.001 0.001"))
        + collision(mesh("arm.stl", scale="0.001 0.001 0.001"))
        + inertial(2.0, 0.001)
    )
    assert lint(arm(body), "IN031") == []


def test_millimetre_scale_on_a_metre_mesh(lint, tmp_path):
    write_box_stl(tmp_path / "arm.stl", (0.3, 0.05, 0.05))
    body = collision(mesh("arm.stl", scale="0.001 0.001 0.001")) + inertial(2.0, 0.001)
    findings = lint(arm(body), "IN031")
    assert len(findings) == 1
    assert findings[0].message == (
        "link `arm`: collision mesh `arm.stl` spans 0.0003 m at scale 0.001, as if already in "
        "metres"
    )
    assert "as if a millimetre scale were put on a mesh already in metres" in findings[0].detail
    assert findings[0].expected["scale"] == pytest.approx([1.0, 1.0, 1.0])


def test_non_uniform_scale_keeps_its_shape(lint, tmp_path):
    write_box_stl(tmp_path / "arm.stl", (150, 50, 50))
    body = collision(mesh("arm.stl", scale="2 1 1")) + inertial(2.0, 0.001)
    (finding,) = lint(arm(body), "IN031")
    assert finding.expected["scale"] == pytest.approx([0.002, 0.001, 0.001])
    assert "spans 300 m at its scale, as if in mm" in finding.message
    assert 'scale="0.002 0.001 0.001"' in finding.detail


def test_genuinely_large_part_is_quiet(lint, tmp_path):
    write_box_stl(tmp_path / "boom.stl", (4.0, 0.3, 0.3))  # an excavator boom, 400 kg
    body = visual(mesh("boom.stl")) + collision(mesh("boom.stl")) + inertial(400.0, 0.001)
    assert lint(arm(body, offset=4.0), "IN031") == []


def test_genuinely_tiny_part_is_quiet(lint, tmp_path):
    write_box_stl(tmp_path / "screw.stl", (0.003, 0.003, 0.003))
    body = collision(mesh("screw.stl")) + inertial(0.0002, 0.001)
    assert lint(arm(body, offset=0.005), "IN031") == []


def test_lone_massless_scene_is_quiet(lint, tmp_path):
    write_box_stl(tmp_path / "monastery.stl", (120.0, 80.0, 30.0))
    body = visual(mesh("monastery.stl")) + collision(mesh("monastery.stl"))
    assert lint(lone(body), "IN031") == []


def test_visual_in_mm_next_to_a_collision_primitive(lint, tmp_path):
    write_box_stl(tmp_path / "arm_mm.stl", (300, 50, 50))
    body = (
        visual(mesh("arm_mm.stl"))
        + collision(box(0.3, 0.05, 0.05), xyz="0.15 0 0")
        + inertial(2.0, 0.001)
    )
    findings = lint(arm(body), "IN031")
    assert len(findings) == 1 and findings[0].expected["kind"] == "visual"
    assert "its collision box (0.3 × 0.05 × 0.05 m) spans 0.3 m" in findings[0].detail


def test_visual_in_mm_told_apart_by_a_collision_mesh_in_metres(lint, tmp_path):
    write_box_stl(tmp_path / "pad_mm.stl", (20, 20, 5))
    write_box_stl(tmp_path / "pad.stl", (0.02, 0.02, 0.005))
    # the collision mesh passes on its size and density (1000 kg/m³), so it vouches against
    # the visual one, which on its own is only too large (20 m): one observation
    body = visual(mesh("pad_mm.stl")) + collision(mesh("pad.stl")) + inertial(0.002, 0.001)
    findings = lint(mounted(body), "IN031")
    assert len(findings) == 1 and findings[0].expected["kind"] == "visual"
    assert "its collision mesh `pad.stl` spans 0.02 m" in findings[0].detail


def test_a_mesh_that_passes_on_size_alone_vouches_for_nothing(lint, tmp_path):
    # a tiny visual mesh (2.8 mm, its scale wrong) next to a sound collision mesh whose
    # placeholder mass gives an odd density: neither is blamed on the other's word
    write_box_stl(tmp_path / "teddy.stl", (2.8, 2.0, 2.0))
    body = (
        visual(mesh("teddy.stl", scale="0.001 0.001 0.001")) + collision(mesh("teddy.stl"))
    ) + inertial(0.1, 0.001)
    findings = lint(lone(body), "IN031")
    assert all(f.expected["kind"] == "visual" for f in findings)


def test_min_evidence_option(lint, tmp_path):
    write_box_stl(tmp_path / "pad_mm.stl", (20, 20, 5))
    text = mounted(visual(mesh("pad_mm.stl")))
    findings = lint(text, "IN031", options={"IN031": {"min_evidence": 1}})
    assert len(findings) == 1 and findings[0].expected["factor"] == 0.001


def test_size_options(lint, tmp_path):
    write_box_stl(tmp_path / "arm.stl", (300, 50, 50))
    text = arm(visual(mesh("arm.stl")), offset=0.3)  # size and joints against it
    assert len(lint(text, "IN031")) == 1
    assert lint(text, "IN031", options={"IN031": {"max_size": 1000.0}}) == []
    write_box_stl(tmp_path / "tiny.stl", (0.3, 0.05, 0.05))
    text = arm(visual(mesh("tiny.stl", scale="0.001 0.001 0.001")))
    assert len(lint(text, "IN031")) == 1
    assert lint(text, "IN031", options={"IN031": {"min_size": 1e-5}}) == []


def test_density_options(lint, tmp_path):
    write_box_stl(tmp_path / "cube_mm.stl", (100, 100, 100))
    text = lone(collision(mesh("cube_mm.stl")) + inertial(0.5, 0.001))  # size and density
    assert len(lint(text, "IN031")) == 1
    assert lint(text, "IN031", options={"IN031": {"min_density": 1e-9}}) == []
    write_box_stl(tmp_path / "cube.stl", (0.1, 0.1, 0.1))
    text = lone(collision(mesh("cube.stl", scale="0.001 0.001 0.001")) + inertial(0.5, 0.001))
    assert len(lint(text, "IN031")) == 1
    assert lint(text, "IN031", options={"IN031": {"max_density": 1e13}}) == []


def test_primitives_and_missing_meshes_are_not_judged(lint):
    text = arm(collision(box(300, 50, 50)))
    assert lint(text, "IN031") == []
    assert lint(arm(collision(mesh("missing.stl"))), "IN031") == []


def test_ambiguous_units_name_the_alternatives(lint, tmp_path):
    write_box_stl(
        tmp_path / "arm_cm.stl", (30, 5, 5)
    )  # a 0.3 m arm in cm, without a mass to weigh it
    (finding,) = lint(arm(visual(mesh("arm_cm.stl"))), "IN031")
    assert finding.expected["factor"] == 0.01
    assert finding.expected["alternatives"]
    assert finding.message.endswith("spans 30 m, as if in cm, mm or inches")
    assert "would fit too" in finding.detail and "inches" in finding.detail


def test_the_same_file_at_the_same_scale_slips_together(lint, tmp_path):
    # only the collision mesh, where the mass comes from, has a density; the visual shape is
    # the same file at the same scale, so it is reported with it
    write_box_stl(tmp_path / "cube_mm.stl", (100, 100, 100))
    body = visual(mesh("cube_mm.stl")) + collision(mesh("cube_mm.stl")) + inertial(0.5, 0.001)
    findings = lint(lone(body), "IN031")
    assert sorted(f.expected["kind"] for f in findings) == ["collision", "visual"]
    assert all(f.expected["factor"] == 0.001 for f in findings)


def test_the_message_is_one_short_line_and_the_detail_keeps_the_basis(lint, tmp_path):
    """The mesh, its size and the unit it looks authored in in the message; the evidence, the
    scale that fits and the size and density it gives in the detail (the scale also in
    `expected` and the help)."""
    write_box_stl(tmp_path / "arm.stl", (300, 50, 50))
    body = collision(mesh("arm.stl")) + inertial(2.0, 0.001)
    (finding,) = lint(arm(body), "IN031")
    assert finding.message == "link `arm`: collision mesh `arm.stl` spans 300 m, as if in mm"
    assert len(finding.message) <= 100
    assert finding.detail.startswith(
        "collision mesh `arm.stl` spans 300 m with no scale, as if millimetres were read as "
        "metres: "
    )
    assert finding.detail.endswith(
        'with scale="0.001 0.001 0.001" it spans 0.3 m and 2 kg in it is 2667 kg/m³'
    )
