"""
inertia-fill: one table of (input bytes, options, exit code, expected bytes), run through the API
and through the CLI. Expected numbers come from closed forms (solid box and cylinder), written
with six significant digits as the file format says.
"""

from __future__ import annotations

import os
import stat
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from click.testing import CliRunner
from kit import REPO
from kit.moments import solid_box, solid_cylinder, solid_sphere
from kit.urdf import filled_inertial, joint

from inertia_kit.cli import fill_command
from inertia_kit.fill.plan import MATERIALS, apply, plan_fill
from inertia_kit.lint.runner import Selection, lint_file
from inertia_kit.physics.formatting import xml_number

# --- robots ------------------------------------------------------------------------------------

ARM = """<?xml version="1.0"?>
<!-- an arm: comments, odd spacing and both quote styles stay as they are -->
<robot   name='arm'>
  <link name="base"/>
  {joint}
  <!-- the upper arm -->
  <link
      name='upper'  >
    <collision>
      <origin xyz="0 0 0.2"/>   <!-- raised -->
      <geometry><box size='0.1 0.1 0.4'/></geometry>
    </collision>
  </link>
</robot>
""".replace("{joint}", joint("base", "upper"))

ARM_FILLED = ARM.replace(
    "name='upper'  >\n",
    "name='upper'  >\n"
    + filled_inertial(solid_box((0.1, 0.1, 0.4), density=1000), com=(0, 0, 0.2), indent="    ")
    + "\n",
)

CRLF_TABS = (
    '<robot name="r">\r\n\t<link name="base"/>\r\n\t'
    + joint("base", "wheel", "continuous")
    + '\r\n\t<link name="wheel">\r\n\t\t<collision>\r\n\t\t\t<geometry>'
    '<cylinder radius="0.1" length="0.05"/></geometry>\r\n\t\t</collision>\r\n\t</link>\r\n'
    "</robot>\r\n"
)


def crlf_filled(values):
    return CRLF_TABS.replace(
        '<link name="wheel">\r\n',
        '<link name="wheel">\r\n'
        + filled_inertial(values, indent="\t\t", unit="\t", nl="\r\n")
        + "\r\n",
    )


CROSS = """<robot name="r">
    <link name="base"/>
    {joint}
    <link name="cross">
        <collision><geometry><box size="0.2 0.1 0.1"/></geometry></collision>
        <collision><geometry><box size="0.1 0.2 0.1"/></geometry></collision>
    </link>
</robot>
""".replace("{joint}", joint("base", "cross"))


def cross_values(density):
    """Two boxes overlapping in a 0.1 m cube: inclusion-exclusion of three boxes."""
    a = solid_box((0.2, 0.1, 0.1), density=density)
    b = solid_box((0.1, 0.2, 0.1), density=density)
    c = solid_box((0.1, 0.1, 0.1), density=density)
    return tuple(x + y - z for x, y, z in zip(a, b, c, strict=True))


IMPOSSIBLE = """<robot name="r">
  <link name="base"/>
  {joint}
  <link name="body">
    <!-- measured on the scale -->
    <inertial>
      <origin xyz="0.5 0 0"/>
      <mass value="3"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="5"/>
    </inertial>
    <collision>
      <origin xyz="0 0 0.1"/>
      <geometry><box size="0.3 0.2 0.1"/></geometry>
    </collision>
  </link>
</robot>
""".replace("{joint}", joint("base", "body"))
IMPOSSIBLE_OLD = IMPOSSIBLE[IMPOSSIBLE.index("<inertial>") : IMPOSSIBLE.index("</inertial>") + 11]
IMPOSSIBLE_FIXED = IMPOSSIBLE.replace(
    IMPOSSIBLE_OLD,
    filled_inertial(
        solid_box((0.3, 0.2, 0.1), mass=3.0), com=(0, 0, 0.1), indent="    ", first=False
    ),
)

MISSING_MESH = """<robot name="r">
  <link name="base"/>
  {j1}
  <link name="shell">
    <collision><geometry><mesh filename="meshes/nowhere.stl"/></geometry></collision>
  </link>
  {j2}
  <link name="rod">
    <collision><geometry><cylinder radius="0.02" length="0.5"/></geometry></collision>
  </link>
</robot>
""".format(j1=joint("base", "shell"), j2=joint("base", "rod"))
MISSING_MESH_FILLED = MISSING_MESH.replace(
    '<link name="rod">\n',
    '<link name="rod">\n'
    + filled_inertial(solid_cylinder(0.02, 0.5, density=1000), indent="    ")
    + "\n",
)

# a massless frame and a fixed visual-only part: --fix missing leaves both alone
FRAMES = """<robot name="r">
  <link name="base">
    <inertial><mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <visual><geometry><box size="0.2 0.2 0.2"/></geometry></visual>
  </link>
  {j1}
  <link name="tool_frame"/>
  {j2}
  <link name="badge">
    <visual><geometry><box size="0.05 0.02 0.01"/></geometry></visual>
  </link>
</robot>
""".format(j1=joint("base", "tool_frame", "fixed"), j2=joint("base", "badge", "fixed"))
FRAMES_ALL = FRAMES.replace(
    '<link name="badge">\n',
    '<link name="badge">\n'
    + filled_inertial(solid_box((0.05, 0.02, 0.01), density=1000), indent="    ")
    + "\n",
).replace(
    FRAMES[FRAMES.index("<inertial>") : FRAMES.index("</inertial>") + 11],
    # the declared 2 kg is kept, its tensor recomputed for the 0.2 m cube
    filled_inertial(solid_box((0.2, 0.2, 0.2), mass=2.0), indent="    ", first=False),
)


@dataclass(frozen=True)
class Case:
    id: str
    text: str
    args: tuple[str, ...] = ()
    exit: int = 1
    expected: str | None = None  # None: unchanged
    newline: str = field(default="\n")

    @property
    def expected_bytes(self) -> bytes:
        return (self.text if self.expected is None else self.expected).encode()


# a byte-order mark and non-ASCII text before the link on its line: offsets are characters
BOM = (
    "\ufeff<robot name='r'>\n  <link name='base'/>\n  "
    + joint("base", "ärm")
    + "\n  <!-- Oberarm, ä -->  <link name='ärm'>\n"
    "    <visual><geometry><box size='0.1 0.2 0.3'/></geometry></visual>\n"
    "  </link>\n</robot>\n"
)
BOM_FILLED = BOM.replace(
    "<link name='ärm'>\n",
    "<link name='ärm'>\n"
    + filled_inertial(solid_box((0.1, 0.2, 0.3), density=1000), indent="    ")
    + "\n",
)

# the link's content on its start tag's line
ONE_LINE = (
    '<robot name="r">\n  <link name="base"/>\n  '
    + joint("base", "pin")
    + '\n  <link name="pin"><collision><geometry><sphere radius="0.1"/></geometry></collision>'
    "</link>\n</robot>\n"
)


ONE_LINE_FILLED = ONE_LINE.replace(
    '<link name="pin">',
    '<link name="pin">\n'
    + filled_inertial(solid_sphere(0.1, density=1000), indent="    ")
    + "\n  ",
)


CASES = [
    Case("missing-default-density", ARM, (), 1, ARM_FILLED),
    Case("crlf-tabs", CRLF_TABS, (), 1, crlf_filled(solid_cylinder(0.1, 0.05, density=1000))),
    Case(
        "density",
        CRLF_TABS,
        ("--density", "2700"),
        1,
        crlf_filled(solid_cylinder(0.1, 0.05, density=2700)),
    ),
    Case(
        "material",
        CRLF_TABS,
        ("--material", "steel"),
        1,
        crlf_filled(solid_cylinder(0.1, 0.05, density=7850)),
    ),
    Case(
        "mass",
        CRLF_TABS,
        ("--mass", "wheel=1.5"),
        1,
        crlf_filled(solid_cylinder(0.1, 0.05, mass=1.5)),
    ),
    Case(
        "union-of-overlapping-collisions",
        CROSS,
        (),
        1,
        CROSS.replace(
            '<link name="cross">\n',
            '<link name="cross">\n'
            + filled_inertial(cross_values(1000), indent="        ", unit="    ")
            + "\n",
        ),
    ),
    Case("invalid-keeps-mass", IMPOSSIBLE, ("--fix", "invalid"), 1, IMPOSSIBLE_FIXED),
    Case("missing-leaves-declared", IMPOSSIBLE, (), 0, None),
    Case("refuse-missing-mesh-fill-others", MISSING_MESH, (), 1, MISSING_MESH_FILLED),
    Case("frames-left-alone", FRAMES, (), 0, None),
    Case("all", FRAMES, ("--fix", "all"), 1, FRAMES_ALL),
    Case("bom-unicode", BOM, (), 1, BOM_FILLED),
    Case("content-on-the-start-tag-line", ONE_LINE, (), 1, ONE_LINE_FILLED),
    Case("nothing-to-do", ARM_FILLED, (), 0, None),
    Case("all-already-right", ARM_FILLED, ("--fix", "all"), 0, None),
]


def _api(path: Path, args: tuple[str, ...]) -> int:
    """The same options through plan_fill/apply."""
    options: dict = {"masses": {}}
    it = iter(args)
    for arg in it:
        value = next(it)
        if arg == "--density":
            options["density"] = float(value)
        elif arg == "--material":
            options["density"] = MATERIALS[value]
        elif arg == "--mass":
            name, _, kg = value.partition("=")
            options["masses"][name] = float(kg)
        elif arg == "--fix":
            options["fix"] = value
    plan = plan_fill(path, **options)
    apply(plan)
    return 1 if plan.changed or plan.refused else 0


@pytest.mark.parametrize("how", ["api", "cli"])
@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_fill_table(case: Case, how: str, tmp_path: Path):
    path = tmp_path / "robot.urdf"
    path.write_bytes(case.text.encode())
    if how == "api":
        code = _api(path, case.args)
    else:
        result = CliRunner().invoke(fill_command, [*case.args, str(path)])
        assert result.exception is None or isinstance(result.exception, SystemExit), result.output
        code = result.exit_code
    assert code == case.exit
    assert path.read_bytes() == case.expected_bytes
    if case.expected is not None:
        # a second run changes nothing, and the filled file passes the rules fill answers to
        again = plan_fill(path, **({"fix": "all"} if "all" in case.args else {}))
        assert not again.changed
        findings = lint_file(
            path,
            Selection(
                select=("IN001", "IN002", "IN003", "IN010", "IN011", "IN020", "IN022", "IN023")
            ),
        ).findings
        filled = {f.link for f in plan_fill(path, fix="all").fills}
        bad = [
            f
            for f in findings
            if f.link in filled and (f.code != "IN020" or f.severity.name == "ERROR")
        ]
        assert bad == []


def test_report_lines(tmp_path: Path):
    path = tmp_path / "robot.urdf"
    path.write_text(MISSING_MESH)
    result = CliRunner().invoke(fill_command, [str(path)])
    assert result.exit_code == 1
    mass = xml_number(solid_cylinder(0.02, 0.5, density=1000)[0], 6)
    assert f"Filled 1 link in {path}: rod {mass} kg" in result.stderr
    assert f"{path}: link `shell` not filled: its collision mesh" in result.stderr
    assert "mesh not found" in result.stderr


def test_diff_and_check_write_nothing(tmp_path: Path):
    path = tmp_path / "robot.urdf"
    path.write_text(ARM)
    before = os.stat(path).st_mtime_ns
    result = CliRunner().invoke(fill_command, ["--diff", str(path)])
    assert result.exit_code == 1
    assert result.stdout.startswith(f"--- {path}\n+++ {path}\n")
    assert "+    <inertial>\n" in result.stdout
    assert "Would fill 1 link" in result.stderr
    result = CliRunner().invoke(fill_command, ["--check", str(path)])
    assert (result.exit_code, result.stdout) == (1, "")
    assert path.read_text() == ARM and os.stat(path).st_mtime_ns == before
    path.write_text(ARM_FILLED)
    for flag in ("--diff", "--check"):
        result = CliRunner().invoke(fill_command, [flag, str(path)])
        assert (result.exit_code, result.stdout, result.stderr) == (0, "", "")


def test_read_only_file_is_an_error_and_untouched(tmp_path: Path):
    path = tmp_path / "robot.urdf"
    path.write_text(ARM)
    path.chmod(stat.S_IRUSR | stat.S_IRGRP)
    try:
        result = CliRunner().invoke(fill_command, [str(path)])
        assert result.exit_code == 2
        assert "read-only" in result.stderr
        assert path.read_text() == ARM
    finally:
        path.chmod(stat.S_IRUSR | stat.S_IWUSR)


def test_literal_link_in_xacro_is_filled(tmp_path: Path):
    path = tmp_path / "robot.urdf.xacro"
    text = ARM.replace(
        "<robot   name='arm'>",
        '<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:property name="l" value="0.4"/>',
    )
    text = text.replace("box size='0.1 0.1 0.4'", "box size='0.1 0.1 ${l}'")
    path.write_text(text)
    result = CliRunner().invoke(fill_command, [str(path)])
    assert result.exit_code == 1, result.stderr
    expected = text.replace(
        "name='upper'  >\n",
        "name='upper'  >\n"
        + filled_inertial(solid_box((0.1, 0.1, 0.4), density=1000), com=(0, 0, 0.2), indent="    ")
        + "\n",
    )
    assert path.read_text() == expected


@pytest.mark.parametrize(
    "args, message",
    [
        (("--density", "1000", "--material", "steel"), "not both"),
        (("--material", "unobtainium"), "unknown 'unobtainium'"),
        (("--mass", "upper"), "LINK=KG"),
        (("--mass", "upper=-1"), "LINK=KG"),
        (("--mass", "nosuch=1"), "names no link"),
        (("--density", "0"), "positive"),
    ],
)
def test_usage_errors_exit_2(args, message, tmp_path: Path):
    path = tmp_path / "robot.urdf"
    path.write_text(ARM)
    result = CliRunner().invoke(fill_command, [*args, str(path)])
    assert result.exit_code == 2
    assert message in result.stderr
    assert path.read_text() == ARM


def test_unreadable_input_exits_2(tmp_path: Path):
    result = CliRunner().invoke(fill_command, [str(tmp_path / "missing.urdf")])
    assert result.exit_code == 2
    assert "cannot read" in result.stderr


def test_millimetre_mesh_is_refused(tmp_path: Path):
    trimesh = pytest.importorskip("trimesh")
    trimesh.creation.box(extents=(300, 50, 50)).export(tmp_path / "part.stl")  # 0.3 m, in mm
    elbow = (
        '<joint name="elbow" type="revolute"><origin xyz="0.3 0 0"/><parent link="shell"/>'
        '<child link="tip"/><axis xyz="0 0 1"/>'
        '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>\n  <link name="tip"/>\n'
    )
    text = MISSING_MESH.replace("meshes/nowhere.stl", "part.stl").replace("</robot>", "")
    text += "  " + elbow + "</robot>\n"
    path = tmp_path / "robot.urdf"
    path.write_text(text)
    result = CliRunner().invoke(fill_command, [str(path)])
    assert result.exit_code == 1
    assert "link `shell` not filled: a mesh looks authored in other units (IN031)" in result.stderr
    assert 'set scale="0.001 0.001 0.001" if that is its unit' in result.stderr
    expected = text.replace(
        '<link name="rod">\n',
        '<link name="rod">\n'
        + filled_inertial(solid_cylinder(0.02, 0.5, density=1000), indent="    ")
        + "\n",
    )
    assert path.read_text() == expected


def test_console_script_umbrella():
    done = subprocess.run(["inertia-kit", "fill", "--help"], capture_output=True, text=True)
    assert done.returncode == 0
    assert "--material" in done.stdout


# --- -o OUT ------------------------------------------------------------------------------------

EXAMPLE = REPO / "examples" / "my_robot_description" / "urdf"


def _inertial(path: Path, link: str):
    """(com, mass, {ixx..izz}) of ``link``'s <inertial> in the URDF file ``path``."""
    from lxml import etree

    (element,) = etree.parse(str(path)).getroot().findall(f"link[@name='{link}']/inertial")
    com = tuple(float(v) for v in element.find("origin").get("xyz").split())
    mass = float(element.find("mass").get("value"))
    inertia = {k: float(v) for k, v in element.find("inertia").attrib.items()}
    return com, mass, inertia


@pytest.mark.parametrize(
    "text, code, expected",
    [
        (ARM, 1, ARM_FILLED),
        (MISSING_MESH, 1, MISSING_MESH_FILLED),  # a refusal: the other link still filled
        (ARM_FILLED, 0, ARM_FILLED),  # nothing to fill: OUT is written all the same
    ],
    ids=["filled", "refusal", "nothing-to-fill"],
)
def test_output_of_a_urdf_is_its_bytes_edited(text, code, expected, tmp_path: Path):
    path = tmp_path / "robot.urdf"
    path.write_text(text)
    out = tmp_path / "out" / "filled.urdf"
    out.parent.mkdir()
    result = CliRunner().invoke(fill_command, ["-o", str(out), str(path)])
    assert result.exit_code == code, result.stderr
    assert path.read_text() == text
    assert out.read_text() == expected
    if code and expected is ARM_FILLED:
        assert f"Filled 1 link of {path} into {out}: upper " in result.stderr
    if not code:
        assert f"Wrote {out}: nothing to fill in {path}" in result.stderr
    assert [p.name for p in out.parent.iterdir()] == ["filled.urdf"]  # no temporary left


def test_output_check_and_diff_write_nothing(tmp_path: Path):
    path = tmp_path / "robot.urdf"
    path.write_text(ARM)
    out = tmp_path / "filled.urdf"
    result = CliRunner().invoke(fill_command, ["--check", "-o", str(out), str(path)])
    assert (result.exit_code, out.exists()) == (1, False)
    result = CliRunner().invoke(fill_command, ["--diff", "-o", str(out), str(path)])
    assert (result.exit_code, out.exists()) == (1, False)
    assert "+    <inertial>\n" in result.stdout


def test_output_of_the_example_xacro_is_the_expanded_urdf_filled(tmp_path: Path):
    sources = {p: p.read_bytes() for p in EXAMPLE.iterdir()}
    out = tmp_path / "robot.urdf"
    result = CliRunner().invoke(
        fill_command, ["--density", "500", "-o", str(out), str(EXAMPLE / "robot.xacro")]
    )
    assert result.exit_code == 1, result.stderr
    assert {p: p.read_bytes() for p in EXAMPLE.iterdir()} == sources  # the input untouched
    text = out.read_text()
    assert "xacro" not in text.replace("from robot.xacro", "")  # fully expanded
    # base_link: its collision box 0.4 × 0.4 × 0.1 m raised 0.05 m, at 500 kg/m³
    m, ixx, iyy, izz = solid_box((0.4, 0.4, 0.1), density=500)
    com, mass, inertia = _inertial(out, "base_link")
    assert com == (0, 0, 0.05)
    assert mass == pytest.approx(m, rel=1e-6) and m == pytest.approx(8.0)
    assert inertia["ixx"] == pytest.approx(ixx, rel=1e-5)
    assert inertia["iyy"] == pytest.approx(iyy, rel=1e-5)
    assert inertia["izz"] == pytest.approx(izz, rel=1e-5)
    assert (inertia["ixy"], inertia["ixz"], inertia["iyz"]) == (0, 0, 0)
    assert f"into {out}: base_link 8 kg" in result.stderr
    # the wheels keep the inertials their macro wrote
    assert _inertial(out, "left_wheel_link")[1] == 0.3
    # the output is a URDF that needs nothing more
    assert not plan_fill(out).changed
    assert lint_file(out, Selection(select=("IN001",))).findings == []


def test_output_fills_links_made_by_xacro_macros(tmp_path: Path):
    path = tmp_path / "robot.urdf.xacro"
    text = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="part" params="name size">
    <link name="${name}">
      <collision><geometry><box size="${size}"/></geometry></collision></link>
  </xacro:macro>
  <link name="base"/>
  <xacro:part name="arm" size="0.1 0.1 0.4"/>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""
    path.write_text(text)
    out = tmp_path / "robot.urdf"
    out.write_text("old")
    out.chmod(0o640)
    result = CliRunner().invoke(fill_command, ["--mass", "arm=2", "-o", str(out), str(path)])
    assert result.exit_code == 1, result.stderr
    assert path.read_text() == text
    assert stat.S_IMODE(out.stat().st_mode) == 0o640  # an existing OUT keeps its mode
    m, ixx, iyy, izz = solid_box((0.1, 0.1, 0.4), mass=2)
    assert out.read_text().endswith(
        '  <link name="arm">\n'
        + filled_inertial((m, ixx, iyy, izz), indent="    ")
        + "\n    <collision>\n      <geometry>\n"
        '        <box size="0.1 0.1 0.4"/>\n      </geometry>\n    </collision>\n  </link>\n'
        '  <joint name="j" type="revolute">\n'
        '    <parent link="base"/>\n    <child link="arm"/>\n    <axis xyz="0 0 1"/>\n'
        '    <limit lower="-1" upper="1" effort="1" velocity="1"/>\n  </joint>\n</robot>\n'
    )
    # run again: the same bytes, so OUT is not rewritten
    before = out.stat().st_mtime_ns
    again = CliRunner().invoke(fill_command, ["--mass", "arm=2", "-o", str(out), str(path)])
    assert again.exit_code == 1 and out.stat().st_mtime_ns == before


@pytest.mark.parametrize(
    "args, message",
    [
        (("-o", "{out}", "{path}", "{path}"), "-o takes exactly one PATH, got 2"),
        (("-o", "{path}", "{path}"), "names the input file itself"),
        (("-o", "{tmp}/nowhere/out.urdf", "{path}"), "no folder"),
        (("--xacro-arg", "nope", "-o", "{out}", "{path}"), "NAME:=VALUE"),
    ],
)
def test_output_errors_exit_2(args, message, tmp_path: Path):
    path = tmp_path / "robot.urdf"
    path.write_text(ARM)
    out = tmp_path / "out.urdf"
    fields = {"path": path, "out": out, "tmp": tmp_path}
    result = CliRunner().invoke(fill_command, [a.format(**fields) for a in args])
    assert result.exit_code == 2
    assert message in result.stderr
    assert path.read_text() == ARM
    assert not out.exists()


def test_output_of_a_xacro_resolves_meshes_from_its_sources(tmp_path: Path):
    """A relative mesh path resolves from the xacro file that wrote it, wherever OUT goes."""
    trimesh = pytest.importorskip("trimesh")
    source = tmp_path / "description"
    source.mkdir()
    trimesh.creation.box(extents=(0.1, 0.2, 0.3)).export(source / "part.stl")
    path = source / "robot.xacro"
    path.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:macro name="part" params="name">\n'
        '    <link name="${name}"><collision><geometry><mesh filename="part.stl"/></geometry>'
        "</collision></link>\n"
        "  </xacro:macro>\n"
        '  <link name="base"/>\n  <xacro:part name="arm"/>\n  '
        + joint("base", "arm")
        + "\n</robot>\n"
    )
    out = tmp_path / "elsewhere" / "robot.urdf"
    out.parent.mkdir()
    result = CliRunner().invoke(fill_command, ["-o", str(out), str(path)])
    assert result.exit_code == 1, result.stderr
    assert "not filled" not in result.stderr
    _, mass, inertia = _inertial(out, "arm")
    m, ixx, iyy, izz = solid_box((0.1, 0.2, 0.3), density=1000)
    assert mass == pytest.approx(m, rel=1e-5)
    assert [inertia[k] for k in ("ixx", "iyy", "izz")] == pytest.approx([ixx, iyy, izz], rel=1e-5)


# --- --total-mass and per-link configuration ---------------------------------------------------

TWO_LINKS = """<robot name="r">
  <link name="base">
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
    <inertial><mass value="2"/>
      <inertia ixx="0.00833333" ixy="0" ixz="0" iyy="0.00833333" iyz="0" izz="0.0133333"/>
    </inertial>
  </link>
  {j1}
  <link name="upper">
    <collision><geometry><box size="0.1 0.1 0.4"/></geometry></collision>
  </link>
  {j2}
  <link name="lower">
    <collision><geometry><box size="0.1 0.1 0.2"/></geometry></collision>
  </link>
</robot>
""".format(j1=joint("base", "upper"), j2=joint("upper", "lower"))


def filled_two_links(upper_mass: float, lower_mass: float) -> str:
    return TWO_LINKS.replace(
        '<link name="upper">\n',
        '<link name="upper">\n'
        + filled_inertial(solid_box((0.1, 0.1, 0.4), mass=upper_mass), indent="    ")
        + "\n",
    ).replace(
        '<link name="lower">\n',
        '<link name="lower">\n'
        + filled_inertial(solid_box((0.1, 0.1, 0.2), mass=lower_mass), indent="    ")
        + "\n",
    )


def test_total_mass_is_shared_by_volume_after_the_declared_masses(tmp_path: Path):
    """5 kg in all, the base declares 2: the other 3 kg go 2:1 to the 4 L and 2 L boxes."""
    path = tmp_path / "robot.urdf"
    path.write_text(TWO_LINKS)
    result = CliRunner().invoke(fill_command, ["--total-mass", "5", str(path)])
    assert result.exit_code == 1, result.stderr
    assert path.read_text() == filled_two_links(2.0, 1.0)
    assert "upper 2 kg, lower 1 kg" in result.stderr
    assert CliRunner().invoke(fill_command, ["--total-mass", "5", str(path)]).exit_code == 0


def test_total_mass_below_what_the_others_weigh_is_refused(tmp_path: Path):
    path = tmp_path / "robot.urdf"
    path.write_text(TWO_LINKS)
    result = CliRunner().invoke(fill_command, ["--total-mass", "1.5", str(path)])
    assert result.exit_code == 1
    assert "link `upper` not filled: --total-mass 1.5 kg leaves nothing" in result.stderr
    assert "already weigh 2 kg" in result.stderr
    assert path.read_text() == TWO_LINKS


@pytest.mark.parametrize(
    "args", [("--total-mass", "5", "--density", "1000"), ("--total-mass", "-1")]
)
def test_total_mass_usage_errors(args, tmp_path: Path):
    path = tmp_path / "robot.urdf"
    path.write_text(TWO_LINKS)
    result = CliRunner().invoke(fill_command, [*args, str(path)])
    assert result.exit_code == 2 and "--total-mass" in result.stderr


def test_configured_link_density_and_mass(tmp_path: Path):
    """[links.NAME] in .inertia-kit.toml: a density for one link, a mass for another; a
    --mass on the command line wins over the configured one."""
    path = tmp_path / "robot.urdf"
    path.write_text(TWO_LINKS)
    (tmp_path / ".inertia-kit.toml").write_text(
        "[links.upper]\ndensity = 2700.0\n\n[links.lower]\nmass = 0.75\n"
    )
    result = CliRunner().invoke(fill_command, ["--diff", str(path)])
    assert result.exit_code == 1, result.stderr
    assert "upper 10.8 kg, lower 0.75 kg" in result.stderr
    result = CliRunner().invoke(fill_command, ["--mass", "lower=0.5", str(path)])
    assert path.read_text() == filled_two_links(2700 * 0.004, 0.5)


def test_bad_configuration_exits_2(tmp_path: Path):
    path = tmp_path / "robot.urdf"
    path.write_text(TWO_LINKS)
    (tmp_path / ".inertia-kit.toml").write_text("[links.upper]\ndensity = -1.0\n")
    result = CliRunner().invoke(fill_command, [str(path)])
    assert result.exit_code == 2 and ".inertia-kit.toml" in result.stderr
    assert path.read_text() == TWO_LINKS
