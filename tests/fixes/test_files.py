"""fixes.files: the files fixes may edit, read and parsed once."""

from __future__ import annotations

from click.testing import CliRunner

from inertia_kit.cli import main

#: xacro's parser reads these bytes (UTF-8), libxml2 honours the declaration and cannot
XACRO_DECLARING_ANOTHER_ENCODING = """<?xml version="1.0" encoding="utf-16le"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="box_link" params="name size">
    <link name="${name}">
      <inertial><mass/><inertia/></inertial>
      <collision><geometry><box size="${size} ${size} ${size}"/></geometry></collision>
    </link>
  </xacro:macro>
  <link name="base"/>
  <xacro:box_link name="l1" size="0.1"/>
  <joint name="j" type="fixed"><parent link="base"/><child link="l1"/></joint>
</robot>
"""


def test_a_file_libxml2_cannot_parse_gets_no_fix_and_no_internal_error(tmp_path):
    """Fuzz input 59 of seed s1: placing a fix parsed the macro's file with libxml2, whose
    InputError was an internal error; now no fix goes there, the findings are told."""
    path = tmp_path / "robot.urdf.xacro"
    path.write_bytes(XACRO_DECLARING_ANOTHER_ENCODING.encode())
    for args in (["lint", "--unsafe-fixes"], ["lint", "--fix", "--unsafe-fixes"]):
        result = CliRunner().invoke(main, [*args, str(path)])
        assert "internal error" not in result.output, (args, result.output)
        assert result.exit_code == 1, (args, result.output)
    # fill reads the file it writes as declared, and says it cannot
    filled = CliRunner().invoke(main, ["fill", str(path)])
    assert filled.exit_code == 2 and "cannot decode as utf-16le" in filled.output
