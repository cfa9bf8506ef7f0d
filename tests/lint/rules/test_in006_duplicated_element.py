"""
IN006 duplicated-element: which element the engines read, what the finding says, its fix, and
that inertia-kit itself reads and edits the element the engines read.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner
from kit.moments import box_moments

from inertia_kit.cli import lint_main
from inertia_kit.cli.fill import fill_command
from inertia_kit.description.edits import apply_edits
from inertia_kit.description.loader import load
from inertia_kit.lint.findings import Severity

HEAD = (
    '<robot name="r"><link name="world"/>'
    '<joint name="j" type="revolute"><parent link="world"/><child link="arm"/>'
    '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>\n'
    '<link name="arm">\n'
)
SIZE = (0.1, 0.2, 0.3)
BOX = f'<collision><geometry><box size="{" ".join(map(str, SIZE))}"/></geometry></collision>\n'


def tensor(mass: float) -> str:
    ixx, iyy, izz = box_moments(mass, SIZE)
    return f'<inertia ixx="{ixx}" ixy="0" ixz="0" iyy="{iyy}" iyz="0" izz="{izz}"/>'


def inertial(mass: float) -> str:
    """The box's own values for ``mass``: every rule but IN006 is quiet about it."""
    return f'<inertial><mass value="{mass}"/>{tensor(mass)}</inertial>\n'


def robot(body: str) -> str:
    return HEAD + body + "</link></robot>\n"


def in006(lint, text):
    return [f for f in lint(text, ("IN0",)) if f.code == "IN006"]


def write(tmp_path: Path, text: str, name: str = "robot.urdf") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def test_a_single_of_each_is_quiet(lint):
    assert lint(robot(inertial(3.0) + BOX), ("IN0",)) == []


def test_a_second_inertial_that_differs_is_an_error_naming_both_and_the_values(lint, tmp_path):
    text = robot(inertial(3.0) + inertial(30.0) + BOX)
    (finding,) = in006(lint, text)
    assert finding.severity == Severity.ERROR
    assert finding.line == 4  # on the ignored one
    assert finding.message == (
        "link `arm`: second `<inertial>` (line 4) ignored, they differ: mass 3.0 vs 30.0 (+3 more)"
    )
    assert "read line 3" in finding.detail and "MuJoCo refuses the file" in finding.detail
    # every difference is in the detail and the help, the message shows one and counts the rest
    for name in ("ixx", "iyy", "izz"):
        assert f"inertia {name} " in finding.help and f"inertia {name} " in finding.detail
    assert finding.fix is None  # which one is right is the author's call
    # inertia-kit reads the first, as the engines do, and every other rule judges that one
    (link,) = [link for link in load(write(tmp_path, text)).links if link.name == "arm"]
    assert link.inertial.mass == 3.0
    assert [(d.tag, d.parent, d.read.line, d.ignored.line) for d in link.duplicates] == [
        ("inertial", "link", 3, 4)
    ]


@pytest.mark.parametrize(
    ("inside", "tag", "difference"),
    [
        ('<mass value="3"/><mass value="5"/>' + tensor(3.0), "mass", "mass 3 vs 5"),
        ('<mass value="3"/>' + tensor(3.0) + tensor(5.0), "inertia", "ixx 0.0325 vs"),
        (
            '<origin xyz="0 0 0"/><origin xyz="0 0 0.1"/><mass value="3"/>' + tensor(3.0),
            "origin",
            "xyz 0 0 0 vs 0 0 0.1",
        ),
    ],
)
def test_a_second_element_inside_the_inertial(lint, tmp_path, inside, tag, difference):
    text = robot(f"<inertial>{inside}</inertial>\n" + BOX)
    (finding,) = in006(lint, text)
    assert finding.severity == Severity.ERROR
    assert f"second `<{tag}>` in `<inertial>`" in finding.message
    assert difference in finding.message
    loaded = load(write(tmp_path, text)).link("arm").inertial
    assert loaded.mass == 3.0 and loaded.ixx == pytest.approx(box_moments(3.0, SIZE)[0])
    assert loaded.origin.xyz == (0.0, 0.0, 0.0)


def test_identical_duplicates_are_a_warning_with_a_safe_fix(lint):
    text = robot(inertial(3.0) + "  " + inertial(3.0) + BOX)
    (finding,) = in006(lint, text)
    assert finding.severity == Severity.WARNING
    assert "the same values" in finding.message
    assert finding.fix is not None and finding.fix.safety.value == "safe"
    fixed, applied = apply_edits(text, finding.fix.edits)
    assert len(applied) == 1
    assert fixed == robot(inertial(3.0) + BOX)  # the line of the ignored one is gone
    assert lint(fixed, ("IN0",)) == []


def test_numbers_are_compared_by_value_the_fix_needs_the_same_text(lint):
    second = inertial(3.0).replace('value="3.0"', 'value="3"')
    (finding,) = in006(lint, robot(inertial(3.0) + second + BOX))
    assert finding.severity == Severity.WARNING and "the same values" in finding.message
    assert finding.fix is None


def test_the_fix_removes_an_inline_duplicate_alone(lint, tmp_path):
    text = robot(inertial(3.0).rstrip("\n") + " " + inertial(3.0) + BOX)
    (finding,) = in006(lint, text)
    fixed, _ = apply_edits(text, finding.fix.edits)
    assert fixed == robot(inertial(3.0).rstrip("\n") + " \n" + BOX)


def test_lint_fix_applies_it_and_a_second_run_changes_nothing(tmp_path):
    path = write(tmp_path, robot(inertial(3.0) + inertial(3.0) + BOX))
    result = CliRunner().invoke(lint_main, ["--select", "IN006", "--fix", str(path)])
    assert result.exit_code == 0, result.output
    assert path.read_text() == robot(inertial(3.0) + BOX)
    again = CliRunner().invoke(lint_main, ["--select", "IN006", "--fix", str(path)])
    assert again.exit_code == 0 and path.read_text() == robot(inertial(3.0) + BOX)


def test_two_shapes_in_a_geometry_the_first_is_read(lint, tmp_path):
    text = robot(
        inertial(3.0)
        + f'<collision><geometry><box size="{" ".join(map(str, SIZE))}"/>'
        + '<sphere radius="0.5"/></geometry></collision>\n'
    )
    (finding,) = in006(lint, text)
    assert finding.severity == Severity.ERROR
    assert "second shape `<sphere>` in `<geometry>`" in finding.message
    assert "shape box vs sphere" in finding.message
    assert "MuJoCo refuses" not in finding.detail  # it reads the first shape too
    (shape,) = load(write(tmp_path, text)).link("arm").collisions
    assert type(shape.geometry).__name__ == "Box"


def test_a_second_origin_in_a_collision_is_an_error_in_a_visual_a_warning(lint):
    shape = '<{0}><origin xyz="0 0 0"/><origin xyz="0 0 1"/><geometry><box size="0.1 0.2 0.3"/>'
    collision = in006(
        lint, robot(inertial(3.0) + shape.format("collision") + "</geometry></collision>\n")
    )
    visual = in006(
        lint, robot(inertial(3.0) + BOX + shape.format("visual") + "</geometry></visual>\n")
    )
    assert [f.severity for f in collision] == [Severity.ERROR]
    assert [f.severity for f in visual] == [Severity.WARNING]
    assert "MuJoCo refuses" not in visual[0].detail  # its URDF import drops visuals


def test_a_second_shape_in_a_visual_is_a_warning_and_a_material_there_no_shape(lint):
    visual = '<visual><geometry><box size="0.1 0.2 0.3"/>{}</geometry></visual>\n'
    (finding,) = in006(lint, robot(inertial(3.0) + BOX + visual.format('<sphere radius="1"/>')))
    assert finding.severity == Severity.WARNING
    # pybullet_data's racecar writes <material> inside a visual's <geometry>
    assert in006(lint, robot(inertial(3.0) + BOX + visual.format('<material name="g"/>'))) == []


def test_several_visuals_and_collisions_are_allowed(lint):
    assert in006(lint, robot(inertial(3.0) + BOX + BOX)) == []


def test_a_duplicate_with_unreadable_values_does_not_crash(lint):
    text = robot(
        '<inertial><mass value="abc"/><mass/><inertia ixx="nan"/><inertia/></inertial>\n' + BOX
    )
    findings = in006(lint, text)
    assert [f.message.split("`")[3] for f in findings] == ["<mass>", "<inertia>"]
    assert "mass abc vs absent" in findings[0].message


XACRO = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="arm_link" params="name mass">
    <link name="${name}">
      <inertial>
        <mass value="${mass}"/>
        <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.3"/>
      </inertial>
      <inertial>
        <mass value="2"/>
        <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.3"/>
      </inertial>
    </link>
  </xacro:macro>
  <link name="world"/>
  <joint name="j" type="fixed"><parent link="world"/><child link="a"/></joint>
  <xacro:arm_link name="a" mass="2"/>
  <joint name="k" type="fixed"><parent link="a"/><child link="b"/></joint>
  <xacro:arm_link name="b" mass="3"/>
</robot>
"""


def test_xacro_a_duplicate_from_a_macro_points_at_its_line_in_the_body(tmp_path):
    path = write(tmp_path, XACRO, "r.urdf.xacro")
    result = CliRunner().invoke(
        lint_main, ["--select", "IN006", "--output-format", "json", str(path)]
    )
    findings = json.loads(result.stdout)
    by_link = {f["link"]: f for f in findings}
    # the same macro body agrees with itself for one call, not for the other
    assert by_link["a"]["severity"] == "warning" and by_link["b"]["severity"] == "error"
    assert "mass 3 vs 2" in by_link["b"]["message"]
    for link, call in (("a", 17), ("b", 19)):
        assert by_link[link]["line"] == call
        assert "second `<inertial>` (line 9)" in by_link[link]["message"]
        assert "read line 5" in by_link[link]["detail"]
        # no removal inside a macro body: it would drop b's element too
        assert by_link[link]["fix"] is None


def test_fill_edits_the_inertial_the_engines_read(tmp_path):
    ignored = inertial(7.0)
    # no izz: inertia-fill --fix invalid completes it
    incomplete = inertial(3.0).replace(' izz="', ' zz="')
    path = write(tmp_path, robot(incomplete + ignored + BOX))
    result = CliRunner().invoke(fill_command, ["--fix", "invalid", str(path)])
    assert result.exit_code == 1, result.output
    text = path.read_text()
    assert ignored in text  # untouched
    first = load(path).link("arm").inertial
    *_, izz = box_moments(3.0, SIZE)
    assert first.mass == 3.0 and first.izz == pytest.approx(izz, rel=1e-5)


# --- the engines themselves ------------------------------------------------------------------

CASES = {
    "inertial": inertial(3.0) + inertial(30.0) + BOX,
    "mass": f'<inertial><mass value="3"/><mass value="30"/>{tensor(3.0)}</inertial>\n' + BOX,
    "inertia": f'<inertial><mass value="3"/>{tensor(3.0)}{tensor(30.0)}</inertial>\n' + BOX,
    "origin": f'<inertial><origin xyz="0 0 0"/><origin xyz="0 0 0.1"/><mass value="3"/>'
    f"{tensor(3.0)}</inertial>\n" + BOX,
}


@pytest.mark.parametrize("tag", sorted(CASES))
def test_mujoco_refuses_a_repeated_element_as_in070_predicts(tag, tmp_path):
    mujoco = pytest.importorskip("mujoco")
    path = write(tmp_path, robot(CASES[tag]))
    with pytest.raises(ValueError, match=f"repeated element: '{tag}'"):
        mujoco.MjModel.from_xml_path(str(path))
    result = CliRunner().invoke(
        lint_main,
        ["--engine", "mujoco", "--select", "IN070", "--output-format", "json", str(path)],
    )
    (finding,) = json.loads(result.stdout)
    assert finding["expected"]["engine_message"] == f"repeated element: '{tag}'"
    assert f"a second <{tag}>" in finding["message"]
    assert f"repeated element: '{tag}'" in finding["detail"]


@pytest.mark.parametrize("tag", sorted(CASES))
def test_drake_reads_the_first_as_inertia_kit_does(tag, tmp_path):
    pytest.importorskip("pydrake")
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant

    path = write(tmp_path, robot(CASES[tag]))
    plant = MultibodyPlant(0.0)
    Parser(plant).AddModels(str(path))
    plant.Finalize()
    body = plant.GetBodyByName("arm").default_spatial_inertia()
    ours = load(path).link("arm").inertial
    assert body.get_mass() == ours.mass == 3.0
    assert tuple(body.get_com()) == pytest.approx(ours.origin.xyz)
    about_com = body.Shift(body.get_com()).CalcRotationalInertia().get_moments()
    assert tuple(about_com) == pytest.approx((ours.ixx, ours.iyy, ours.izz))


CALLED_TWICE = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="box_inertial" params="m">
    <inertial>
      <mass value="${m}"/>
      <inertia ixx="${m*0.01}" ixy="0" ixz="0" iyy="${m*0.01}" iyz="0" izz="${m*0.01}"/>
    </inertial>
  </xacro:macro>
  <link name="a">
    <xacro:box_inertial m="2"/>
    <xacro:box_inertial m="4"/>
  </link>
</robot>
"""


def test_xacro_one_macro_line_made_both_the_calls_are_named(tmp_path):
    path = write(tmp_path, CALLED_TWICE, "m.urdf.xacro")
    result = CliRunner().invoke(
        lint_main, ["--select", "IN006", "--output-format", "json", str(path)]
    )
    (finding,) = json.loads(result.stdout)
    assert finding["line"] == 11
    assert "second `<inertial>` (line 11)" in finding["message"]
    assert "read line 10" in finding["detail"] and "mass 2 vs 4" in finding["message"]


def test_xacro_no_removal_when_one_is_in_a_condition_the_other_is_not(tmp_path):
    block = inertial(3.0)
    text = (
        '<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '<xacro:arg name="light" default="true"/>\n<link name="arm">\n'
        f'<xacro:if value="$(arg light)">{block}</xacro:if>\n{block}{BOX}</link>\n</robot>\n'
    )
    path = write(tmp_path, text, "c.urdf.xacro")
    result = CliRunner().invoke(
        lint_main, ["--select", "IN006", "--output-format", "json", str(path)]
    )
    (finding,) = json.loads(result.stdout)
    assert finding["severity"] == "warning"
    # with light:=false the second is the only <inertial>: removing it would lose it
    assert finding["fix"] is None
    # written side by side in the same element, the second goes
    plain = text.replace('<xacro:if value="$(arg light)">', "").replace("</xacro:if>", "")
    path.write_text(plain)
    result = CliRunner().invoke(
        lint_main, ["--select", "IN006", "--output-format", "json", str(path)]
    )
    (finding,) = json.loads(result.stdout)
    assert finding["fix"]["safety"] == "safe"


def test_the_message_is_one_short_line_and_the_detail_has_the_basis(lint):
    (finding,) = in006(lint, robot(inertial(3.0) + inertial(30.0) + BOX))
    assert len(finding.message) <= 100
    assert finding.detail.startswith(
        "the second `<inertial>` (line 4) is ignored, urdfdom, Drake and PyBullet read line 3, "
        "MuJoCo refuses the file: they differ: mass 3.0 vs 30.0, inertia ixx "
    )
