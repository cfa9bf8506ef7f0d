"""
One mesh authored in mm, judged the same by the three commands (analysis.mesh_units decides):
IN031 in inertia-lint, inertia-fill's refusal, and inertia-kit mass mesh's warning.
"""

from __future__ import annotations

import json
from pathlib import Path

from click.testing import CliRunner
from kit.meshes import write_box_stl
from kit.urdf import joint, link, mesh, moving

from inertia_kit.cli import lint_main, main
from inertia_kit.cli.fill import fill_command

# a 150 × 100 × 40 mm part, its file in mm
SIZE_MM = (150.0, 100.0, 40.0)


def _robot(tmp_path: Path) -> tuple[Path, Path]:
    part = write_box_stl(tmp_path / "part.stl", SIZE_MM)
    body = f"<collision><geometry>{mesh(str(part))}</geometry></collision>"
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(moving(body, joint("arm", "tip", xyz=(0, 0, 0.2)) + link("tip")))
    return urdf, part


def test_lint_fill_and_mass_mesh_agree_on_millimetres(tmp_path: Path):
    urdf, part = _robot(tmp_path)
    before = urdf.read_text()

    linted = CliRunner().invoke(
        lint_main, ["--select", "IN031", "--output-format", "json", str(urdf)]
    )
    assert linted.exit_code == 1, linted.output
    (finding,) = json.loads(linted.stdout)
    assert finding["code"] == "IN031"
    assert finding["expected"]["scale"] == [0.001, 0.001, 0.001]

    filled = CliRunner().invoke(fill_command, [str(urdf)])
    assert "IN031" in filled.stderr and 'scale="0.001 0.001 0.001"' in filled.stderr
    assert urdf.read_text() == before

    measured = CliRunner().invoke(main, ["mass", "mesh", str(part)])
    assert measured.exit_code == 0
    assert "spans 150 m as scaled: it looks authored in mm" in measured.stderr
    assert "pass --scale 0.001 (it then spans 0.15 m)" in measured.stderr
    assert "<inertial>" not in measured.stdout
    assert "URDF: none: the mesh looks authored in other units" in measured.stdout


def test_mass_mesh_prints_the_block_once_the_unit_is_settled(tmp_path: Path):
    _, part = _robot(tmp_path)
    scaled = CliRunner().invoke(main, ["mass", "mesh", str(part), "--scale", "0.001"])
    assert scaled.exit_code == 0 and scaled.stderr == ""
    # 0.15 × 0.1 × 0.04 m at 1000 kg/m³: 0.6 kg
    assert '<mass value="0.6"/>' in scaled.stdout
    trusted = CliRunner().invoke(main, ["mass", "mesh", str(part), "--trust-units"])
    assert "looks authored in mm" in trusted.stderr
    assert '<mass value="600000000"/>' in trusted.stdout


def test_mass_mesh_density_is_evidence_too(tmp_path: Path):
    """--mass 0.6 kg in the mm file's 600 000 m³ is 1e-6 kg/m³, no material: said too."""
    _, part = _robot(tmp_path)
    light = CliRunner().invoke(main, ["mass", "mesh", str(part), "--mass", "0.6"])
    assert "no robot part is that large; 0.6 kg in it is 1e-06 kg/m³" in light.stderr
    metres = write_box_stl(tmp_path / "metres.stl", [v / 1000 for v in SIZE_MM])
    plain = CliRunner().invoke(main, ["mass", "mesh", str(metres), "--mass", "0.6"])
    assert plain.stderr == "" and '<mass value="0.6"/>' in plain.stdout
