"""
inertia-fill -o OUT (fill.output): the filled robot goes to a new file and the input is not
touched. A URDF gives its own bytes with the edits; a xacro gives its expanded URDF, in which the
links its macros make are filled too.
"""

from __future__ import annotations

import stat
from pathlib import Path

import pytest
from click.testing import CliRunner
from kit import REPO
from kit.moments import solid_box
from kit.urdf import filled_inertial, joint
from test_plan import ARM, ARM_FILLED, MISSING_MESH, MISSING_MESH_FILLED

from inertia_kit.cli.fill import fill_command
from inertia_kit.fill.plan import plan_fill
from inertia_kit.lint.runner import Selection, lint_file

EXAMPLE = REPO / "examples" / "my_robot_description" / "urdf"


def _inertial(path: Path, link: str):
    """(com, mass, {ixx..izz}) of ``link``'s <inertial> in the URDF file ``path``."""
    from lxml import etree

    (element,) = etree.parse(str(path)).getroot().findall(f"link[@name='{link}']/inertial")
    com = tuple(float(v) for v in element.find("origin").get("xyz").split())
    mass = float(element.find("mass").get("value"))
    inertia = {k: float(v) for k, v in element.find("inertia").attrib.items()}
    return com, mass, inertia


def _generated(text: str) -> str:
    """``text`` as xacro writes its output: the namespace declared, and here a comment quoting
    a ``${…}`` (PR2's pr2.urdf), which xacro leaves as it is: still a URDF."""
    return text.replace(
        "<robot   name='arm'>",
        "<robot   name='arm' xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n"
        "  <!-- replaced by ${arm_length} from common.xacro -->",
    )


@pytest.mark.parametrize(
    "text, code, expected",
    [
        (ARM, 1, ARM_FILLED),
        (MISSING_MESH, 1, MISSING_MESH_FILLED),  # a refusal: the other link still filled
        (ARM_FILLED, 0, ARM_FILLED),  # nothing to fill: OUT is written all the same
        (_generated(ARM), 1, _generated(ARM_FILLED)),
    ],
    ids=["filled", "refusal", "nothing-to-fill", "xacro-output"],
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
  <link name="world"/>
  <xacro:part name="arm" size="0.1 0.1 0.4"/>
  <joint name="j" type="revolute"><parent link="world"/><child link="arm"/>
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
        '    <parent link="world"/>\n    <child link="arm"/>\n    <axis xyz="0 0 1"/>\n'
        '    <limit lower="-1" upper="1" effort="1" velocity="1"/>\n  </joint>\n</robot>\n'
    )
    # run again: the same bytes, so OUT is not rewritten
    before = out.stat().st_mtime_ns
    again = CliRunner().invoke(fill_command, ["--mass", "arm=2", "-o", str(out), str(path)])
    assert again.exit_code == 1 and out.stat().st_mtime_ns == before


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
        '  <link name="world"/>\n  <xacro:part name="arm"/>\n  '
        + joint("world", "arm")
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
