"""
`inertia-fill` (and `inertia-kit fill`): usage errors, unreadable input and a bad configuration
exit 2 and leave the file as it was; --help shows the materials; the console script.
"""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
from click.testing import CliRunner
from console_scripts import console_script
from kit.urdf import moving

from inertia_kit.cli.fill import fill_command
from inertia_kit.fill.materials import MATERIALS

# a moving link `upper` that inertia-fill would fill
ROBOT = moving('<collision><geometry><box size="0.1 0.1 0.4"/></geometry></collision>', "upper")


@pytest.mark.parametrize(
    "args, message",
    [
        (("--density", "1000", "--material", "steel"), "not both"),
        (("--material", "unobtainium"), "unknown 'unobtainium'"),
        (("--mass", "upper"), "LINK=KG"),
        (("--mass", "upper=-1"), "LINK=KG"),
        (("--mass", "nosuch=1"), "name no link"),
        (("--density", "0"), "positive"),
    ],
)
def test_usage_errors_exit_2(args, message, tmp_path: Path):
    path = tmp_path / "robot.urdf"
    path.write_text(ROBOT)
    result = CliRunner().invoke(fill_command, [*args, str(path)])
    assert result.exit_code == 2
    assert message in result.stderr
    assert path.read_text() == ROBOT


def test_unreadable_input_exits_2(tmp_path: Path):
    result = CliRunner().invoke(fill_command, [str(tmp_path / "missing.urdf")])
    assert result.exit_code == 2
    assert "missing.urdf: no such file" in result.stderr


def test_console_script_umbrella():
    done = subprocess.run(
        [console_script("inertia-kit"), "fill", "--help"], capture_output=True, text=True
    )
    assert done.returncode == 0
    assert "--material" in done.stdout


@pytest.mark.parametrize(
    "args, message",
    [
        (("-o", "{out}", "{path}", "{path}"), "-o takes exactly one file PATH"),
        (("-o", "{path}", "{path}"), "names the input file itself"),
        (("-o", "{tmp}/nowhere/out.urdf", "{path}"), "no folder"),
        (("--xacro-arg", "nope", "-o", "{out}", "{path}"), "NAME:=VALUE"),
    ],
)
def test_output_errors_exit_2(args, message, tmp_path: Path):
    path = tmp_path / "robot.urdf"
    path.write_text(ROBOT)
    out = tmp_path / "out.urdf"
    fields = {"path": path, "out": out, "tmp": tmp_path}
    result = CliRunner().invoke(fill_command, [a.format(**fields) for a in args])
    assert result.exit_code == 2
    assert message in result.stderr
    assert path.read_text() == ROBOT
    assert not out.exists()


@pytest.mark.parametrize(
    "args", [("--total-mass", "5", "--density", "1000"), ("--total-mass", "-1")]
)
def test_total_mass_usage_errors(args, tmp_path: Path):
    path = tmp_path / "robot.urdf"
    path.write_text(ROBOT)
    result = CliRunner().invoke(fill_command, [*args, str(path)])
    assert result.exit_code == 2 and "--total-mass" in result.stderr


def test_bad_configuration_exits_2(tmp_path: Path):
    path = tmp_path / "robot.urdf"
    path.write_text(ROBOT)
    (tmp_path / ".inertia-kit.toml").write_text("[links.upper]\ndensity = -1.0\n")
    result = CliRunner().invoke(fill_command, [str(path)])
    assert result.exit_code == 2 and ".inertia-kit.toml" in result.stderr
    assert path.read_text() == ROBOT


def test_help_shows_every_material_with_its_density():
    result = CliRunner().invoke(fill_command, ["--help"])
    assert result.exit_code == 0
    # click wraps after a hyphen (`stainless-` / `steel`) when the option column is wide
    shown = " ".join(result.stdout.split()).replace("- ", "-")
    for name, density in MATERIALS.items():
        assert f"{name} {density:g}" in shown


@pytest.mark.parametrize(
    "spelling, density",
    [
        ("aluminum", 2700.0),
        ("Aluminium", 2700.0),
        ("ALUMINUM", 2700.0),
        ("stainless steel", 8000.0),
        ("stainless-steel", 8000.0),
        ("Stainless_Steel", 8000.0),
        ("ABS", 1040.0),
        ("pla", 1240.0),
        ("carbon fiber", 1600.0),
    ],
)
def test_material_spellings_give_the_density_of_their_name(spelling, density, tmp_path: Path):
    """The box of `upper` (0.1 × 0.1 × 0.4 m) filled at the material's density."""
    by_name, by_density = tmp_path / "name.urdf", tmp_path / "density.urdf"
    by_name.write_text(ROBOT)
    by_density.write_text(ROBOT)
    result = CliRunner().invoke(fill_command, ["--material", spelling, str(by_name)])
    assert result.exit_code == 1, result.stderr
    CliRunner().invoke(fill_command, ["--density", str(density), str(by_density)])
    assert by_name.read_text() == by_density.read_text()
    assert f'<mass value="{density * 0.004:g}"/>' in by_name.read_text()


def test_unknown_material_lists_the_canonical_names(tmp_path: Path):
    path = tmp_path / "robot.urdf"
    path.write_text(ROBOT)
    result = CliRunner().invoke(fill_command, ["--material", "aluminum alloy", str(path)])
    assert result.exit_code == 2
    assert f"known: {', '.join(MATERIALS)} (in any case" in result.stderr
