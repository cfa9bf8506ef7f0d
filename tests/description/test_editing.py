"""fixes.files: the files fixes may edit, read and parsed once."""

from __future__ import annotations

from click.testing import CliRunner

from inertia_kit.cli import main

#: xacro's parser reads these bytes (UTF-8), libxml2 honours the declaration and cannot
# the fuzz reproducer's bytes as they were (libxml2's error depends on their number)
XACRO_DECLARING_ANOTHER_ENCODING = (
    '<?xml version="1.0" encoding="utf-16le"?>\n'
    '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
    '  <xacro:arg name="prefix" default=""/>\n'
    '  <xacro:property name="pi2"/>\n'
    '  <xacro:macro name="box_link" params="name mass:=1 size:=0.1 *origin">\n'
    '    <link name="${name}">\n'
    '      <inertial><xacro:insert_block name="origin"/><mass/>\n'
    "        <inertia/>\n"
    "      </inertial>\n"
    '      <collision><geometry><box size="${size} ${size}'
    ' ${size}"/></geometry></collision>\n'
    "    </link>\n"
    "  </xacro:macro>\n"
    '  <link name="$(arg prefix)base"/>\n'
    '  <xacro:box_link name="$(arg prefix)l1" mass="2.5" size="0.1"><origin xyz="0 0'
    ' ${0.1/2}"/></xacro:box_link>\n'
    '  <xacro:macro name="wrap" params="**body"><xacro:insert_block'
    ' name="body"/></xacro:macro><xacro:wrap><body><link'
    ' name="wrapped"/></body></xacro:wrap>\n'
    "</robot>\n"
)


def test_a_file_libxml2_cannot_parse_gets_no_fix_and_no_internal_error(tmp_path):
    """Fuzz input 59 of seed s1: placing a fix parsed the macro's file with libxml2, whose
    InputError was an internal error; now no fix goes there, the findings are told."""
    path = tmp_path / "robot.urdf.xacro"
    path.write_bytes(XACRO_DECLARING_ANOTHER_ENCODING.encode())
    for args in (["lint", "--unsafe-fixes"], ["lint", "--fix", "--unsafe-fixes"]):
        result = CliRunner().invoke(main, [*args, str(path)])
        assert "internal error" not in result.output, (args, result.output)
        assert result.exit_code == 1, (args, result.output)
    filled = CliRunner().invoke(main, ["fill", "--fix", "all", str(path)])
    assert "internal error" not in filled.output


def test_an_included_file_that_cannot_be_decoded_for_editing_gets_no_fix(tmp_path):
    """Fuzz input 5827 of seed s1: the mrm arm's included macros file declaring utf-16le over
    UTF-8 bytes (xacro reads them as UTF-8), of an odd length that UTF-16 cannot decode. Placing
    a fix read it for editing: an internal error for every command; now it is not editable and
    the findings are told."""
    import shutil

    from kit import EXAMPLES

    root = tmp_path / "mrm_description"
    shutil.copytree(EXAMPLES / "mrm_description", root)
    macros = root / "urdf" / "links_joints.xacro"
    data = macros.read_bytes().replace(
        b'<?xml version="1.0" ?>', b'<?xml version="1.0" encoding="utf-16le"?>', 1
    )
    macros.write_bytes(data if len(data) % 2 else data + b"\n")
    before = macros.read_bytes()
    robot = root / "urdf" / "mrm.xacro"
    for args in (
        ["lint", "--engine", "all"],
        ["lint", "--fix", "--unsafe-fixes"],
        ["fill", "--fix", "all"],
    ):
        result = CliRunner().invoke(main, [*args, str(robot)])
        assert "internal error" not in result.output, (args, result.output)
        assert result.exit_code in (0, 1), (args, result.output)
    assert macros.read_bytes() == before
