"""`inertia-kit report`: the link table in every format."""

import json

import pytest
from click.testing import CliRunner
from kit import REPO

from inertia_kit.cli import main

EXAMPLES = REPO / "examples"


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


def test_mesh_found_by_column_names_the_resolution_rule(tmp_path, monkeypatch):
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    from kit.meshes import write_box_stl

    write_box_stl(tmp_path / "urdf" / "meshes" / "a.stl", (0.1, 0.1, 0.1))
    write_box_stl(tmp_path / "data" / "parts" / "b.stl", (0.1, 0.1, 0.1))
    path = tmp_path / "urdf" / "r.urdf"
    path.write_text(
        '<robot name="r"><link name="a"><collision><geometry><mesh filename="meshes/a.stl"/>'
        '</geometry></collision><visual><geometry><mesh filename="parts/b.stl"/></geometry>'
        '</visual></link><link name="gone"><collision><geometry><mesh filename="x.stl"/>'
        "</geometry></collision></link></robot>"
    )
    result = report(str(path), "--package-path", str(tmp_path / "data"))
    assert result.exit_code == 0, result.output
    header, _, first, second = result.output.splitlines()[:4]
    column = header.index("mesh found by")
    assert first[column:].startswith("next-to-file, search-path  ")
    assert second[column:].startswith("not found  ")
    data = json.loads(
        report(str(path), "--format", "json", "--package-path", str(tmp_path / "data")).output
    )
    a, gone = data["links"]
    assert [(m["kind"], m["rule"]) for m in a["meshes"]] == [
        ("collision", "next-to-file"),
        ("visual", "search-path"),
    ]
    assert a["meshes"][1]["path"] == str(tmp_path / "data" / "parts" / "b.stl")
    (missing,) = gone["meshes"]
    assert (
        missing["rule"] is None
        and missing["path"] is None
        and "does not exist" in missing["problem"]
    )
    assert missing["searched"][0] == f"next to the file: {tmp_path / 'urdf' / 'x.stl'}"


# --- report --lumped -----------------------------------------------------------------------


LUMPED_URDF = """<robot name="r">
  <link name="base"><inertial><mass value="1"/>
    <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <link name="arm"><inertial><mass value="1"/>
    <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <joint name="f" type="fixed"><parent link="arm"/><child link="tool"/>
    <origin xyz="0 0 0.5"/></joint>
  <link name="tool"><inertial><mass value="2"/>
    <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <joint name="j2" type="revolute"><parent link="arm"/><child link="ghost"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <link name="ghost"/>
</robot>"""


def test_report_lumped_json_per_engine(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_text(LUMPED_URDF)
    result = CliRunner().invoke(
        main, ["report", "--lumped", "--engine", "gazebo,mujoco", "--format", "json", str(path)]
    )
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert [e["engine"] for e in data["engines"]] == ["mujoco", "gazebo"]
    gazebo = data["engines"][1]
    arm = next(b for b in gazebo["bodies"] if b["body"] == "arm")
    # 1 kg at 0 and 2 kg at 0.5: 3 kg at 1/3; ixx = 0.2 + 1 (1/3)² + 2 (1/6)²
    assert arm["links"] == ["arm", "tool"] and arm["mass"] == 3.0
    assert arm["com"][2] == pytest.approx(1 / 3)
    assert arm["inertia"][0][0] == pytest.approx(0.2 + 1 / 9 + 2 / 36)
    assert gazebo["dropped"] == [
        {"link": "ghost", "joint": "j2", "cause": "ghost", "reason": "no-inertial"}
    ]
    mujoco = data["engines"][0]
    assert mujoco["bodies"][0]["body"] == "world" and mujoco["bodies"][0]["static"]
    assert [b["body"] for b in mujoco["bodies"]] == ["world", "arm", "ghost"]


@pytest.mark.parametrize("output_format", ["text", "markdown"])
def test_report_lumped_tables_for_all_engines(tmp_path, output_format):
    path = tmp_path / "r.urdf"
    path.write_text(LUMPED_URDF)
    result = CliRunner().invoke(main, ["report", "--lumped", "--format", output_format, str(path)])
    assert result.exit_code == 0, result.output
    for title in ("MuJoCo", "Gazebo", "Drake", "PyBullet", "KDL"):
        assert title in result.output
    assert "arm, tool" in result.output and "dropped: ghost (joint j2)" in result.output


def test_report_lumped_shows_what_pybullet_gives_a_link_without_inertial(tmp_path):
    """As IN073 says: 1 kg at the link origin and the box inertia of its collision shape (a
    0.3 × 0.05 × 0.05 m box: m (b² + c²) / 12 about each axis), not a `-`."""
    path = tmp_path / "r.urdf"
    path.write_text(
        LUMPED_URDF.replace(
            '<link name="ghost"/>',
            '<link name="ghost"><collision><geometry><box size="0.3 0.05 0.05"/></geometry>'
            "</collision></link>",
        )
    )
    result = CliRunner().invoke(
        main, ["report", "--lumped", "--engine", "pybullet", "--format", "json", str(path)]
    )
    assert result.exit_code == 0, result.output
    (pybullet,) = json.loads(result.output)["engines"]
    ghost = next(b for b in pybullet["bodies"] if b["body"] == "ghost")
    assert ghost["mass"] == 1.0 and ghost["com"] == [0.0, 0.0, 0.0]
    # one box at the inertial frame: its own calculateLocalInertia, no margin
    x, y, z = 0.3, 0.05, 0.05
    expected = [(y * y + z * z) / 12, (x * x + z * z) / 12, (x * x + y * y) / 12]
    assert [ghost["inertia"][i][i] for i in range(3)] == pytest.approx(expected, rel=1e-6)
    assert "PyBullet gives it 1 kg" in ghost["note"]
    lint = CliRunner().invoke(
        main,
        ["lint", "--engine", "pybullet", "--select", "IN073", "--output-format", "json", str(path)],
    )
    (finding,) = [f for f in json.loads(lint.stdout) if f["link"] == "ghost"]
    assert finding["expected"]["inertia_diagonal"] == pytest.approx(
        [ghost["inertia"][i][i] for i in range(3)]
    )
