"""
Which links inertia-fill fills and the mass each gets (fill.policy).

--fix invalid undoes a recognised slip (IN060-IN064) instead of replacing the declared tensor
with the geometry's: the closed-form tensor of a turned box is written wrongly in each way,
filled, and read back. Expected values come from the closed form computed here. A mesh authored
in other units is refused; --total-mass is shared by volume after the declared masses; a
configured link density or mass is used, under --mass.
"""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from kit import EXAMPLES
from kit.moments import box_tensor, solid_box, solid_cylinder
from kit.urdf import box, collision, filled_inertial, inertial, joint, link, moving, robot
from test_plan import MISSING_MESH

from inertia_kit import load
from inertia_kit.cli.fill import fill_command
from inertia_kit.fill.plan import FillPlan
from inertia_kit.fill.policy import density_option, per_link, unknown_links
from inertia_kit.lint.config import LinkSettings
from inertia_kit.lint.runner import Selection, lint_file
from inertia_kit.physics.frames import rpy_matrix
from inertia_kit.physics.mass import shift_tensor

MASS, SIZE, YAW = 12.0, (0.4, 0.3, 0.2), math.pi / 6
COM = np.array([0.0, 0.0, 0.25])
NAMES = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
INDEX = ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))


def turned_box() -> np.ndarray:
    """The box's tensor about its centre, in link axes (turned by YAW about z)."""
    return box_tensor(MASS, SIZE, rpy_matrix([0.0, 0.0, YAW]))


def plate(values: dict[str, float], mass: float = MASS) -> str:
    """The turned box at COM, with these ``<inertia>`` values written."""
    xyz = tuple(float(v) for v in COM)
    written = inertial(mass, **values, xyz=xyz)
    return moving(written + collision(box(*SIZE), xyz=xyz, rpy=f"0 0 {YAW!r}"), name="plate")


def values_of(tensor: np.ndarray) -> dict[str, float]:
    return {name: float(tensor[i, j]) for name, (i, j) in zip(NAMES, INDEX, strict=True)}


def about_origin(t):
    return values_of(t + shift_tensor(MASS, COM))


def flipped(t):
    v = values_of(t)
    return {k: (-x if k in ("ixy", "ixz", "iyz") else x) for k, x in v.items()}


def in_kg_mm2(t):
    return {k: x * 1e6 for k, x in values_of(t).items()}


def swapped_products(t):
    v = values_of(t)
    v["ixy"], v["ixz"] = v["ixz"], v["ixy"]
    return v


SLIPS = {
    "IN060": about_origin,
    "IN061": flipped,
    "IN063": in_kg_mm2,
    "IN064": swapped_products,
}


@pytest.mark.parametrize("code", SLIPS)
def test_fix_invalid_undoes_the_slip(code: str, tmp_path: Path):
    truth = turned_box()
    path = tmp_path / "robot.urdf"
    path.write_text(plate(SLIPS[code](truth)))
    before = lint_file(path, Selection()).findings
    assert code in {f.code for f in before}, [(f.code, f.message) for f in before]
    result = CliRunner().invoke(fill_command, ["--fix", "invalid", str(path)])
    assert result.exit_code == 1, result.stderr
    assert f"plate {MASS:g} kg" in result.stderr
    inertial = load(path).links[1].inertial
    written = np.array([getattr(inertial, name) for name in NAMES])
    expected = np.array(list(values_of(truth).values()))
    assert written == pytest.approx(expected, rel=1e-5, abs=1e-6 * truth.trace())
    assert inertial.origin.xyz == pytest.approx(tuple(COM))
    after = lint_file(path, Selection()).findings
    assert not {f.code for f in after} & {code, "IN020", "IN023"}, [f.message for f in after]
    assert CliRunner().invoke(fill_command, ["--fix", "invalid", str(path)]).exit_code == 0


def test_a_given_mass_wins_over_the_correction(tmp_path: Path):
    """--mass: the geometry's tensor for that mass, not the declared one corrected."""
    path = tmp_path / "robot.urdf"
    path.write_text(plate(about_origin(turned_box())))
    result = CliRunner().invoke(fill_command, ["--fix", "invalid", "--mass", "plate=6", str(path)])
    assert result.exit_code == 1, result.stderr
    inertial = load(path).links[1].inertial
    assert inertial.mass == 6.0
    assert inertial.ixx == pytest.approx(turned_box()[0, 0] / 2, rel=1e-5)


def copy(name: str, tmp_path: Path) -> Path:
    shutil.copytree(EXAMPLES / name, tmp_path / name)
    return tmp_path / name


def test_mrm_cad_tensors_about_the_base_are_moved_to_the_com(tmp_path: Path):
    """The seed arm (IN060 on every cylinder): ixx = declared − m·d² at each call site, izz
    (about the axis through both points) unchanged; links_joints.xacro untouched."""
    folder = copy("mrm_description", tmp_path)
    macros = (folder / "urdf" / "links_joints.xacro").read_bytes()
    path = folder / "urdf" / "mrm.xacro"
    result = CliRunner().invoke(fill_command, ["--fix", "invalid", str(path)])
    assert result.exit_code == 1, result.stderr
    assert "Filled 5 links" in result.stderr
    text = path.read_text()
    for declared, mass, height, izz in [
        (13.235, 157.633, 0.2, "9.655"),
        (12.679, 57.906, 0.4, "0.651"),
        (0.479, 18.056, 0.125, "0.204"),
    ]:
        about_com = declared - mass * height**2
        assert f'ixx="{about_com:.6g}" ixy="0" ixz="0"' in text
        assert f'iyy="{about_com:.6g}" iyz="0"\n              izz="{izz}"' in text
    assert (folder / "urdf" / "links_joints.xacro").read_bytes() == macros
    findings = lint_file(path, Selection()).findings
    assert not {f.code for f in findings} & {"IN060", "IN020", "IN023"}
    assert CliRunner().invoke(fill_command, ["--fix", "invalid", str(path)]).exit_code == 0


def test_simple_arm_tensor_for_the_wrong_axes_is_turned(tmp_path: Path):
    """IN062 on link_1/link_2: the z formula of a rod lying along x. The slip is undone the
    way the author would: the <inertial> takes the collision's <origin> (the formula is right
    in the rod's own axes), so in link axes the tensor is the rod's, about its centre (IN021)."""
    from inertia_kit.analysis.declared import declared

    folder = copy("simple_arm", tmp_path)
    path = folder / "urdf" / "simple_arm.urdf.xacro"
    result = CliRunner().invoke(fill_command, ["--fix", "invalid", str(path)])
    assert result.exit_code == 1, result.stderr
    robot = load(path)
    m, r, length = 1.0, 0.02, 0.3
    for name in ("link_1", "link_2"):
        link = next(link for link in robot.links if link.name == name)
        assert link.inertial.origin.xyz == pytest.approx((length / 2, 0, 0))
        tensor = declared(link).inertia
        side = m * (3 * r * r + length**2) / 12
        assert np.diag(tensor) == pytest.approx((m * r * r / 2, side, side), rel=1e-5)
    findings = lint_file(path, Selection()).findings
    assert not {f.code for f in findings} & {"IN062", "IN021", "IN020", "IN023"}
    assert 'cylinder_inertia mass="2.0" radius="0.1" length="0.05"/>' in path.read_text()


def test_a_mass_in_grams_is_written_in_kilograms(tmp_path: Path):
    path = tmp_path / "robot.urdf"
    path.write_text(plate(values_of(turned_box()), mass=MASS * 1000))
    assert "IN063" in {f.code for f in lint_file(path, Selection()).findings}
    result = CliRunner().invoke(fill_command, ["--fix", "invalid", str(path)])
    assert result.exit_code == 1, result.stderr
    inertial = load(path).links[1].inertial
    assert inertial.mass == pytest.approx(MASS)
    assert inertial.ixx == pytest.approx(turned_box()[0, 0], rel=1e-5)
    assert CliRunner().invoke(fill_command, ["--fix", "invalid", str(path)]).exit_code == 0


# --- refusals, --total-mass and per-link configuration -----------------------------------------


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
    assert "link `shell` not filled: its geometry cannot be trusted (IN031)" in result.stderr
    assert 'set scale="0.001 0.001 0.001" if that is its unit' in result.stderr
    expected = text.replace(
        '<link name="rod">\n',
        '<link name="rod">\n'
        + filled_inertial(solid_cylinder(0.02, 0.5, density=1000), indent="    ")
        + "\n",
    )
    assert path.read_text() == expected


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


# --- the options --------------------------------------------------------------------------------


def test_density_options():
    assert density_option(None, None, None) == 1000.0
    assert density_option(None, "Aluminium", None) == 2700.0
    assert density_option(None, None, 5.0) == 1000.0  # each link's share replaces it
    for density, material, total, message in [
        (1000.0, "pla", None, "give --density or --material, not both"),
        (None, "pla", 5.0, "give --total-mass or --density/--material, not both"),
        (None, None, float("inf"), "--total-mass must be a positive number of kg, got inf"),
        (0.0, None, None, "--density must be a positive number of kg/m³, got 0.0"),
    ]:
        with pytest.raises(ValueError) as raised:
            density_option(density, material, total)
        assert str(raised.value) == message


def test_configured_links_under_given_masses_and_unknown_names():
    configured = {"a": LinkSettings(mass=1.0), "b": LinkSettings(density=2.0)}
    assert per_link(configured, {"a": 3.0, "c": 4.0}) == {
        "masses": {"a": 3.0, "c": 4.0},
        "densities": {"b": 2.0},
    }
    plans = [FillPlan("x.urdf", None, links=frozenset({"a", "b"}))]
    assert unknown_links(["c", "a", "nosuch"], plans) == ["c", "nosuch"]
    assert unknown_links(["c"], []) == []  # no file was read: its error is what to tell


def test_a_massless_base_without_geometry_is_refused_with_the_way_out(tmp_path: Path):
    """IN001 flags a massless root above moving links; with no geometry fill cannot help."""
    text = robot(
        link("base"),
        joint("base", "arm"),
        link("arm", inertial(2, 0.01), collision(box(0.1, 0.1, 0.1))),
    )
    path = tmp_path / "robot.urdf"
    path.write_text(text)
    result = CliRunner().invoke(fill_command, [str(path)])
    assert result.exit_code == 1
    why = "the robot's base has no <visual> or <collision> geometry"
    assert f"{path}: link `base` not filled: {why}" in result.stderr
    assert "hang the robot from a `world` link by a fixed joint" in result.stderr
    assert path.read_text() == text
    welded = text.replace('"base"', '"world"')
    path.write_text(welded)
    assert CliRunner().invoke(fill_command, [str(path)]).exit_code == 0


def test_fix_invalid_keeps_a_tensor_that_is_only_doubtfully_impossible(tmp_path: Path):
    """IN023 as a warning (2.3 % over a rounded radius: Unitree Go1's rotors) is no licence to
    replace a measured tensor; the same overshoot on precisely written numbers is an error."""
    along_x = "0 1.5707963267948966 0"
    rotor = inertial(0.089, 0.000111842, 5.9647e-05, 5.9647e-05)
    doubtful = moving(collision('<cylinder radius="0.035" length="0.02"/>', rpy=along_x) + rotor)
    path = tmp_path / "robot.urdf"
    path.write_text(doubtful)
    result = CliRunner().invoke(fill_command, ["--fix", "invalid", str(path)])
    assert (result.exit_code, path.read_text()) == (0, doubtful), result.stderr
    firm = doubtful.replace('radius="0.035" length="0.02"', 'radius="0.0349999" length="0.02"')
    firm = firm.replace('value="0.089"', 'value="0.0890001"')
    path.write_text(firm)
    result = CliRunner().invoke(fill_command, ["--fix", "invalid", str(path)])
    assert result.exit_code == 1 and "0.000111842" not in path.read_text(), result.stderr
