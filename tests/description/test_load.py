"""Loading robot descriptions: examples, xacro source map, meshes, hostile and broken input."""

from __future__ import annotations

import time
from pathlib import Path

import pytest
from kit import REPO, least_cpu, write

from inertia_kit.description import model
from inertia_kit.description import safexml as load_module
from inertia_kit.description.loader import load
from inertia_kit.errors import InputError

EXAMPLES = REPO / "examples"
NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


@pytest.fixture(autouse=True)
def no_ros_environment(monkeypatch):
    """Package lookup must not depend on the machine's ROS set-up."""
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)


def make_package(folder: Path, name: str) -> Path:
    write(folder / "package.xml", f'<package format="3"><name>{name}</name></package>\n')
    return folder


def at(source: model.Source) -> tuple:
    """File name, line and column of a source, for short assertions."""
    return (Path(source.path).name, source.line, source.column)


def position(text: str, needle: str, occurrence: int = 1) -> tuple[int, int]:
    """1-based (line, column) of the ``occurrence``-th ``needle`` in ``text``."""
    index = -1
    for _ in range(occurrence):
        index = text.index(needle, index + 1)
    line = text.count("\n", 0, index) + 1
    return line, index - (text.rfind("\n", 0, index) + 1) + 1


def raises_input_error(path: Path, **kwargs) -> InputError:
    with pytest.raises(InputError) as caught:
        load(path, **kwargs)
    return caught.value


# --- the examples ------------------------------------------------------------------------------

EXAMPLE_ROBOTS = {
    "simple_arm/urdf/simple_arm.urdf.xacro": (
        "simple_arm",
        ["base_link", "link_1", "link_2"],
        ["joint_1", "joint_2"],
    ),
    "robot1/urdf/robot1_base.xacro": (
        "robot0",
        ["base_footprint", "base_link", "wheel_1", "wheel_2", "wheel_3", "wheel_4"],
        ["base_footprint_joint", *(f"base_to_wheel{i}" for i in range(1, 5))],
    ),
    "my_robot_description/urdf/robot.xacro": (
        "my_wheeled_robot",
        ["base_footprint", "base_link", "left_wheel_link", "right_wheel_link", "lidar_link"],
        ["joint_name", "left_wheel_joint", "right_wheel_joint", "lidar_joint"],
    ),
    "my_robot_description/urdf/robot.urdf": (
        "my_robot",
        ["base_link", "link1", "link2"],
        ["joint1", "joint2"],
    ),
    "mrm_description/urdf/mrm.xacro": (
        "mrm",
        ["base_link", *(f"link_0{i}" for i in range(1, 6))],
        [
            f"{a}__link_0{i}"
            for i, a in enumerate(["base_link", *(f"link_0{i}" for i in range(1, 5))], 1)
        ],
    ),
    "pan_tilt_description/urdf/pan_tilt.urdf": (
        "pan_tilt",
        ["base_footprint", "base", "pan_link", "tilt_link", "camera_link"],
        ["base_joint", "pan_joint", "tilt_joint", "camera_joint"],
    ),
}
FRAGMENTS = [
    "mrm_description/urdf/links_joints.xacro",
    "mrm_description/urdf/robot_parameters.xacro",
    "my_robot_description/urdf/base.xacro",
    "my_robot_description/urdf/macros.xacro",
    "my_robot_description/urdf/sensors.xacro",
    "my_robot_description/urdf/wheels.xacro",
]


def test_every_example_file_is_covered():
    files = {
        str(p.relative_to(EXAMPLES)) for p in EXAMPLES.rglob("*") if p.suffix in (".urdf", ".xacro")
    }
    assert files == set(EXAMPLE_ROBOTS) | set(FRAGMENTS)


@pytest.mark.parametrize("relative", sorted(EXAMPLE_ROBOTS))
def test_example_loads(relative):
    name, links, joints = EXAMPLE_ROBOTS[relative]
    robot = load(EXAMPLES / relative)
    assert robot.name == name
    assert [link.name for link in robot.links] == links
    assert [joint.name for joint in robot.joints] == joints
    assert not robot.fragment and robot.invalid == ()
    assert robot.files[0] == str(EXAMPLES / relative)
    # one tree: every joint names links that exist, and one root
    assert {j.parent for j in robot.joints} | {j.child for j in robot.joints} <= set(links)
    assert robot.root == links[0]


@pytest.mark.parametrize("relative", FRAGMENTS)
def test_example_fragments_load_as_fragments(relative):
    robot = load(EXAMPLES / relative)
    assert robot.fragment and robot.links == () and robot.joints == ()


def test_mrm_inertials_come_from_the_macro_body_called_in_mrm_xacro():
    robot = load(EXAMPLES / "mrm_description/urdf/mrm.xacro")
    assert [Path(f).name for f in robot.files] == [
        "mrm.xacro",
        "robot_parameters.xacro",
        "links_joints.xacro",
    ]
    link = robot.link("link_01")
    inertial = link.inertial
    assert (inertial.mass, inertial.ixx, inertial.iyy, inertial.izz) == (
        157.633,
        13.235,
        13.235,
        9.655,
    )
    assert (inertial.ixy, inertial.ixz, inertial.iyz) == (0.0, 0.0, 0.0)
    assert inertial.origin.xyz == (0.0, 0.0, 0.2)
    # the <inertial> of macro m_link_cylinder, links_joints.xacro line 16
    assert at(inertial.source) == ("links_joints.xacro", 16, 7)
    assert at(inertial.mass_source) == ("links_joints.xacro", 17, 9)
    assert at(inertial.inertia_source) == ("links_joints.xacro", 19, 9)
    # called from mrm.xacro line 24
    assert [at(call) for call in inertial.source.calls] == [("mrm.xacro", 24, 3)]
    assert at(link.source) == ("links_joints.xacro", 15, 5)
    assert at(link.source.call_site) == ("mrm.xacro", 24, 3)
    # the box link comes from the other macro, called first
    base = robot.link("base_link")
    assert base.inertial.mass == 1024.0
    assert at(base.source) == ("links_joints.xacro", 37, 5)
    assert at(base.source.call_site) == ("mrm.xacro", 10, 3)
    assert isinstance(base.collisions[0].geometry, model.Box)
    assert base.collisions[0].geometry.size == (1.0, 1.0, 1.0)
    joint = robot.joint("link_01__link_02")
    assert (joint.parent, joint.child, joint.axis) == ("link_01", "link_02", (0.0, 1.0, 0.0))
    assert joint.limit.lower == -3.14 and joint.limit.effort == 1000.0
    assert at(joint.source.call_site) == ("mrm.xacro", 32, 3)


def test_split_xacro_elements_point_into_their_include():
    robot = load(EXAMPLES / "my_robot_description/urdf/robot.xacro")
    assert [Path(f).name for f in robot.files] == [
        "robot.xacro",
        "macros.xacro",
        "base.xacro",
        "wheels.xacro",
        "sensors.xacro",
    ]
    left, right = robot.link("left_wheel_link"), robot.link("right_wheel_link")
    assert at(left.source) == ("wheels.xacro", 39, 5)
    assert at(left.source.call_site) == ("robot.xacro", 17, 3)
    assert at(right.source.call_site) == ("robot.xacro", 18, 3)
    # properties local to the macro: wheel_mass 0.3, ixx 0.5 m r² with r = wheel_radius
    assert left.inertial.mass == 0.3
    assert at(left.inertial.source) == ("wheels.xacro", 58, 7)
    radius = left.collisions[0].geometry.radius
    assert left.inertial.ixx == pytest.approx(0.5 * 0.3 * radius**2)
    assert robot.link("base_link").inertial is None


def test_simple_arm_inertia_is_the_macro_formula():
    robot = load(EXAMPLES / "simple_arm/urdf/simple_arm.urdf.xacro")
    base = robot.link("base_link").inertial
    m, r, length = 2.0, 0.1, 0.05
    assert base.mass == m
    assert base.ixx == pytest.approx(m * (3 * r**2 + length**2) / 12)
    assert base.izz == pytest.approx(m * r**2 / 2)
    assert at(base.source) == ("simple_arm.urdf.xacro", 12, 5)
    assert at(base.source.call_site) == ("simple_arm.urdf.xacro", 34, 5)
    link_1 = robot.link("link_1")
    assert link_1.visuals[0].origin.xyz == (0.15, 0.0, 0.0)
    assert link_1.visuals[0].origin.rpy == pytest.approx((0.0, 3.14159265359 / 2, 0.0))


def test_plain_urdf_example_locations():
    path = EXAMPLES / "pan_tilt_description/urdf/pan_tilt.urdf"
    text = path.read_text()
    robot = load(path)
    tilt = robot.link("tilt_link")
    assert (tilt.source.line, tilt.source.column) == position(text, '<link name="tilt_link"')
    assert tilt.source.calls == ()
    assert tilt.inertial.mass == 0.115344
    assert (tilt.inertial.mass_source.line, tilt.inertial.mass_source.column) == position(
        text, '<mass value="0.115344"'
    )
    pan = robot.joint("pan_joint")
    assert (pan.limit.lower, pan.limit.upper, pan.limit.effort, pan.limit.velocity) == (
        -2.7,
        2.7,
        2.0,
        3.0,
    )
    assert (pan.dynamics.damping, pan.dynamics.friction) == (0.01, 0.0)


def test_package_meshes_of_the_example_resolve():
    robot = load(EXAMPLES / "pan_tilt_description/urdf/pan_tilt.urdf")
    shapes = [shape for link in robot.links for shape in (*link.visuals, *link.collisions)]
    meshes = [shape.geometry for shape in shapes if isinstance(shape.geometry, model.Mesh)]
    assert len(meshes) == 6
    for mesh in meshes:
        assert mesh.problem is None
        assert (
            Path(mesh.path) == EXAMPLES / "pan_tilt_description/meshes" / Path(mesh.filename).name
        )
    pan = robot.link("pan_link").collisions[0].geometry
    assert pan.scale == (0.001, 0.001, 0.001)
    assert robot.link("base").collisions[0].geometry.scale == (1.0, 1.0, 1.0)


# --- xacro: includes, arguments, macros --------------------------------------------------------


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    """``ws/src`` with a robot package including a part from another package via ``$(find)``."""
    src = tmp_path / "ws" / "src"
    robot_pkg = make_package(src / "my_robot", "my_robot")
    parts_pkg = make_package(src / "group" / "parts_description", "parts_description")
    write(
        parts_pkg / "urdf" / "arm.xacro",
        f"""<?xml version="1.0"?>
<robot {NS}>
  <xacro:macro name="arm" params="name mass">
    <link name="${{name}}">
      <inertial>
        <mass value="${{mass}}"/>
        <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/>
      </inertial>
      <collision>
        <geometry><mesh filename="package://parts_description/meshes/arm.stl"/></geometry>
      </collision>
      <visual>
        <geometry><mesh filename="$(find parts_description)/meshes/arm.stl"/></geometry>
      </visual>
    </link>
  </xacro:macro>
</robot>
""",
    )
    write(parts_pkg / "meshes" / "arm.stl", "solid a\nendsolid a\n")
    write(
        robot_pkg / "urdf" / "robot.urdf.xacro",
        f"""<?xml version="1.0"?>
<robot name="ws_robot" {NS}>
  <xacro:arg name="arm_mass" default="1.5"/>
  <xacro:arg name="with_tool" default="false"/>
  <xacro:include filename="$(find parts_description)/urdf/arm.xacro"/>
  <link name="base_link"/>
  <xacro:arm name="arm" mass="$(arg arm_mass)"/>
  <joint name="arm_joint" type="revolute">
    <parent link="base_link"/>
    <child link="arm"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <xacro:if value="$(arg with_tool)">
    <link name="tool"/>
    <joint name="tool_joint" type="fixed"><parent link="arm"/><child link="tool"/></joint>
  </xacro:if>
</robot>
""",
    )
    return tmp_path / "ws"


def test_find_includes_resolve_from_a_workspace_layout(workspace):
    path = workspace / "src/my_robot/urdf/robot.urdf.xacro"
    robot = load(path)
    assert [link.name for link in robot.links] == ["base_link", "arm"]
    assert [Path(f).name for f in robot.files] == ["robot.urdf.xacro", "arm.xacro"]
    arm = robot.link("arm")
    assert arm.inertial.mass == 1.5
    assert at(arm.source) == ("arm.xacro", 4, 5)
    assert Path(arm.source.path).parent.parent.name == "parts_description"
    assert at(arm.source.call_site) == ("robot.urdf.xacro", 7, 3)
    # a package:// URI and a $(find) path to the same mesh
    expected = workspace / "src/group/parts_description/meshes/arm.stl"
    for shape in (*arm.collisions, *arm.visuals):
        assert shape.geometry.problem is None
        assert Path(shape.geometry.path).resolve() == expected.resolve()


def test_find_includes_resolve_through_package_paths(workspace, tmp_path):
    # the robot copied away from the workspace: only --package-path can find the parts
    path = write(
        tmp_path / "elsewhere" / "robot.urdf.xacro",
        (workspace / "src/my_robot/urdf/robot.urdf.xacro").read_text(),
    )
    error = raises_input_error(path)
    assert "parts_description" in error.message and error.line == 5
    robot = load(path, package_paths=[workspace / "src"])
    assert robot.link("arm").collisions[0].geometry.problem is None


def test_xacro_arguments(workspace):
    path = workspace / "src/my_robot/urdf/robot.urdf.xacro"
    robot = load(path, xacro_args={"arm_mass": "2.25", "with_tool": "true"})
    assert robot.link("arm").inertial.mass == 2.25
    assert [link.name for link in robot.links] == ["base_link", "arm", "tool"]
    assert robot.joint("tool_joint").source.line == 15


def test_undefined_xacro_argument_is_an_input_error(tmp_path):
    path = write(
        tmp_path / "r.xacro",
        f'<robot name="r" {NS}>\n  <link name="a">\n    <inertial><mass value="$(arg m)"/>'
        "</inertial>\n  </link>\n</robot>\n",
    )
    error = raises_input_error(path)
    assert "m" in error.message and error.path == str(path) and error.line == 3
    assert load(path, xacro_args={"m": "4"}).link("a").inertial.mass == 4.0


def test_macro_generated_link_points_at_macro_body_and_call_site(tmp_path):
    text = f"""<?xml version="1.0"?>
<robot name="r" {NS}>
  <xacro:macro name="leg" params="side">
    <link name="${{side}}_leg">
      <inertial>
        <mass value="2"/>
        <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
      </inertial>
    </link>
  </xacro:macro>
  <link name="body"/>
  <xacro:leg side="left"/>
      <xacro:leg side="right"/>
</robot>
"""
    robot = load(write(tmp_path / "legs.urdf.xacro", text))
    left, right = robot.link("left_leg"), robot.link("right_leg")
    assert at(left.source) == at(right.source) == ("legs.urdf.xacro", 4, 5)
    assert at(left.source.call_site) == ("legs.urdf.xacro", 12, 3)
    assert at(right.source.call_site) == ("legs.urdf.xacro", 13, 7)
    assert at(left.inertial.inertia_source) == ("legs.urdf.xacro", 7, 9)
    assert robot.link("body").source.calls == ()


def test_nested_macros_list_calls_outermost_first(tmp_path):
    text = f"""<robot name="r" {NS}>
  <xacro:macro name="inner" params="n">
    <link name="${{n}}"/>
  </xacro:macro>
  <xacro:macro name="outer" params="n">
    <xacro:inner n="${{n}}"/>
  </xacro:macro>
  <xacro:outer n="a"/>
</robot>
"""
    robot = load(write(tmp_path / "nested.xacro", text))
    link = robot.link("a")
    assert at(link.source) == ("nested.xacro", 3, 5)
    assert [at(call)[1:] for call in link.source.calls] == [(8, 3), (6, 5)]


def test_xacro_fragment_loads_as_fragment(tmp_path):
    path = write(
        tmp_path / "macros.xacro",
        f'<robot {NS}>\n  <xacro:property name="w" value="0.1"/>\n'
        '  <xacro:macro name="m" params="x"><link name="${x}"/></xacro:macro>\n</robot>\n',
    )
    robot = load(path)
    assert robot.fragment is True
    assert (robot.links, robot.joints, robot.invalid) == ((), (), ())
    assert robot.files == (str(path),)


def test_file_declaring_the_xacro_namespace_without_using_it_is_plain_urdf(tmp_path):
    # as xacro's own output is; libxml2 then reports the true columns
    text = (
        "\n<?xml version='1.0'?>\n"  # a declaration after a blank line: expat would refuse it
        f'<robot name="r" {NS}>\n\t<link name="a"/>\n</robot>\n'
    )
    robot = load(write(tmp_path / "generated.urdf", text))
    assert [link.name for link in robot.links] == ["a"]
    assert at(robot.link("a").source) == ("generated.urdf", 4, 2)


def test_xacro_in_comments_alone_is_plain_urdf(tmp_path, monkeypatch):
    """PR2's generated URDF quotes ``${cal_head_x}`` and commented-out ``${…}`` values in
    comments, which xacro leaves as they are: it loads as URDF, without xacro, to the model
    xacro's expansion gives."""
    from inertia_kit.description.urdf import reader

    text = (
        f'<robot name="r" {NS}>\n  <!-- replaced by ${{cal_head_x}} and $(find pkg) -->\n'
        '  <link name="a">\n    <!--\n    <origin xyz="${0.09/2.0} 0 0"/> -->\n'
        '    <inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" '
        'izz="1"/></inertial>\n  </link>\n</robot>\n'
    )
    path = write(tmp_path / "generated.urdf", text)
    assert not reader.needs_expansion(path.read_bytes())
    plain = load(path)
    monkeypatch.setattr(reader, "needs_expansion", lambda data: True)
    expanded = load(path)
    assert plain.links == expanded.links and plain.links[0].source.line == 3


@pytest.mark.parametrize(
    "text",
    [
        # a comment turning comment evaluation on: xacro evaluates the comments after it
        f"<robot name='r' {NS}>\n  <!-- xacro:eval-comments -->\n  <!-- ${{1+1}} -->\n</robot>\n",
        # a CDATA section may hold a "<!--" that is no comment: comments are not taken out
        f"<robot name='r' {NS}>\n  <![CDATA[ <!-- ]]> ${{x}} <!-- -->\n</robot>\n",
        # outside comments
        f"<robot name='r' {NS}>\n  <!-- c -->\n  <link name='${{n}}'/>\n</robot>\n",
    ],
)
def test_xacro_outside_comments_or_in_evaluated_comments_is_expanded(text):
    from inertia_kit.description.urdf.reader import needs_expansion

    assert needs_expansion(text.encode())


def test_comments_are_taken_out_in_linear_time():
    """A hostile file of ``<!--`` with no ``-->`` after them: 8 times as many take ~8 times as
    long (a pattern retried from each would take ~64 times, ~20 s for the larger)."""
    from inertia_kit.description.urdf.reader import needs_expansion

    def seconds(count):
        data = f"<robot name='r' {NS}><!-- c -->".encode() + b"<!--" * count + b"</robot>"
        spent, needed = least_cpu(lambda: needs_expansion(data), runs=5)
        assert not any(needed)
        return spent

    assert seconds(32000) / max(seconds(4000), 1e-6) < 24


def test_empty_robot_declaring_the_xacro_namespace_is_a_fragment(tmp_path):
    # example-robot-data's ur3.urdf: xacro output of a file that defined nothing
    text = f"<?xml version='1.0'?>\n<!-- generated -->\n<robot {NS}>\n  <!-- c -->\n</robot>\n"
    robot = load(write(tmp_path / "ur3.urdf", text))
    assert robot.fragment and robot.links == ()
    # without the namespace it is a robot with no links, for the rules to judge
    robot = load(write(tmp_path / "plain.urdf", "<robot name='r'/>\n"))
    assert not robot.fragment and robot.links == () and robot.name == "r"


@pytest.mark.parametrize(
    ("name", "body"),
    [
        # turtlebot3's common_properties.urdf: the namespace declared, materials only
        ("common_properties.urdf", '<material name="blue"><color rgba="0 0 0.8 1"/></material>'),
        # a robot's Gazebo settings kept apart, xacro by name
        ("robot.gazebo.xacro", '<gazebo reference="base"><mu1>0.5</mu1></gazebo>'),
        # everything behind a condition that is off by default
        (
            "extras.urdf.xacro",
            '<xacro:arg name="on" default="false"/>'
            '<xacro:if value="$(arg on)"><link name="x"/></xacro:if>',
        ),
    ],
)
def test_a_xacro_file_without_links_or_joints_is_a_fragment(tmp_path, name, body):
    robot = load(write(tmp_path / name, f'<robot name="parts" {NS}>\n  {body}\n</robot>\n'))
    assert robot.fragment and (robot.links, robot.joints) == ((), ())


def test_a_plain_file_without_links_is_a_robot_for_the_rules_and_other_roots_are_refused(
    tmp_path,
):
    robot = load(write(tmp_path / "colours.urdf", '<robot name="r"><material name="m"/></robot>'))
    assert not robot.fragment and robot.links == ()
    # joints and no links: not a fragment either (IN040 names the missing links)
    text = f'<robot name="r" {NS}><joint name="j" type="fixed"><parent link="a"/>'
    text += '<child link="b"/></joint></robot>'
    assert not load(write(tmp_path / "joints.urdf.xacro", text)).fragment
    raises_input_error(write(tmp_path / "l.xacro", f"<launch {NS}><arg name='x'/></launch>"))


# --- meshes ------------------------------------------------------------------------------------


def test_relative_package_and_missing_meshes(tmp_path):
    package = make_package(tmp_path / "pkg", "pkg")
    write(package / "meshes" / "a.stl", "solid a\nendsolid a\n")
    path = write(
        package / "urdf" / "r.urdf",
        """<robot name="r">
  <link name="a">
    <visual><geometry><mesh filename="../meshes/a.stl" scale="1 1 1"/></geometry></visual>
    <collision><geometry><mesh filename="package://pkg/meshes/a.stl"/></geometry></collision>
    <collision><geometry><mesh filename="package://pkg/meshes/gone.stl"/></geometry></collision>
    <collision><geometry><mesh filename="package://nowhere/a.stl"/></geometry></collision>
    <collision><geometry><mesh filename="https://example.com/a.stl"/></geometry></collision>
    <collision><geometry><mesh/></geometry></collision>
  </link>
</robot>
""",
    )
    link = load(path).link("a")
    relative = link.visuals[0].geometry
    assert Path(relative.path) == package / "meshes" / "a.stl" and relative.problem is None
    found, gone, nowhere, remote, empty = (shape.geometry for shape in link.collisions)
    assert Path(found.path) == package / "meshes" / "a.stl" and found.problem is None
    for mesh in (gone, nowhere, remote, empty):
        assert isinstance(mesh, model.Mesh)
        assert mesh.path is None and mesh.problem
    assert "gone.stl" in gone.problem and "does not exist" in gone.problem
    assert "`nowhere`" in nowhere.problem and "--package-path" in nowhere.problem
    assert "https://" in remote.problem
    assert "empty" in empty.problem
    assert gone.source.line == 5


def test_missing_mesh_in_xacro_is_recorded_not_raised(tmp_path):
    path = write(
        tmp_path / "r.xacro",
        f'<robot name="r" {NS}>\n  <xacro:property name="f" value="meshes/none.dae"/>\n'
        '  <link name="a"><visual><geometry><mesh filename="${f}"/></geometry></visual></link>\n'
        "</robot>\n",
    )
    mesh = load(path).link("a").visuals[0].geometry
    assert mesh.path is None and "does not exist" in mesh.problem
    assert mesh.filename == "meshes/none.dae" and mesh.source.line == 3


# --- hostile and broken XML --------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "line", "column"),
    [
        ('<robot name="r">\n  <link name="a">\n</robot>\n', 3, None),
        ('<robot name="r">\n  <link name="a"/>\n  <link name=a/>\n</robot>\n', 3, None),
        ("<robot>\n", 2, None),
        ('<robot name="r"/>\n<robot name="s"/>\n', 2, None),
    ],
    ids=["mismatched-tag", "unquoted-attribute", "truncated", "two-roots"],
)
def test_malformed_xml(tmp_path, text, line, column):
    path = write(tmp_path / "bad.urdf", text)
    error = raises_input_error(path)
    assert error.message.startswith("not well-formed XML")
    assert (error.path, error.line) == (str(path), line)
    assert error.column is not None
    assert str(error).startswith(f"{path}:{line}:")


def test_malformed_xacro_reports_the_include_and_line(tmp_path):
    write(tmp_path / "part.xacro", f'<robot {NS}>\n  <link name="a">\n</robot>\n')
    path = write(
        tmp_path / "r.xacro",
        f'<robot name="r" {NS}>\n  <xacro:include filename="part.xacro"/>\n</robot>\n',
    )
    error = raises_input_error(path)
    assert "not well-formed" in error.message
    assert (Path(error.path).name, error.line) == ("part.xacro", 3)


@pytest.mark.parametrize(
    ("text", "tag"),
    [
        ('<?xml version="1.0"?>\n<sdf version="1.6"><model name="m"/></sdf>\n', "sdf"),
        (f'<?xml version="1.0"?>\n<launch {NS}><arg name="x"/></launch>\n', "launch"),
    ],
)
def test_wrong_root_element(tmp_path, text, tag):
    path = write(tmp_path / "r.urdf", text)
    error = raises_input_error(path)
    assert f"<{tag}>" in error.message and "<robot>" in error.message
    assert (error.path, error.line, error.column) == (str(path), 2, 1)


SECRET = "inertia-kit-secret-7f3a"


@pytest.fixture
def secret_file(tmp_path: Path) -> Path:
    return write(tmp_path / "secret.txt", SECRET)


@pytest.mark.parametrize("xacro", [False, True])
def test_external_entity_is_refused_and_nothing_fetched(tmp_path, secret_file, xacro):
    namespace = f" {NS}" if xacro else ""
    text = (
        '<?xml version="1.0"?>\n'
        f'<!DOCTYPE r [<!ENTITY x SYSTEM "file://{secret_file}">]>\n'
        f'<robot name="&x;"{namespace}>\n  <link name="&x;"/>\n</robot>\n'
    )
    path = write(tmp_path / "xxe.urdf", text)
    error = raises_input_error(path)
    assert "entity" in error.message and "nothing was expanded or fetched" in error.message
    assert (error.path, error.line) == (str(path), 2)
    assert SECRET not in str(error)


def test_external_entity_in_utf16_is_refused_after_parsing_nothing_fetched(tmp_path, secret_file):
    text = (
        '<?xml version="1.0" encoding="UTF-16"?>\n'
        f'<!DOCTYPE r [<!ENTITY x SYSTEM "file://{secret_file}">]>\n'
        '<robot name="r"><link name="a">&x;</link></robot>\n'
    )
    # the bytes hide the declaration from the byte-level check: the parsed DTD shows it
    path = write(tmp_path / "xxe16.urdf", text.encode("utf-16"))
    error = raises_input_error(path)
    assert "entity" in error.message and SECRET not in str(error)
    assert error.path == str(path) and error.line == 1


def test_external_entity_in_a_xacro_include_is_refused(tmp_path, secret_file):
    write(
        tmp_path / "part.xacro",
        f'<?xml version="1.0"?>\n\n<!DOCTYPE r [<!ENTITY x SYSTEM "file://{secret_file}">]>\n'
        f'<robot {NS}><link name="&x;"/></robot>\n',
    )
    path = write(
        tmp_path / "r.xacro",
        f'<robot name="r" {NS}>\n  <xacro:include filename="part.xacro"/>\n</robot>\n',
    )
    error = raises_input_error(path)
    assert "entity" in error.message and SECRET not in str(error)
    assert (Path(error.path).name, error.line) == ("part.xacro", 3)


BILLION_LAUGHS = """<?xml version="1.0"?>
<!DOCTYPE lolz [
 <!ENTITY lol "lol">
 <!ENTITY lol1 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">
 <!ENTITY lol2 "&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;">
 <!ENTITY lol3 "&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;">
 <!ENTITY lol4 "&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;">
 <!ENTITY lol5 "&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;">
 <!ENTITY lol6 "&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;">
 <!ENTITY lol7 "&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;">
 <!ENTITY lol8 "&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;">
 <!ENTITY lol9 "&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;">
]>
<robot name="&lol9;"{namespace}><link name="&lol9;"/></robot>
"""


@pytest.mark.parametrize("xacro", [False, True])
def test_billion_laughs_is_refused_without_expanding(tmp_path, xacro):
    namespace = f" {NS}" if xacro else ""
    path = write(tmp_path / "lol.urdf", BILLION_LAUGHS.format(namespace=namespace))
    started = time.perf_counter()
    error = raises_input_error(path)
    assert time.perf_counter() - started < 2
    assert "entity" in error.message
    assert (error.path, error.line) == (str(path), 3)


def test_a_doctype_without_entities_is_fine(tmp_path):
    path = write(
        tmp_path / "r.urdf", '<!DOCTYPE robot>\n<robot name="r"><link name="a"/></robot>\n'
    )
    assert at(load(path).link("a").source) == ("r.urdf", 2, 17)


# --- numbers -----------------------------------------------------------------------------------

NUMBERS = """<robot name="r">
  <link name="bad">
    <inertial>
      <origin xyz="1 2" rpy="0 0 0"/>
      <mass value="abc"/>
      <inertia ixx="nan" ixy="0" ixz="0" iyy="inf" iyz="0" izz="-Infinity"/>
    </inertial>
  </link>
  <link name="good">
    <inertial>
      <origin xyz=" 1e-3 -.5 +2. " rpy="0 0 0"/>
      <mass value=" 2.5 "/>
      <inertia ixx="1E-2" ixy="-0" ixz="0" iyy="3" iyz="0" izz="4"/>
    </inertial>
    <collision><geometry><box size="1 1_0 1"/></geometry></collision>
    <collision><geometry><cylinder radius="0x10" length=""/></geometry></collision>
  </link>
  <joint name="j" type="revolute">
    <parent link="bad"/><child link="good"/>
    <axis xyz="0, 0, 1"/>
    <limit lower="-1.57." upper="1" effort="1" velocity="1"/>
  </joint>
</robot>
"""


def test_non_numeric_values_are_located_and_the_rest_loads(tmp_path):
    path = write(tmp_path / "numbers.urdf", NUMBERS)
    robot = load(path)
    bad, good = robot.link("bad").inertial, robot.link("good").inertial
    assert isinstance(bad.origin.xyz, model.Invalid)
    assert (bad.origin.xyz.text, bad.origin.xyz.attribute) == ("1 2", "xyz")
    assert at(bad.origin.xyz.source) == ("numbers.urdf", 4, 7)
    assert bad.origin.rpy == (0.0, 0.0, 0.0)
    assert isinstance(bad.mass, model.Invalid) and bad.mass.text == "abc"
    assert at(bad.mass.source) == ("numbers.urdf", 5, 7)
    for name, text in (("ixx", "nan"), ("iyy", "inf"), ("izz", "-Infinity")):
        value = getattr(bad, name)
        assert isinstance(value, model.Invalid)
        assert (value.text, value.attribute) == (text, name)
        assert at(value.source) == ("numbers.urdf", 6, 7)
    assert (bad.ixy, bad.ixz, bad.iyz) == (0.0, 0.0, 0.0)
    # the other link is whole
    assert good.mass == 2.5 and good.origin.xyz == (1e-3, -0.5, 2.0)
    assert (good.ixx, good.ixy, good.iyy, good.izz) == (0.01, 0.0, 3.0, 4.0)
    box, cylinder = (shape.geometry for shape in robot.link("good").collisions)
    assert isinstance(box.size, model.Invalid) and box.size.text == "1 1_0 1"
    assert isinstance(cylinder.radius, model.Invalid) and isinstance(cylinder.length, model.Invalid)
    joint = robot.joint("j")
    assert isinstance(joint.axis, model.Invalid) and joint.axis.text == "0, 0, 1"
    assert isinstance(joint.limit.lower, model.Invalid) and joint.limit.upper == 1.0
    # robot.invalid lists each, in document order
    assert [(i.attribute, i.text, i.source.line) for i in robot.invalid] == [
        ("xyz", "1 2", 4),
        ("value", "abc", 5),
        ("ixx", "nan", 6),
        ("iyy", "inf", 6),
        ("izz", "-Infinity", 6),
        ("size", "1 1_0 1", 15),
        ("radius", "0x10", 16),
        ("length", "", 16),
        ("xyz", "0, 0, 1", 20),
        ("lower", "-1.57.", 21),
    ]


def test_non_numeric_values_from_xacro_point_at_the_macro(tmp_path):
    text = f"""<robot name="r" {NS}>
  <xacro:macro name="body" params="name mass">
    <link name="${{name}}">
      <inertial><mass value="${{mass}}"/></inertial>
    </link>
  </xacro:macro>
  <xacro:body name="a" mass="heavy"/>
  <xacro:body name="b" mass="1"/>
</robot>
"""
    robot = load(write(tmp_path / "m.xacro", text))
    (invalid,) = robot.invalid
    assert invalid.text == "heavy" and robot.link("a").inertial.mass is invalid
    assert at(invalid.source) == ("m.xacro", 4, 17)
    assert at(invalid.source.call_site) == ("m.xacro", 7, 3)
    assert robot.link("b").inertial.mass == 1.0


def test_missing_values_stay_none(tmp_path):
    path = write(
        tmp_path / "r.urdf",
        """<robot name="r">
  <link name="partial">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1"/></inertial>
  </link>
  <link name="no_inertia"><inertial><mass value="1"/></inertial></link>
  <link name="no_mass">
    <inertial><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
  </link>
  <link name="bare"/>
  <joint name="j" type="fixed"><parent link="bare"/><child link="partial"/></joint>
</robot>
""",
    )
    robot = load(path)
    partial = robot.link("partial").inertial
    assert (partial.ixx, partial.iyy, partial.izz) == (1.0, 1.0, 1.0)
    assert (partial.ixy, partial.ixz, partial.iyz) == (None, None, None)
    no_inertia = robot.link("no_inertia").inertial
    assert no_inertia.mass == 1.0 and no_inertia.inertia_source is None
    assert all(value is None for value in no_inertia.tensor_values().values())
    assert no_inertia.origin == model.Origin()
    no_mass = robot.link("no_mass").inertial
    assert no_mass.mass is None and no_mass.mass_source is None and no_mass.izz == 1.0
    assert robot.link("bare").inertial is None
    joint = robot.joint("j")
    assert (joint.axis, joint.limit, joint.dynamics, joint.mimic) == (None, None, None, None)
    assert robot.invalid == ()


# --- files that are not robot descriptions -----------------------------------------------------


def test_file_that_is_not_there(tmp_path):
    error = raises_input_error(tmp_path / "nope.urdf")
    assert error.message == "no such file" and error.path == str(tmp_path / "nope.urdf")


def test_directory(tmp_path):
    error = raises_input_error(tmp_path)
    assert "directory" in error.message and error.path == str(tmp_path)


@pytest.mark.parametrize("data", [b"", b"  \n\t\r\n", b"\xef\xbb\xbf", b"\xef\xbb\xbf\n \n"])
@pytest.mark.parametrize("name", ["empty.urdf", "empty.xacro"])
def test_empty_file(tmp_path, data, name):
    error = raises_input_error(write(tmp_path / name, data))
    assert "empty" in error.message


@pytest.mark.parametrize(
    "data",
    [
        b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\x00\x00\x00\x10",
        b"solid\x00\x00\x00" + bytes(range(256)) * 4,
        b'<robot name="r">\x00<link name="a"/></robot>',
        bytes(range(256)),
    ],
    ids=["png", "binary-stl", "nul-inside", "all-bytes"],
)
def test_binary_file(tmp_path, data):
    error = raises_input_error(write(tmp_path / "b.urdf", data))
    assert "binary" in error.message and error.path == str(tmp_path / "b.urdf")
    assert error.line is not None


@pytest.mark.parametrize("name", ["big.urdf", "big.xacro"])
def test_file_over_the_size_bound(tmp_path, monkeypatch, name):
    monkeypatch.setattr(load_module, "MAX_BYTES", 64)
    text = f'<robot name="r" {NS}>' + "<link name='a'/>" * 10 + "</robot>"
    error = raises_input_error(write(tmp_path / name, text))
    assert "larger than 64 bytes" in error.message and error.path == str(tmp_path / name)
    # at the bound it still loads
    monkeypatch.setattr(load_module, "MAX_BYTES", len(text))
    assert len(load(tmp_path / name).links) == 10


def test_nul_in_path_is_an_input_error(tmp_path):
    with pytest.raises(InputError):
        load(str(tmp_path / "a\0b.urdf"))


def test_utf8_bom_and_crlf(tmp_path):
    text = '<?xml version="1.0"?>\r\n<robot name="r">\r\n  <link name="é"><inertial>\r\n'
    text += '    <mass value="2"/></inertial></link>\r\n</robot>\r\n'
    for name, data in (
        ("bom.urdf", b"\xef\xbb\xbf" + text.encode()),
        ("bom.xacro", b"\xef\xbb\xbf" + text.replace('"r"', f'"r" {NS}').encode()),
        ("crlf.urdf", text.encode()),
    ):
        robot = load(write(tmp_path / name, data))
        link = robot.link("é")
        assert link.inertial.mass == 2.0
        assert at(link.source) == (name, 3, 3)
        assert at(link.inertial.mass_source) == (name, 4, 5)
    # the BOM is not a column: <robot> on line 1 starts at column 1
    robot = load(
        write(tmp_path / "first.urdf", b'\xef\xbb\xbf<robot name="r"><link name="a"/></robot>')
    )
    assert at(robot.source) == ("first.urdf", 1, 1)
    assert at(robot.link("a").source) == ("first.urdf", 1, 17)


def test_latin1_declared_encoding(tmp_path):
    data = '<?xml version="1.0" encoding="ISO-8859-1"?>\n<robot name="ü"><link name="ß"/></robot>\n'
    robot = load(write(tmp_path / "latin.urdf", data.encode("latin-1")))
    assert robot.name == "ü" and at(robot.link("ß").source) == ("latin.urdf", 2, 17)


def test_utf16_loads(tmp_path):
    data = (
        '<?xml version="1.0" encoding="UTF-16"?>\n<robot name="r">\n  <link name="a"/>\n</robot>\n'
    )
    robot = load(write(tmp_path / "wide.urdf", data.encode("utf-16")))
    assert [link.name for link in robot.links] == ["a"]
    assert robot.link("a").source.line == 3


# --- positions ---------------------------------------------------------------------------------

TENSOR = 'ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"'
SPHERE = '<visual><geometry><sphere radius="1"/></geometry></visual>'
LAYOUT = f"""<?xml version="1.0"?>
<!-- a <link name="in a comment"/> before everything -->
<robot name="r">
\t<link name="tabbed"><inertial><mass value="1"/><inertia {TENSOR}/></inertial></link>
  <link name="ünïcödé"> <!-- <inertia --> <inertial>
    <inertia
        ixx="1" ixy="0" ixz="0"
        iyy="1" iyz="0" izz="zz"/>
    <mass
      value="3"/></inertial>
  </link>
  <link name="cdata"><![CDATA[ <inertial> ]]>{SPHERE}</link>
  <joint name="j" type="fixed"><parent link="tabbed"/><child link="cdata"/></joint>
</robot>
"""


def test_columns_point_at_the_start_of_the_element(tmp_path):
    path = write(tmp_path / "layout.urdf", LAYOUT)
    robot = load(path)

    def where(source: model.Source) -> tuple[int, int]:
        assert source.path == str(path) and source.calls == ()
        return source.line, source.column

    assert where(robot.source) == position(LAYOUT, '<robot name="r">')
    tabbed = robot.link("tabbed")
    assert where(tabbed.source) == (4, 2)  # a tab is one column
    assert where(tabbed.inertial.source) == position(LAYOUT, "<inertial>")
    # <inertia right after <mass/>, not the <inertial just before it
    assert where(tabbed.inertial.inertia_source) == position(LAYOUT, "<inertia ixx")
    unicode = robot.link("ünïcödé")
    assert where(unicode.source) == (5, 3)
    # columns count characters, not bytes; the comment's "<inertia" is not an element
    assert where(unicode.inertial.source) == (5, 43)
    assert position(LAYOUT, "<inertial>\n") == (5, 43)
    # a start tag over several lines is where it starts, not where lxml's sourceline puts it
    assert where(unicode.inertial.inertia_source) == (6, 5)
    assert where(unicode.inertial.mass_source) == (9, 5)
    assert unicode.inertial.mass == 3.0
    (invalid,) = robot.invalid
    assert (invalid.attribute, where(invalid.source)) == ("izz", (6, 5))
    sphere = robot.link("cdata").visuals[0].geometry
    assert where(sphere.source) == position(LAYOUT, "<sphere")
    joint = robot.joint("j")
    assert where(joint.source) == position(LAYOUT, '<joint name="j"') == (13, 3)


def test_lines_past_65535_are_exact(tmp_path):
    # libxml2 2.14 reports sourceline one too high there
    text = '<robot name="r">' + "\n" * 70_000 + '  <link name="far"/>\n</robot>\n'
    robot = load(write(tmp_path / "long.urdf", text))
    assert at(robot.link("far").source) == ("long.urdf", 70_001, 3)


def test_lines_and_columns_of_every_element_match_the_text(tmp_path):
    """Each located element's source names a line and column where its start tag begins."""
    path = EXAMPLES / "pan_tilt_description/urdf/pan_tilt.urdf"
    lines = path.read_text().split("\n")
    robot = load(path)
    sources = [robot.source]
    for link in robot.links:
        sources.append(link.source)
        if link.inertial:
            sources += [
                link.inertial.source,
                link.inertial.mass_source,
                link.inertial.inertia_source,
            ]
        for shape in (*link.visuals, *link.collisions):
            sources += [shape.source, shape.geometry.source]
    for joint in robot.joints:
        sources += [joint.source, *(x.source for x in (joint.limit, joint.dynamics) if x)]
    assert len(sources) > 40
    for source in sources:
        assert lines[source.line - 1][source.column - 1] == "<", source


# --- what TinyXML2 (urdfdom, PyBullet) reads and libxml2 does not --------------------------------


@pytest.mark.parametrize(
    "prefix",
    [
        '<?xml version="0.0" ?>\n',
        '\n\n\n<?xml version="1.0"?>\n',
        ' <?xml version="0.0" ?>\n',
        '<!-- generated -->\n<?xml version="1.0" encoding="utf-8"?>\n',
    ],
    ids=["version-0.0", "blank-lines-first", "space-and-version", "comment-first"],
)
def test_xml_declaration_slips_are_tolerated(tmp_path, prefix):
    text = prefix + '<robot name="r">\n  <link name="a"/>\n</robot>\n'
    robot = load(write(tmp_path / "slip.urdf", text))
    assert at(robot.link("a").source) == ("slip.urdf", prefix.count("\n") + 2, 3)


def test_misplaced_declaration_keeps_its_encoding(tmp_path):
    text = '\n<?xml version="1.0" encoding="ISO-8859-1"?>\n<robot name="Müller"/>\n'
    assert load(write(tmp_path / "l.urdf", text.encode("latin-1"))).name == "Müller"


def test_trailing_nul_bytes_are_ignored(tmp_path):
    robot = load(write(tmp_path / "nul.urdf", b'<robot name="r"><link name="a"/></robot>\r\n\x00'))
    assert [link.name for link in robot.links] == ["a"]


def test_default_namespace_on_robot(tmp_path):
    text = (
        '<robot name="r" xmlns="http://example.com/urdf" xmlns:drake="http://drake.mit.edu">\n'
        '  <link name="a"><inertial><mass value="2"/></inertial>\n'
        '    <collision><geometry><drake:capsule radius="1"/></geometry></collision>\n'
        "  </link>\n"
        '  <drake:joint name="ignored" type="fixed"/>\n'
        "</robot>\n"
    )
    robot = load(write(tmp_path / "ns.urdf", text))
    assert robot.link("a").inertial.mass == 2.0
    assert robot.joints == ()
    geometry = robot.link("a").collisions[0].geometry
    assert isinstance(geometry, model.Unknown) and geometry.tag == "drake:capsule"


# --- nothing but InputError --------------------------------------------------------------------

NASTY = [
    b"<",
    b"<robot",
    b"<robot name='r'><link name='a'><inertial><mass value='1'/>",
    b'<?xml version="1.0" encoding="no-such-encoding"?><robot/>',
    b'<?xml version="1.0" encoding="UTF-16"?><robot/>',
    b"\xff\xfe<\x00r\x00",
    b"\xfe\xff\x00<",
    b"<robot>\xff\xfe\xfd</robot>",
    b"<!-- unterminated <robot/>",
    b"<![CDATA[<robot/>]]>",
    b"<?pi?>",
    b"<robot/><!-- -- -->",
    b"<!DOCTYPE robot [<!ELEMENT robot ANY>]><robot/>",
    b'<robot xmlns:xacro="x"><xacro:macro/></robot>',
    b'<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:include filename="/"/></robot>',
    b'<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="${1/0}"/></robot>',
    b'<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:undefined/></robot>',
    b'<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="$(find)"/></robot>',
    b"<robot>" + b"<a>" * 300 + b"</a>" * 300 + b"</robot>",
    b'<robot><link name="a"><visual><geometry><mesh filename="package://"/></geometry>'
    b"</visual></link></robot>",
    b'<robot><link name="a"><visual><geometry><mesh filename="file://"/></geometry>'
    b"</visual></link></robot>",
    b'<robot><link><inertial><mass value="1e999"/><inertia ixx="-1e-999"/></inertial></link>'
    b"</robot>",
]


@pytest.mark.parametrize("data", NASTY, ids=range(len(NASTY)))
def test_nothing_but_input_error_escapes(tmp_path, data):
    path = write(tmp_path / "nasty.urdf", data)
    try:
        robot = load(path)
    except InputError as error:
        assert error.path is not None and error.message
    else:
        assert isinstance(robot, model.Robot)
