"""`inertia-kit report`: unreadable input, a bad --xacro-arg and a misused --engine exit 2."""

from click.testing import CliRunner
from kit import EXAMPLES
from kit.urdf import moving

from inertia_kit.cli import main


def report(*args: str):
    return CliRunner().invoke(main, ["report", *args])


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


def test_report_engine_needs_lumped_and_a_known_name(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_text(moving(""))
    assert CliRunner().invoke(main, ["report", "--engine", "kdl", str(path)]).exit_code == 2
    result = CliRunner().invoke(main, ["report", "--lumped", "--engine", "isaac", str(path)])
    assert result.exit_code == 2 and "unknown engine" in result.output
