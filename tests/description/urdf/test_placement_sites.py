"""
inertia-fill on xacro sources: a table of (files, options, exit code, expected files), run through
the CLI. Each case says where the values must go: the literal link, the macro body (used once, or
identical copies), the macro call's parameters, the macro call that makes only the <inertial>;
or a refusal that names the macro and prints the block. Numbers come from closed forms.
"""

from __future__ import annotations

import math
import shutil
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from click.testing import CliRunner
from kit import REPO
from kit.moments import solid_box, solid_cylinder
from kit.urdf import filled_inertial, joint

from inertia_kit.cli.fill import fill_command
from inertia_kit.errors import InputError
from inertia_kit.fill.plan import apply, plan_fill
from inertia_kit.lint.runner import Selection, lint_file
from inertia_kit.physics.formatting import xml_number

EXAMPLES = REPO / "examples"
XACRO = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
CHECKED = ("IN001", "IN002", "IN003", "IN010", "IN011", "IN020", "IN022", "IN023")


def n(value: float) -> str:
    return xml_number(value, 6)


@dataclass(frozen=True)
class Case:
    id: str
    files: dict[str, str]  # name -> text; the first is the one filled
    args: tuple[str, ...] = ()
    exit: int = 1
    expected: dict[str, str] = field(default_factory=dict)  # name -> text; others unchanged
    stderr: tuple[str, ...] = ()  # phrases stderr must hold


# --- a macro used once: its body is filled ------------------------------------------------------
ONCE = f"""<robot name="r" {XACRO}>
  <xacro:macro name="part" params="name size">
    <link name="${{name}}">
      <collision><geometry><box size="${{size}}"/></geometry></collision>
    </link>
  </xacro:macro>
  <link name="base"/>
  <xacro:part name="arm" size="0.1 0.2 0.4"/>
  {joint("base", "arm")}
</robot>
"""
ONCE_FILLED = ONCE.replace(
    '    <link name="${name}">\n',
    '    <link name="${name}">\n'
    + filled_inertial(solid_box((0.1, 0.2, 0.4), density=1000), indent="      ")
    + "\n",
)

# --- a macro used twice for identical links: its body is filled once -------------------------
TWINS = f"""<robot name="r" {XACRO}>
  <xacro:macro name="wheel" params="side">
    <link name="${{side}}_wheel">
      <collision><geometry><cylinder radius="0.1" length="0.05"/></geometry></collision>
      <inertial>
        <mass value="2"/>
        <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
      </inertial>
    </link>
    {joint("base", "${side}_wheel")}
  </xacro:macro>
  <link name="base"/>
  <xacro:wheel side="left"/>
  <xacro:wheel side="right"/>
</robot>
"""
_TWIN = solid_cylinder(0.1, 0.05, mass=2.0)
# only the values that change: the kept mass and the products stay as written
TWINS_FILLED = TWINS.replace(
    '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>',
    f'<inertia ixx="{n(_TWIN[1])}" ixy="0" ixz="0" iyy="{n(_TWIN[2])}" iyz="0" '
    f'izz="{n(_TWIN[3])}"/>',
)

# --- a macro used with different values that takes them as parameters: the calls change ------
PARAMS = f"""<robot name="r" {XACRO}>
  <xacro:macro name="rod" params="name length mass ixx iyy izz:=0">
    <link name="${{name}}">
      <inertial>
        <origin xyz="0 0 0"/>
        <mass value="${{mass}}"/>
        <inertia ixx="${{ixx}}" ixy="0" ixz="0" iyy="${{iyy}}" iyz="0" izz="${{izz}}"/>
      </inertial>
      <collision><geometry><cylinder radius="0.05" length="${{length}}"/></geometry></collision>
    </link>
  </xacro:macro>
  <link name="base"/>
  <xacro:rod name="short" length="0.2" mass="1.5"
             ixx="1" iyy='1' />
  <xacro:rod name="long" length="0.8" mass="3" ixx="2" iyy="2" izz="0.5"/>
  {joint("base", "short")}
  {joint("base", "long")}
</robot>
"""
_S = solid_cylinder(0.05, 0.2, mass=1.5)
_L = solid_cylinder(0.05, 0.8, mass=3.0)
PARAMS_FILLED = PARAMS.replace(
    """name="short" length="0.2" mass="1.5"
             ixx="1" iyy='1' />""",
    f"""name="short" length="0.2" mass="1.5"
             ixx="{n(_S[1])}" iyy='{n(_S[2])}' izz="{n(_S[3])}" />""",
).replace(
    'mass="3" ixx="2" iyy="2" izz="0.5"',
    f'mass="3" ixx="{n(_L[1])}" iyy="{n(_L[2])}" izz="{n(_L[3])}"',
)

# --- a call that makes only the <inertial> (an inertia macro inside a literal link) ----------
INERTIA_MACRO = f"""<robot name="r" {XACRO}>
  <xacro:macro name="placeholder_inertial" params="mass">
    <inertial>
      <mass value="${{mass}}"/>
      <inertia ixx="1.0" ixy="0" ixz="0" iyy="1.0" iyz="0" izz="1.0"/>
    </inertial>
  </xacro:macro>
  <link name="base"/>
  <link name="arm">
    <collision><origin xyz="0 0 0.2"/><geometry><box size="0.1 0.1 0.4"/></geometry></collision>
    <xacro:placeholder_inertial mass="2"/>
  </link>
  <link name="hand">
    <collision><geometry><sphere radius="0.05"/></geometry></collision>
    <xacro:placeholder_inertial mass="0.5"/>
  </link>
  {joint("base", "arm")}
  {joint("arm", "hand")}
</robot>
"""
_HAND = (0.5, 0.4 * 0.5 * 0.05**2, 0.4 * 0.5 * 0.05**2, 0.4 * 0.5 * 0.05**2)
INERTIA_MACRO_FILLED = INERTIA_MACRO.replace(
    '<xacro:placeholder_inertial mass="2"/>',
    filled_inertial(
        solid_box((0.1, 0.1, 0.4), mass=2.0), com=(0, 0, 0.2), indent="    ", first=False
    ),
).replace(
    '<xacro:placeholder_inertial mass="0.5"/>', filled_inertial(_HAND, indent="    ", first=False)
)

# --- refusals: shared bodies with different values and no parameters to carry them -----------
SHARED = f"""<robot name="r" {XACRO}>
  <xacro:macro name="part" params="name size">
    <link name="${{name}}">
      <collision><geometry><box size="${{size}}"/></geometry></collision>
      <inertial>
        <mass value="1"/>
        <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
      </inertial>
    </link>
  </xacro:macro>
  <link name="base"/>
  <xacro:part name="a" size="0.1 0.1 0.1"/>
  <xacro:part name="b" size="0.1 0.2 0.4"/>
  {joint("base", "a")}
  {joint("base", "b")}
</robot>
"""
SHARED_MISSING = SHARED.replace(
    SHARED[SHARED.index("      <inertial>") : SHARED.index("</inertial>") + 12], ""
)

# the centre of mass comes from a parameter that also places the collision
COM_PARAMETER = f"""<robot name="r" {XACRO}>
  <xacro:macro name="part" params="name xyz mass ixx iyy izz">
    <link name="${{name}}">
      <collision><origin xyz="${{xyz}}"/><geometry><sphere radius="0.1"/></geometry></collision>
      <collision><geometry><sphere radius="0.1"/></geometry></collision>
      <inertial>
        <origin xyz="${{xyz}}"/>
        <mass value="${{mass}}"/>
        <inertia ixx="${{ixx}}" ixy="0" ixz="0" iyy="${{iyy}}" iyz="0" izz="${{izz}}"/>
      </inertial>
    </link>
  </xacro:macro>
  <link name="base"/>
  <xacro:part name="a" xyz="0 0 0.5" mass="1" ixx="1" iyy="1" izz="1"/>
  <xacro:part name="b" xyz="0 0 0.6" mass="1" ixx="1" iyy="1" izz="1"/>
  {joint("base", "a")}
  {joint("base", "b")}
</robot>
"""

# a call passing an expression for a value that must change: it becomes the number, and the
# message says the link is no longer parametric
EXPRESSION = PARAMS.replace('ixx="2" iyy="2" izz="0.5"', 'ixx="${2*1}" iyy="2" izz="0.5"')

CASES = [
    Case("macro-used-once", {"robot.xacro": ONCE}, (), 1, {"robot.xacro": ONCE_FILLED}),
    Case(
        "identical-copies-share-one-edit",
        {"robot.xacro": TWINS},
        ("--fix", "invalid"),
        1,
        {"robot.xacro": TWINS_FILLED},
    ),
    Case(
        "macro-parameters-at-each-call",
        {"robot.xacro": PARAMS},
        ("--fix", "all"),
        1,
        {"robot.xacro": PARAMS_FILLED},
        ("Filled 2 links",),
    ),
    Case(
        "inertia-macro-call-replaced",
        {"robot.xacro": INERTIA_MACRO},
        ("--fix", "invalid"),
        1,
        {"robot.xacro": INERTIA_MACRO_FILLED},
    ),
    Case(
        "shared-body-different-values-refused",
        {"robot.xacro": SHARED},
        ("--fix", "all"),
        1,
        {},
        (
            'link `a` not filled: its ixx is written "1" once',
            "for 2 links (`a`, `b`) that need different values",
            "give macro `part` a parameter for each value that differs (ixx, iyy, izz) and pass "
            "each link's own at its call: at this link's call, ",
            f'robot.xacro:13, ixx="{n(solid_box((0.1, 0.2, 0.4), mass=1.0)[1])}" iyy=',
            f'<mass value="{n(1.0)}"/>',
            f'ixx="{n(solid_box((0.1, 0.2, 0.4), mass=1.0)[1])}"',
        ),
    ),
    Case(
        "shared-link-without-inertial-refused",
        {"robot.xacro": SHARED_MISSING},
        (),
        1,
        {},
        ("link `b` not filled: its <link> is written once", "<inertial>"),
    ),
    Case(
        "com-parameter-used-for-the-collision-refused",
        {"robot.xacro": COM_PARAMETER},
        ("--fix", "all"),
        1,
        {},
        (
            'its xyz is written "${xyz}" once',
            "(parameter `xyz` of `part` is used for more than the <inertial>)",
        ),
    ),
    Case(
        "expression-argument-becomes-a-number-and-is-reported",
        {"robot.xacro": EXPRESSION},
        ("--fix", "all"),
        1,
        {"robot.xacro": PARAMS_FILLED},
        (
            f"link `long` is no longer parametric: its ixx is written as {n(_L[1])} (",
            'where "${2*1}" was',
        ),
    ),
]


def write(files: dict[str, str], folder: Path) -> Path:
    for name, text in files.items():
        (folder / name).write_bytes(text.encode())
    return folder / next(iter(files))


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_fill_xacro_table(case: Case, tmp_path: Path):
    path = write(case.files, tmp_path)
    result = CliRunner().invoke(fill_command, [*case.args, str(path)])
    assert result.exception is None or isinstance(result.exception, SystemExit), result.output
    assert result.exit_code == case.exit, result.stderr
    for phrase in case.stderr:
        assert phrase in result.stderr, result.stderr
    for name, text in case.files.items():
        assert (tmp_path / name).read_text() == case.expected.get(name, text), name
    if case.expected:
        assert_second_run_quiet(path, case.args)


def assert_second_run_quiet(path: Path, args: tuple[str, ...]):
    """A second run changes no byte, and the links filled pass the rules fill answers to."""
    again = CliRunner().invoke(fill_command, ["--check", *args, str(path)])
    if again.exit_code != 0:
        assert "not filled" in again.stderr and "Would fill" not in again.stderr, again.stderr
    assert_filled_links_pass(path)


def assert_filled_links_pass(path: Path):
    """No finding of the rules fill answers to (IN020 warnings aside) on a link with geometry."""
    filled = {f.link for f in plan_fill(path, fix="all").fills}
    findings = lint_file(path, Selection(select=CHECKED)).findings
    bad = [
        (f.code, f.link, f.message)
        for f in findings
        if f.link in filled and (f.code != "IN020" or f.severity.name == "ERROR")
    ]
    assert bad == []


# --- the seed robots ---------------------------------------------------------------------------


def copy_example(name: str, tmp_path: Path) -> Path:
    target = tmp_path / name
    shutil.copytree(EXAMPLES / name, target)
    return target


def snapshot(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in folder.rglob("*") if p.is_file()}


def test_seed_wheeled_robot_base_is_filled_in_its_macro_body(tmp_path: Path):
    """robot.xacro calls the base_link macro (base.xacro) once: its body gets the block."""
    folder = copy_example("my_robot_description", tmp_path)
    before = snapshot(folder)
    path = folder / "urdf" / "robot.xacro"
    result = CliRunner().invoke(fill_command, [str(path)])
    assert result.exit_code == 1, result.stderr
    assert "Filled 1 link" in result.stderr and "base_link 16 kg" in result.stderr
    after = snapshot(folder)
    changed = {name for name in after if after[name] != before[name]}
    assert changed == {"urdf/base.xacro"}
    # robot.xacro sets base_size to 0.4 0.4 0.1; the box sits on z = 0.05
    values = solid_box((0.4, 0.4, 0.1), density=1000)
    base = before["urdf/base.xacro"].decode()
    expected = base.replace(
        '    <link name="base_link">\n',
        '    <link name="base_link">\n'
        + filled_inertial(values, com=(0, 0, 0.05), indent="      ")
        + "\n",
    )
    assert after["urdf/base.xacro"].decode() == expected
    assert CliRunner().invoke(fill_command, [str(path)]).exit_code == 0
    assert snapshot(folder) == after


def test_seed_wheeled_robot_fill_all(tmp_path: Path):
    """--fix all: the two wheels share one edit of the wheel macro; the lidar macro (used
    once) gets a block from its visual cylinder; the base frame without geometry is left."""
    folder = copy_example("my_robot_description", tmp_path)
    before = snapshot(folder)
    path = folder / "urdf" / "robot.xacro"
    result = CliRunner().invoke(fill_command, ["--fix", "all", str(path)])
    assert result.exit_code == 1, result.stderr
    after = snapshot(folder)
    changed = {name for name in after if after[name] != before[name]}
    # the lidar, a visual-only part welded to the base, is a helper link: not given mass
    assert changed == {"urdf/base.xacro", "urdf/wheels.xacro"}
    # the wheel's values (as its author wrote them: tests/fixes/test_xacro_native.py)
    assert after["urdf/wheels.xacro"].count(b"<inertial>") == 2  # mul_wheel's and wheel's
    assert "base_footprint" not in result.stderr
    assert CliRunner().invoke(fill_command, ["--fix", "all", str(path)]).exit_code == 0
    assert snapshot(folder) == after
    # asked by name, it is filled where its macro writes it
    named = CliRunner().invoke(fill_command, ["--fix", "all", "--link", "lidar_link", str(path)])
    assert named.exit_code == 1, named.stderr
    lidar = solid_cylinder(0.03, 0.02, density=1000)
    assert (
        filled_inertial(lidar, com=(0, 0, 0.01), indent="      ")
        in (folder / "urdf" / "sensors.xacro").read_text()
    )


def test_seed_mrm_arm_fill_all_edits_the_call_parameters(tmp_path: Path):
    """mrm.xacro passes mass and ixx..izz to m_link_cylinder at five calls: those numbers
    change to each cylinder's tensor about its COM (1024 kg/m³: the declared masses are the
    cylinders' own); links_joints.xacro is not touched; the base box is already right."""
    folder = copy_example("mrm_description", tmp_path)
    before = snapshot(folder)
    path = folder / "urdf" / "mrm.xacro"
    result = CliRunner().invoke(fill_command, ["--fix", "all", "--density", "1024", str(path)])
    assert result.exit_code == 1, result.stderr
    after = snapshot(folder)
    assert {name for name in after if after[name] != before[name]} == {"urdf/mrm.xacro"}
    text = after["urdf/mrm.xacro"].decode()
    for radius, length, mass in [(0.35, 0.4, 157.633), (0.15, 0.8, 57.906), (0.15, 0.25, 18.056)]:
        # the CAD masses are 1024 kg/m³ × the cylinder's volume to 0.3 % (kept as declared)
        assert math.isclose(mass, 1024 * math.pi * radius**2 * length, rel_tol=3e-3)
        _, side, _, axial = solid_cylinder(radius, length, mass=mass)
        assert f'ixx="{n(side)}" ixy="0" ixz="0"\n' in text
        assert f'iyy="{n(side)}" iyz="0"\n              izz="{n(axial)}"' in text
    assert 'ixx="6.92928"' in text  # link_01: 6.929 about its COM (13.235 about its base)
    assert CliRunner().invoke(fill_command, ["--fix", "all", str(path)]).exit_code == 0
    findings = lint_file(path, Selection(select=CHECKED)).findings
    assert [f for f in findings if f.code != "IN020" or f.severity.name == "ERROR"] == []


def test_macro_files_outside_the_package_are_not_edited(tmp_path: Path):
    library = tmp_path / "library"
    library.mkdir()
    (library / "package.xml").write_text("<package><name>library</name></package>")
    (library / "parts.xacro").write_text(
        ONCE[ONCE.index("  <xacro:macro") : ONCE.index("  </xacro:macro>") + 17].join(
            (f"<robot {XACRO}>\n", "</robot>\n")
        )
    )
    robot = tmp_path / "robot"
    robot.mkdir()
    (robot / "package.xml").write_text("<package><name>robot</name></package>")
    path = robot / "robot.xacro"
    path.write_text(
        f'<robot name="r" {XACRO}>\n  <xacro:include filename="../library/parts.xacro"/>\n'
        f'  <link name="base"/>\n  <xacro:part name="arm" size="0.1 0.2 0.4"/>\n'
        f"  {joint('base', 'arm')}\n</robot>\n"
    )
    before = (library / "parts.xacro").read_text()
    result = CliRunner().invoke(fill_command, [str(path)])
    assert result.exit_code == 1
    assert "outside" in result.stderr and "<inertial>" in result.stderr
    assert (library / "parts.xacro").read_text() == before


def test_several_files_are_checked_before_any_is_written(tmp_path: Path):
    """A plan editing two files: the second changed meanwhile, so neither is written."""
    folder = copy_example("my_robot_description", tmp_path)
    path = folder / "urdf" / "robot.xacro"
    plan = plan_fill(path, fix="all", links=["lidar_link"])
    assert len(plan.changes()) == 3
    sensors = folder / "urdf" / "sensors.xacro"
    sensors.write_text(sensors.read_text() + "<!-- edited meanwhile -->\n")
    before = snapshot(folder)
    with pytest.raises(InputError, match="changed while"):
        apply(plan)
    assert snapshot(folder) == before


ROBOTS = [
    "mrm_description/urdf/mrm.xacro",
    "my_robot_description/urdf/robot.xacro",
    "my_robot_description/urdf/robot.urdf",
    "pan_tilt_description/urdf/pan_tilt.urdf",
    "robot1/urdf/robot1_base.xacro",
    "simple_arm/urdf/simple_arm.urdf.xacro",
]


@pytest.mark.parametrize("robot", ROBOTS)
def test_every_example_after_fix_invalid(robot: str, tmp_path: Path):
    """The issue's acceptance: after --fix invalid the filled links pass IN001/002/003/010/011/
    020 (error)/022/023, and a second run exits 0 and changes no byte."""
    package = robot.split("/")[0]
    folder = copy_example(package, tmp_path)
    path = folder / robot.split("/", 1)[1]
    first = CliRunner().invoke(fill_command, ["--fix", "invalid", str(path)])
    assert first.exit_code in (0, 1), first.stderr
    assert "not filled" not in first.stderr, first.stderr
    after = snapshot(folder)
    second = CliRunner().invoke(fill_command, ["--fix", "invalid", str(path)])
    nothing = "inertia-fill: 1 file checked, nothing to change\n"
    assert (second.exit_code, second.stderr) == (0, nothing), second.stderr
    assert snapshot(folder) == after
    assert_filled_links_pass(path)


def test_readme_shows_the_real_mrm_run(monkeypatch):
    """docs/fill.md's mrm run is what the command prints (its '...' stands for two hunks)."""
    readme = (EXAMPLES.parent / "docs" / "fill.md").read_text()
    command = "$ inertia-fill --fix all --density 1024 --diff mrm_description/urdf/mrm.xacro\n"
    shown = readme[readme.index(command) + len(command) :]
    shown = shown[: shown.index("```")]
    monkeypatch.chdir(EXAMPLES)
    result = CliRunner().invoke(fill_command, command.split()[2:])
    assert result.exit_code == 1, result.stderr
    printed = result.stdout + result.stderr
    for part in shown.split("...\n"):
        assert part in printed
