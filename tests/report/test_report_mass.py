"""
The `inertia-kit mass` report of a part (report.mass): text and JSON, for primitives placed and
weighed as asked, and for meshes with how they were integrated. Numbers from closed forms.
"""

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from inertia_kit.cli import main
from inertia_kit.physics.primitives import capsule
from inertia_kit.report.mass import Part, render


def run(*args: str):
    return CliRunner().invoke(main, ["mass", *args])


# README's quick start: the cylinder of MRM's link_01, and its tensor about its base
QUICK_START = ("cylinder", "--radius", "0.35", "--length", "0.4", "--density", "1024")
QUICK_START += ("--about", "0", "0", "-0.2")


def test_quick_start_cylinder_about_its_base():
    result = run(*QUICK_START)
    assert result.exit_code == 0, result.output
    assert "mass:   157.633 kg" in result.output
    assert "ixx      6.9293" in result.output
    assert "inertia about (0, 0, -0.2) m" in result.output
    assert "ixx      13.235" in result.output
    assert '<mass value="157.633"/>' in result.output


def test_json_has_the_numbers_of_the_closed_form():
    result = run(*QUICK_START, "--format", "json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    m = 1024 * math.pi * 0.35**2 * 0.4
    assert data["mass"] == pytest.approx(m, rel=1e-12)
    assert data["inertia"][0][0] == pytest.approx(m * (3 * 0.35**2 + 0.4**2) / 12, rel=1e-12)
    assert data["about"]["inertia"][0][0] == pytest.approx(
        m * (3 * 0.35**2 + 0.4**2) / 12 + m * 0.04, rel=1e-12
    )
    assert data["urdf"].startswith("<inertial>")
    assert data["mesh"] is None


def test_mass_option_and_placement():
    result = run(
        "box",
        "--size",
        "0.1",
        "0.2",
        "0.3",
        "--mass",
        "2",
        "--xyz",
        "1",
        "0",
        "0",
        "--rpy",
        "0",
        "0",
        "1.5707963267948966",
        "--format",
        "json",
    )
    data = json.loads(result.output)
    assert data["mass"] == 2
    np.testing.assert_allclose(data["com"], (1, 0, 0), atol=1e-15)
    # yawed by 90°: the x and y extents swap
    np.testing.assert_allclose(
        np.diag(data["inertia"]),
        [2 * (0.1**2 + 0.3**2) / 12, 2 * (0.2**2 + 0.3**2) / 12, 2 * (0.1**2 + 0.2**2) / 12],
        rtol=1e-12,
    )
    assert 'xyz="1 0 0"' in data["urdf"]


def test_about_rpy_rotates_the_reported_axes():
    result = run(
        "cylinder",
        "--radius",
        "0.1",
        "--length",
        "1",
        "--mass",
        "1",
        "--about-rpy",
        "0",
        "1.5707963267948966",
        "0",
        "--format",
        "json",
    )
    tensor = json.loads(result.output)["about"]["inertia"]
    np.testing.assert_allclose(
        np.diag(tensor), [0.005, (3 * 0.01 + 1) / 12, (3 * 0.01 + 1) / 12], rtol=1e-12
    )


def test_mesh_in_millimetres_with_scale(tmp_path):
    trimesh = pytest.importorskip("trimesh")
    path = tmp_path / "part.stl"
    # a 100 × 200 × 300 mm block, authored in millimetres
    trimesh.creation.box(extents=(100, 200, 300)).export(path)
    result = run("mesh", str(path), "--density", "2700", "--scale", "0.001", "--format", "json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    m = 2700 * 0.1 * 0.2 * 0.3
    assert data["mass"] == pytest.approx(m, rel=1e-9)
    np.testing.assert_allclose(
        np.diag(data["inertia"]),
        [m * (0.04 + 0.09) / 12, m * (0.01 + 0.09) / 12, m * (0.01 + 0.04) / 12],
        rtol=1e-9,
    )
    assert data["mesh"]["method"] == "exact"
    assert data["mesh"]["triangles"] == 12
    text = run("mesh", str(path), "--density", "2700", "--scale", "0.001")
    assert "mesh: 12 triangles, exact" in text.output


def test_open_mesh_reports_its_error_bound(tmp_path):
    trimesh = pytest.importorskip("trimesh")
    box = trimesh.creation.box(extents=(1, 1, 1))
    open_box = trimesh.Trimesh(box.vertices, box.faces[2:], process=False)
    path = tmp_path / "open.stl"
    open_box.export(path)
    result = run("mesh", str(path))
    assert result.exit_code == 0, result.output
    assert "convex-hull (volume error up to" in result.output


def test_text_report_of_a_capsule_about_turned_axes():
    """The whole text, as the command printed it before the report moved out of the CLI."""
    part = Part({"shape": "capsule", "radius": 0.1, "length": 0.3}, capsule(0.1, 0.3, density=1.0))
    text = render(
        part,
        density=None,
        mass_kg=None,
        xyz=(0.0, 0.0, 0.0),
        rpy=(0.0, 0.0, 0.0),
        about=None,
        about_rpy=(0.0, 1.0, 0.0),
        output_format="text",
    )
    assert text == (
        "capsule radius 0.1 m, length 0.3 m, density 1000 kg/m³\n"
        "mass:   13.6136 kg   (volume 0.0136136 m³, density 1000 kg/m³)\n"
        "centre of mass: (0, 0, 0) m\n"
        "inertia about the centre of mass, link axes (kg·m²):\n"
        "  ixx     0.25237   iyy     0.25237   izz    0.063879\n"
        "  ixy           0   ixz           0   iyz           0\n"
        "principal moments: (0.063879, 0.25237, 0.25237) kg·m²; radii of gyration "
        "(0.0685, 0.13616, 0.13616) m\n"
        "inertia about (0, 0, 0) m, axes rotated by rpy (0, 1, 0) (kg·m²):\n"
        "  ixx     0.11891   iyy     0.25237   izz     0.19735\n"
        "  ixy           0   ixz    0.085699   iyz           0\n"
        "URDF:\n"
        "<inertial>\n"
        '  <origin xyz="0 0 0" rpy="0 0 0"/>\n'
        '  <mass value="13.6136"/>\n'
        '  <inertia ixx="0.252375" ixy="0" ixz="0" iyy="0.252375" iyz="0" izz="0.0638791"/>\n'
        "</inertial>"
    )
