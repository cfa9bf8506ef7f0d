"""build_scene on built robots and the seed examples: boxes, densities, findings per link."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import trimesh
from click.testing import CliRunner
from kit import EXAMPLES, write
from kit.meshes import torus_triangles, write_binary_stl
from kit.moments import solid_box
from kit.urdf import box, box_inertial, collision, inertial, joint, link, mesh, robot, visual

from inertia_kit.cli import lint_main
from inertia_kit.errors import ConfigError, InputError
from inertia_kit.view.scene import build_scene

PAN_TILT = EXAMPLES / "pan_tilt_description" / "urdf" / "pan_tilt.urdf"
MRM = EXAMPLES / "mrm_description" / "urdf" / "mrm.xacro"


def _scene(tmp_path, text, **options):
    scene = build_scene(write(tmp_path / "robot.urdf", text), **options)
    json.dumps(scene, allow_nan=False)  # JSON-ready, without NaN or infinities
    return scene


def _link(scene, name):
    return next(record for record in scene["links"] if record["name"] == name)


def _box_robot(mass, size, inertial_size=None):
    return robot(
        link("base"),
        joint("base", "arm", xyz=(0, 0, 0.5)),
        link(
            "arm",
            box_inertial(mass, inertial_size or size, xyz=(0.1, 0, 0)),
            visual(box(*size), xyz=(0.1, 0, 0)),
            collision(box(*size), xyz=(0.1, 0, 0)),
        ),
    )


def test_a_box_link_s_declared_and_geometry_boxes_are_the_box(tmp_path):
    size = (0.4, 0.2, 0.1)
    scene = _scene(tmp_path, _box_robot(2.0, size))
    arm = _link(scene, "arm")
    assert arm["parent"] == "base"
    assert arm["joint"]["name"] == "j_arm" and arm["joint"]["type"] == "revolute"
    assert arm["joint"]["axis"] == [0, 0, 1] and arm["joint"]["lower"] == -1.0
    np.testing.assert_allclose(np.reshape(arm["world"], (4, 4))[:3, 3], [0, 0, 0.5])
    for record in (arm["declared"], arm["geometry"]):
        assert record["mass"] == pytest.approx(2.0)
        np.testing.assert_allclose(record["com"], [0.1, 0, 0], atol=1e-12)
        np.testing.assert_allclose(record["box"], sorted(size, reverse=True), rtol=1e-9)
        assert record["problem"] is None
    volume = math.prod(size)
    assert arm["implied_density"] == pytest.approx(2.0 / volume)
    assert arm["geometry"]["density"] == pytest.approx(2.0 / volume)
    assert "collision box" in arm["geometry"]["basis"]
    assert "declared 2 kg" in arm["geometry"]["basis"]
    assert arm["shown"] == "visual" and arm["visuals"][0]["kind"] == "box"
    assert arm["findings"] == [] and arm["worst"] is None


def test_a_wrong_tensor_gives_its_own_box_and_its_findings(tmp_path):
    scene = _scene(tmp_path, _box_robot(2.0, (0.4, 0.2, 0.1), inertial_size=(0.8, 0.2, 0.1)))
    arm = _link(scene, "arm")
    np.testing.assert_allclose(arm["declared"]["box"], [0.8, 0.2, 0.1], rtol=1e-9)
    np.testing.assert_allclose(arm["geometry"]["box"], [0.4, 0.2, 0.1], rtol=1e-9)
    # IN020, or the forensics rule (IN06x) that explains the mismatch in its place
    assert {f["code"][:4] for f in arm["findings"]} & {"IN02", "IN06"}
    assert arm["worst"] in ("warning", "error")
    finding = arm["findings"][0]
    keys = {"code", "name", "severity", "message", "detail", "file", "line", "column"}
    assert set(finding) >= keys


def test_a_link_without_visuals_shows_its_collision_geometry(tmp_path):
    mass, *_ = solid_box((0.2, 0.2, 0.2), density=1000)
    text = robot(
        link("base"),
        joint("base", "arm"),
        link("arm", box_inertial(mass, (0.2, 0.2, 0.2)), collision(box(0.2, 0.2, 0.2))),
    )
    arm = _link(_scene(tmp_path, text), "arm")
    assert arm["shown"] == "collision"
    assert len(arm["visuals"]) == 1
    assert arm["implied_density"] == pytest.approx(1000)


def test_a_link_without_mass_has_the_geometry_at_the_default_density(tmp_path):
    text = robot(link("base"), joint("base", "arm"), link("arm", collision(box(0.1, 0.1, 0.1))))
    arm = _link(_scene(tmp_path, text), "arm")
    assert arm["declared"] is None and arm["implied_density"] is None
    assert arm["geometry"]["mass"] == pytest.approx(1.0)  # 1000 kg/m³ × 1 litre
    assert "no declared mass" in arm["geometry"]["basis"]
    assert "IN001" in {f["code"] for f in arm["findings"]}


def test_an_impossible_tensor_has_no_box_and_says_why(tmp_path):
    text = robot(
        link("base"),
        joint("base", "arm"),
        link("arm", inertial(1.0, 0.1, 0.1, 0.5), collision(box(0.1, 0.1, 0.1))),
    )
    declared = _link(_scene(tmp_path, text), "arm")["declared"]
    assert declared["box"] is None
    assert "triangle inequality" in declared["problem"]
    assert declared["moments"] == pytest.approx([0.1, 0.1, 0.5])


def test_a_missing_mesh_leaves_the_link_undrawn_and_its_finding_in_the_panel(tmp_path):
    text = robot(
        link("base"),
        joint("base", "arm"),
        link("arm", inertial(1.0, 0.01), visual(mesh("gone.stl")), collision(box(0.1, 0.1, 0.1))),
    )
    arm = _link(_scene(tmp_path, text), "arm")
    assert arm["shown"] == "visual" and arm["visuals"] == []
    assert "IN030" in {f["code"] for f in arm["findings"]}


def test_findings_about_no_one_link_are_elsewhere(tmp_path):
    ghost = '<joint name="j" type="fixed"><parent link="one"/><child link="ghost"/></joint>'
    scene = _scene(tmp_path, robot(link("one"), link("two"), ghost))
    # the joint naming no link is the robot's; the second root is link two's
    assert [f["code"] for f in scene["findings_elsewhere"]] == ["IN040"]
    assert "ghost" in scene["findings_elsewhere"][0]["message"]
    assert [f["code"] for f in _link(scene, "two")["findings"]] == ["IN040"]
    assert all(np.allclose(np.reshape(r["world"], (4, 4)), np.eye(4)) for r in scene["links"])


def test_unreadable_input_raises_the_error_lint_reports(tmp_path):
    path = write(tmp_path / "robot.urdf", '<robot name="r">\n  <link name="a">\n</robot>\n')
    with pytest.raises(InputError) as raised:
        build_scene(path)
    assert raised.value.path == str(path) and raised.value.line is not None


def test_a_fragment_or_a_folder_is_no_robot(tmp_path):
    with pytest.raises(InputError, match="fragment"):
        build_scene(EXAMPLES / "mrm_description" / "urdf" / "links_joints.xacro")
    with pytest.raises(InputError, match="folder"):
        build_scene(tmp_path)


def test_a_budget_below_one_triangle_is_a_configuration_error(tmp_path):
    with pytest.raises(ConfigError, match="triangle budget"):
        _scene(tmp_path, robot(link("a")), triangle_budget=0)


def test_select_and_ignore_are_lint_s(tmp_path):
    text = _box_robot(2.0, (0.4, 0.2, 0.1), inertial_size=(0.8, 0.2, 0.1))
    scene = _scene(tmp_path, text, ignore=["IN020"])
    assert "IN020" not in {f["code"] for f in _link(scene, "arm")["findings"]}


def test_pan_tilt_declared_and_geometry_boxes_coincide():
    scene = build_scene(PAN_TILT)
    compared = 0
    for record in scene["links"]:
        declared, geometry = record["declared"], record["geometry"]
        if declared is None:
            continue
        # its inertials are written with 5 to 6 significant digits: 1e-5 relative at most
        np.testing.assert_allclose(declared["box"], geometry["box"], rtol=1.5e-5)
        np.testing.assert_allclose(declared["com"], geometry["com"], atol=1e-6)
        compared += 1
    assert compared == 4


def test_mrm_boxes_differ_and_its_findings_are_on_their_links():
    scene = build_scene(MRM)
    for name in ("link_01", "link_02", "link_03", "link_04", "link_05"):
        record = _link(scene, name)
        declared, geometry = np.array(record["declared"]["box"]), record["geometry"]["box"]
        # its CAD tensors are about the link origin: the boxes are far apart
        assert np.abs(declared / geometry - 1).max() > 0.2, name
        assert "IN060" in {f["code"] for f in record["findings"]}
    # the same findings as the real command's, each on the link it names
    result = CliRunner().invoke(lint_main, ["--output-format", "json", str(MRM)])
    linted = {(f["code"], f["link"]) for f in json.loads(result.stdout)}
    drawn = {(f["code"], r["name"]) for r in scene["links"] for f in r["findings"]}
    drawn |= {(f["code"], None) for f in scene["findings_elsewhere"]}
    assert drawn == linted


def _big_robot(tmp_path, rings, sides):
    stl = write_binary_stl(tmp_path / "ring.stl", torus_triangles(0.2, 0.05, rings, sides))
    return robot(
        link("base"),
        joint("base", "ring"),
        link("ring", inertial(1.0, 0.01), visual(mesh(stl.name)), collision(mesh(stl.name))),
    )


def test_a_robot_over_the_budget_is_decimated_to_it(tmp_path):
    scene = _scene(tmp_path, _big_robot(tmp_path, 100, 50), triangle_budget=2000)
    (carried,) = scene["meshes"]
    assert carried["source_triangles"] == 10_000
    assert 1800 <= carried["triangles"] <= 2000
    assert scene["budget"] == {"triangles": carried["triangles"], "limit": 2000, "decimated": True}
    # the mass properties are the whole mesh's (its volume by trimesh), not the decimated one's
    whole = trimesh.Trimesh(**trimesh.triangles.to_kwargs(torus_triangles(0.2, 0.05, 100, 50)))
    ring = _link(scene, "ring")
    assert ring["implied_density"] == pytest.approx(1.0 / whole.volume, rel=1e-6)


@pytest.mark.slow
def test_a_million_triangles_fit_the_budget_and_the_page(tmp_path):
    scene = _scene(tmp_path, _big_robot(tmp_path, 1000, 500))
    (carried,) = scene["meshes"]
    assert carried["source_triangles"] == 1_000_000
    assert carried["triangles"] <= 300_000
    size = len(json.dumps(scene))
    # measured 7.2 MB at 300 000 triangles (base64 float32 positions, uint32 indices): the page
    # (under 10 MB) also carries three.js, about 0.7 MB
    assert size < 8_000_000, size
