"""IN030 mesh-not-found: mesh URIs that do not resolve, with hints where the file is."""

from __future__ import annotations

import os

import pytest
from kit.meshes import write_box_stl

from inertia_kit.lint.findings import Severity
from inertia_kit.lint.runner import Selection, lint_file


@pytest.fixture(autouse=True)
def no_ros_environment(monkeypatch):
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)


CUBE = (0.1, 0.1, 0.1)


def robot(visual: str, collision: str | None = None) -> str:
    collision = visual if collision is None else collision
    return f"""<robot name="r">
  <link name="part">
    <visual><geometry><mesh filename="{visual}"/></geometry></visual>
    <collision><geometry><mesh filename="{collision}"/></geometry></collision>
  </link>
</robot>"""


def test_existing_mesh_is_quiet(lint, tmp_path):
    write_box_stl(tmp_path / "meshes" / "part.stl", CUBE)
    assert lint(robot("meshes/part.stl"), "IN030") == []


def test_missing_relative_path_names_the_shape_and_the_file(lint, tmp_path):
    findings = lint(robot("meshes/part.stl"), "IN030")
    assert [f.message.split(":")[0] for f in findings] == ["link `part`"] * 2
    kinds = sorted(f.message.split()[2] for f in findings)
    assert kinds == ["collision", "visual"]
    for finding in findings:
        assert finding.severity == Severity.ERROR and finding.link == "part"
        assert finding.message.endswith("mesh `meshes/part.stl` not found")
        assert "does not exist" in finding.detail
        assert finding.line in (3, 4)


def test_similar_name_in_the_folder_is_suggested(lint, tmp_path):
    write_box_stl(tmp_path / "meshes" / "bracket.stl", CUBE)
    findings = lint(robot("meshes/bracket_v2.stl"), "IN030")
    assert findings and all("did you mean" in f.help and "bracket.stl" in f.help for f in findings)


def test_name_differing_in_case(lint, tmp_path):
    write_box_stl(tmp_path / "meshes" / "Part.STL", CUBE)
    if (tmp_path / "meshes" / "part.stl").exists():
        pytest.skip("case-insensitive file system")
    findings = lint(robot("meshes/part.stl"), "IN030")
    assert findings and all("differs only in case" in f.help for f in findings)
    assert findings[0].expected["found"].endswith(os.path.join("meshes", "Part.STL"))


def test_unknown_package_says_to_pass_package_path(lint):
    findings = lint(robot("package://nowhere_description/meshes/part.stl"), "IN030")
    assert len(findings) == 2
    assert "package `nowhere_description` not found" in findings[0].detail
    assert findings[0].help.startswith("pass --package-path DIR")


def test_package_folder_next_to_the_file_resolves_as_pybullet_reads_it(tmp_path):
    # PyBullet strips package:// and looks next to the URDF
    write_box_stl(tmp_path / "my_robot" / "meshes" / "part.stl", CUBE)
    path = tmp_path / "robot.urdf"
    path.write_text(robot("package://my_robot/meshes/part.stl"))
    assert lint_file(path, Selection(select=("IN030",))).findings == []


def test_package_folder_beside_an_ancestor_is_found_with_package_path(tmp_path):
    write_box_stl(tmp_path / "my_robot" / "meshes" / "part.stl", CUBE)
    path = tmp_path / "urdf" / "robot.urdf"
    path.parent.mkdir()
    path.write_text(robot("package://my_robot/meshes/part.stl"))
    findings = lint_file(path, Selection(select=("IN030",))).findings
    assert len(findings) == 2
    assert f"pass --package-path {tmp_path}" in findings[0].help
    resolved = lint_file(path, Selection(select=("IN030",)), package_paths=[tmp_path])
    assert resolved.findings == []


def test_folder_named_after_the_package_elsewhere_with_another_package_xml(tmp_path):
    package = tmp_path / "example-robot-data"
    write_box_stl(package / "robots" / "meshes" / "part.stl", CUBE)
    (package / "package.xml").write_text(
        '<package format="3"><name>example_robot_descriptions</name></package>'
    )
    path = tmp_path / "other" / "robot.urdf"
    path.parent.mkdir()
    path.write_text(robot("package://example-robot-data/robots/meshes/part.stl"))
    findings = lint_file(path, Selection(select=("IN030",))).findings
    assert findings
    assert "package.xml names the package `example_robot_descriptions`" in findings[0].help


def test_the_detail_names_every_place_searched(tmp_path):
    (tmp_path / "pkgs").mkdir()
    path = tmp_path / "robot" / "urdf" / "robot.urdf"
    path.parent.mkdir(parents=True)
    path.write_text(robot("package://nowhere_description/meshes/part.stl", "meshes/part.stl"))
    result = lint_file(path, Selection(select=("IN030",)), package_paths=[tmp_path / "pkgs"])
    by_kind = {f.expected["kind"]: f for f in result.findings}
    visual, collision = by_kind["visual"], by_kind["collision"]
    searched = visual.expected["searched"]
    assert searched[:2] == [
        f"--package-path {tmp_path / 'pkgs'}: no `nowhere_description`",
        "ROS_PACKAGE_PATH: not set",
    ]
    assert searched[2].startswith("ament index: ")
    assert searched[3].startswith("enclosing package: no `nowhere_description` above ")
    stripped = os.path.join("nowhere_description", "meshes", "part.stl")
    assert searched[4] == f"next to the file: {path.parent / stripped}"
    assert f"search path (--package-path): {tmp_path / 'pkgs' / stripped}" in searched
    assert "; searched " + "; ".join(searched) in visual.detail
    assert visual.message == (
        "link `part`: visual mesh `package://nowhere_description/meshes/part.stl` not found"
    )
    assert visual.detail.startswith("`package://nowhere_description/meshes/part.stl`: package")
    # a relative path: next to the file, then the search path
    assert collision.expected["searched"][:2] == [
        f"next to the file: {path.parent / 'meshes' / 'part.stl'}",
        f"search path (--package-path): {tmp_path / 'pkgs' / 'meshes' / 'part.stl'}",
    ]


def test_the_path_after_the_package_name_in_the_folder_above(tmp_path):
    # rtb-data's irb140.urdf names abb_irb140_support, which it does not ship; the meshes are
    # in abb_irb140_description above the file
    package = tmp_path / "arm_description"
    write_box_stl(package / "meshes" / "base.stl", CUBE)
    path = package / "urdf" / "arm.urdf"
    path.parent.mkdir()
    path.write_text(robot("package://arm_support/meshes/base.stl"))
    findings = lint_file(path, Selection(select=("IN030",))).findings
    assert len(findings) == 2
    assert "package `arm_support` not found" in findings[0].detail
    assert (
        "write `package://arm_description/meshes/base.stl` if that is the file" in findings[0].help
    )
    assert findings[0].expected["found"] == str(package / "meshes" / "base.stl")


def test_a_file_of_that_name_near_where_the_uri_points(tmp_path):
    # robot_properties_fingers 2.0 names meshes/stl/..., which its wheel does not have
    package = tmp_path / "fingers"
    write_box_stl(package / "meshes" / "table.stl", CUBE)
    path = package / "urdf" / "stage.urdf"
    path.parent.mkdir()
    path.write_text(robot("package://fingers/meshes/stl/table.stl"))
    findings = lint_file(path, Selection(select=("IN030",))).findings
    assert len(findings) == 2
    assert f"{package / 'meshes' / 'stl' / 'table.stl'} does not exist" in findings[0].detail
    assert findings[0].help.startswith(f"`{package / 'meshes' / 'table.stl'}` exists, nearest to")


def test_the_message_is_one_short_line_with_a_long_uri_shortened(lint):
    """The URI's middle folders are elided in the message (rtb-data's KUKA names
    `package://kuka_lbr_iiwa_support/meshes/lbr_iiwa_14_r820/collision/base_link.stl`); the
    detail and `expected` keep it whole, with the reason and every place searched."""
    uri = "package://kuka_lbr_iiwa_support/meshes/lbr_iiwa_14_r820/collision/base_link.stl"
    findings = lint(robot(uri), "IN030")
    assert [f.message for f in findings] == [
        f"link `part`: {kind} mesh `package://kuka_lbr_iiwa_support/…/base_link.stl` not found"
        for kind in ("visual", "collision")
    ]
    assert all(len(f.message) <= 100 for f in findings)
    for finding in findings:
        assert finding.expected["filename"] == uri
        assert finding.detail.startswith(f"`{uri}`: package `kuka_lbr_iiwa_support` not found")
        assert "; searched " in finding.detail


def test_three_slashes_name_an_empty_package(lint):
    findings = lint(robot("package:///my_robot/meshes/part.stl"), "IN030")
    assert findings and "write `package://my_robot/meshes/part.stl`" in findings[0].help


def test_remote_uri(lint):
    findings = lint(robot("https://example.com/part.stl"), "IN030")
    assert len(findings) == 2 and "are not resolved" in findings[0].detail


def test_primitives_are_not_meshes(lint):
    text = (
        '<robot name="r"><link name="part"><visual><geometry><box size="1 1 1"/></geometry>'
        "</visual></link></robot>"
    )
    assert lint(text, "IN030") == []
