"""`inertia-kit mass`: bad input exits 2 with a message; the real console scripts."""

import subprocess

import pytest
from click.testing import CliRunner
from console_scripts import console_script

from inertia_kit.cli import main


def run(*args: str):
    return CliRunner().invoke(main, ["mass", *args])


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["box", "--size", "1", "0", "1"], "size[1] must be a positive length in m"),
        (["sphere", "--radius", "1", "--density", "-5"], "density must be positive, from 1e-50"),
        (["sphere", "--radius", "1", "--density", "1e-60"], "'1e-60' is non-zero below 1e-50"),
        # numbers mass properties cannot be computed from are refused as options
        (["box", "--size", "1e308", "1e308", "1e308"], "'1e308' is beyond ±1e50"),
        (["box", "--size", "1", "1", "1", "--about", "1e300", "0", "0"], "beyond ±1e50"),
        (["sphere", "--radius", "1e-320"], "'1e-320' is subnormal"),
        (["sphere", "--radius", "1", "--density", "nan"], "'nan' is not a number"),
        # usable dimensions whose product is not: the volume is blamed, not the density
        (["box", "--size", "1e-200", "1e-200", "1e-200"], "the volume underflows to zero"),
        (["mesh", "x.stl", "--scale", "1e308"], "--scale takes numbers of at most 1e50"),
        (["sphere", "--radius", "1", "--density", "5", "--mass", "1"], "exactly one"),
        (["mesh", "missing.stl"], "missing.stl"),
        (["mesh", "x.stl", "--scale", "1 2"], "--scale takes one or three numbers"),
        (["mesh", "x.stl", "--scale", "0"], "--scale takes non-zero factors"),
        (["mesh", "x.stl", "--scale", "1 -0.0 1"], "--scale takes non-zero factors"),
    ],
)
def test_bad_input_exits_2_with_a_message(args, message):
    result = run(*args)
    assert result.exit_code == 2
    assert message in result.output
    assert "Traceback" not in result.output


def test_console_scripts_exist_and_fill_has_help():
    done = subprocess.run(
        [console_script("inertia-fill"), "--help"], capture_output=True, text=True
    )
    assert done.returncode == 0
    assert "--density" in done.stdout
    done = subprocess.run(
        [console_script("inertia-kit"), "mass", "sphere", "--radius", "0.1"],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0
    assert "density 1000 kg/m³" in done.stdout


def test_no_urdf_block_the_linter_would_refuse(tmp_path):
    """A mesh of 1e38 m coordinates: its values are shown, its block is not (IN004)."""
    from kit.meshes import box_triangles, write_binary_stl

    path = write_binary_stl(tmp_path / "huge.stl", box_triangles([1e38, 1e38, 1e38]))
    result = run("mesh", str(path))
    assert result.exit_code == 0
    assert "URDF: none: its mass would be written as 1e117 (beyond ±1e50)" in result.output
    result = run("mesh", str(path), "--scale", "1e30")
    assert (
        result.exit_code == 2 and "its volume or moments overflow double precision" in result.output
    )


@pytest.mark.parametrize(
    "spelling, density",
    [("aluminum", 2700), ("ALUMINIUM", 2700), ("stainless_steel", 8000), ("Stainless Steel", 8000)],
)
def test_material_spellings(spelling, density):
    """A 0.1 m cube of the material weighs density × 0.001 m³."""
    result = run("box", "--size", "0.1", "0.1", "0.1", "--material", spelling)
    assert result.exit_code == 0, result.output
    assert f"mass:   {density * 0.001:g} kg" in result.output
    assert f"density {density} kg/m³" in result.output


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--material", "unobtainium"], "known: steel, stainless-steel, aluminium, abs, pla"),
        (["--material", "pla", "--density", "5"], "give --density or --material, not both"),
    ],
)
def test_material_refusals(args, message):
    result = run("sphere", "--radius", "0.1", *args)
    assert result.exit_code == 2
    assert message in result.output
    assert "Traceback" not in result.output


def test_help_lists_the_canonical_materials():
    from inertia_kit.fill.materials import MATERIALS

    shown = " ".join(run("box", "--help").output.split())
    for name, density in MATERIALS.items():
        assert f"{name} {density:g}" in shown


def test_a_zero_scale_of_a_real_mesh_is_a_usage_error(tmp_path):
    """It flattens the mesh; it was an internal error once the mesh was read (fuzz input 98)."""
    from kit.meshes import write_box_stl

    path = write_box_stl(tmp_path / "part.stl", (0.1, 0.2, 0.3))
    result = run("mesh", str(path), "--scale", "0")
    assert result.exit_code == 2
    assert "--scale takes non-zero factors" in result.output
    assert "internal error" not in result.output
