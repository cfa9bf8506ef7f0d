"""`inertia-kit report`: the link table in every format."""

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from inertia_kit.cli import main

EXAMPLES = Path(__file__).parent.parent / "examples"


def report(*args: str):
    return CliRunner().invoke(main, ["report", *args])


def test_json_report_of_the_mrm_arm_points_at_macro_body_and_call_site():
    result = report(str(EXAMPLES / "mrm_description/urdf/mrm.xacro"), "--format", "json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    links = {row["link"]: row for row in data["links"]}
    assert list(links) == ["base_link", "link_01", "link_02", "link_03", "link_04", "link_05"]
    assert links["link_01"]["mass"] == 157.633
    assert links["link_01"]["com"] == [0, 0, 0.2]
    assert links["link_01"]["principal_moments"] == pytest.approx([9.655, 13.235, 13.235])
    assert links["link_01"]["joint_type"] == "revolute"
    assert links["base_link"]["parent_joint"] is None
    assert links["link_01"]["file"].endswith("links_joints.xacro")
    assert links["link_01"]["call_site"]["file"].endswith("mrm.xacro")
    assert data["total_mass"] == pytest.approx(1024 + 157.633 + 3 * 57.906 + 18.056)


def test_text_report_lists_links_and_total():
    result = report(str(EXAMPLES / "my_robot_description/urdf/robot.xacro"))
    assert result.exit_code == 0, result.output
    assert "left_wheel_link" in result.output
    assert "left_wheel_joint (continuous)" in result.output
    assert "visual only: cylinder r0.03 l0.02" in result.output  # the lidar
    assert "total mass: 0.6 kg over 5 links (my_wheeled_robot)" in result.output


def test_markdown_report_with_meshes():
    result = report(
        str(EXAMPLES / "pan_tilt_description/urdf/pan_tilt.urdf"), "--format", "markdown"
    )
    assert result.exit_code == 0, result.output
    assert result.output.startswith("| link | joint (type) |")
    assert "mesh pan.stl ×0.001" in result.output


def test_unreadable_input_exits_2(tmp_path):
    bad = tmp_path / "bad.urdf"
    bad.write_text("<robot><link></robot>")
    result = report(str(bad))
    assert result.exit_code == 2
    assert f"{bad}:1" in result.output


def test_bad_xacro_arg_exits_2():
    result = report(str(EXAMPLES / "simple_arm/urdf/simple_arm.urdf.xacro"), "--xacro-arg", "oops")
    assert result.exit_code == 2
    assert "NAME:=VALUE" in result.output
