"""
``--redact-env`` (``redact-environment = true``): what xacro read from the environment
(``$(env)``, ``$(optenv)``, YAML files it loads) reaches a link name, a joint name, a mesh path
and a mass; it appears in no output of any command or format, while the files written stay
exactly as without the option.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from kit import write
from kit.in_process import lint_in_process, run_split

from inertia_kit.cli import main

ENVIRONMENT = {
    "SECRET_NAME": "hunter2tok",  # a link name
    "SECRET_MASS": "31337.25",  # a mass (printed as 31337)
    "SECRET_DIR": "/nonexistent/s3cr3t-dir",  # a mesh path
}
YAML_SECRET = "yamlsecret42"  # a joint and a link name, from a YAML file
# what must not be seen: each value, and the mass as messages print it
SECRETS = ("hunter2tok", "31337.25", "31337 kg", "s3cr3t-dir", YAML_SECRET)

ROBOT = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="cfg" value="${xacro.load_yaml('secrets.yaml')}"/>
  <link name="base_$(env SECRET_NAME)"/>
  <joint name="j_${cfg['token']}" type="revolute">
    <parent link="base_$(env SECRET_NAME)"/><child link="arm_${cfg['token']}"/>
    <axis xyz="0 0 1"/>
  </joint>
  <link name="arm_${cfg['token']}">
    <inertial>
      <mass value="$(env SECRET_MASS)"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
    <visual><geometry><mesh filename="$(env SECRET_DIR)/arm.stl"/></geometry></visual>
  </link>
  <link name="wheel_$(optenv SECRET_NAME unset)">
    <collision><geometry><cylinder radius="0.1" length="0.05"/></geometry></collision>
  </link>
  <joint name="w" type="continuous">
    <parent link="arm_${cfg['token']}"/><child link="wheel_$(optenv SECRET_NAME unset)"/>
  </joint>
</robot>
"""
# a robot whose expansion fails, quoting a path the environment gave
BROKEN = """<robot name="b" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(env SECRET_DIR)/parts.xacro"/><link name="a"/>
</robot>
"""


@pytest.fixture
def robots(tmp_path, monkeypatch):
    lint_in_process(monkeypatch)
    monkeypatch.chdir(tmp_path)
    for name, value in ENVIRONMENT.items():
        monkeypatch.setenv(name, value)
    write(tmp_path / "secrets.yaml", f"token: {YAML_SECRET}\n")
    write(tmp_path / "robot.urdf.xacro", ROBOT)
    write(tmp_path / "broken.urdf.xacro", BROKEN)
    return tmp_path


def run(*args: str) -> tuple[int, str, str]:
    return run_split(main, args)


def seen(*texts: str) -> set[str]:
    """The secrets that ``texts`` show."""
    return {secret for secret in SECRETS for text in texts if secret in text}


LINT = [
    *(("--output-format", f) for f in ("full", "concise", "json", "github", "sarif", "junit")),
    ("--output-format", "gitlab"),
    ("--statistics",),
    ("--diff", "--unsafe-fixes"),
    ("--unsafe-fixes", "--output-format", "json"),
]


@pytest.mark.parametrize("options", LINT, ids=" ".join)
def test_lint(robots, options):
    without = run("lint", *options, "robot.urdf.xacro", "broken.urdf.xacro")
    code, out, err = run("lint", "--redact-env", *options, "robot.urdf.xacro", "broken.urdf.xacro")
    assert code == without[0] and not seen(out, err), (out, err)
    if "--output-format" in options:
        # without the option: every one shown (the mass as given only in expected values)
        assert seen(*without[1:]) >= set(SECRETS) - {"31337.25"}
        assert "***" in out and "error: broken.urdf.xacro:" in err
    if "json" in options or "sarif" in options or "gitlab" in options:
        json.loads(out)  # still valid


def test_lint_into_a_file(robots):
    for output_format in ("full", "json"):
        run("lint", "--redact-env", "-o", "report", "--output-format", output_format, ".")
        assert not seen(Path("report").read_text())


def test_the_configuration_key(robots):
    write(robots / "pyproject.toml", "[tool.inertia-kit]\nredact-environment = true\n")
    assert not seen(*run("lint", "--output-format", "json", "robot.urdf.xacro")[1:])
    assert seen(*run("lint", "--no-redact-env", "robot.urdf.xacro")[1:])


@pytest.mark.parametrize("options", [(), ("--diff",), ("--check",), ("--fix", "all")], ids=str)
def test_fill_messages(robots, options):
    without = run("fill", *options, "robot.urdf.xacro", "broken.urdf.xacro")
    shutil.copy(robots / "robot.urdf.xacro", robots / "again.urdf.xacro")
    code, out, err = run("fill", "--redact-env", *options, "again.urdf.xacro", "broken.urdf.xacro")
    assert code == without[0] and not seen(out, err), (out, err)
    assert seen(*without[1:]) and "***" in err


@pytest.mark.parametrize("lumped", [(), ("--lumped",)], ids=["links", "lumped"])
@pytest.mark.parametrize("output_format", ["text", "markdown", "json"])
def test_report(robots, output_format, lumped):
    options = ("report", "--format", output_format, *lumped, "robot.urdf.xacro")
    assert seen(*run(*options)[1:])
    code, out, err = run(*options[:1], "--redact-env", *options[1:])
    assert code == 0 and not seen(out, err)
    if output_format == "json":
        json.loads(out)
    if output_format == "text":  # the columns aligned on the redacted cells
        lines = out.splitlines()
        for at, rule in enumerate(lines):
            if not rule.startswith("--"):
                continue
            starts = [i for i, c in enumerate(rule) if c == "-" and i and rule[i - 1] == " "]
            for line in lines[at + 1 :]:
                footer = line.startswith(("total", "dropped", "note")) or " bodies from " in line
                if not line.strip() or footer:
                    break
                assert all(line[i - 2 : i] == "  " and line[i] != " " for i in starts), line
    code, out, err = run("report", "--redact-env", "broken.urdf.xacro")
    assert code == 2 and not seen(out, err) and "***/parts.xacro" in err


def test_view(robots):
    run("view", "robot.urdf.xacro", "-o", "plain.html")
    assert seen(Path("plain.html").read_text(encoding="utf-8"))
    code, out, err = run("view", "--redact-env", "robot.urdf.xacro", "-o", "page.html")
    assert code == 0 and not seen(out, err, Path("page.html").read_text(encoding="utf-8"))
    code, out, err = run("view", "--redact-env", "broken.urdf.xacro", "-o", "page.html")
    assert code == 2 and not seen(out, err) and "***/parts.xacro" in err


# --- the files written are those written without the option ----------------------------------


def _written(robots: Path, *command: str) -> dict[str, bytes]:
    """The files of a fresh copy of the robot after ``command`` (``{}`` as the robot's path)."""
    folder = robots / f"run{len(list(robots.glob('run*')))}"
    folder.mkdir()
    for name in ("robot.urdf.xacro", "secrets.yaml"):
        shutil.copy(robots / name, folder / name)
    run(*(part.format(folder) for part in command))
    return {path.name: path.read_bytes() for path in sorted(folder.iterdir())}


@pytest.mark.parametrize(
    "command",
    [
        ("fill", "--fix", "all", "{}/robot.urdf.xacro"),
        ("fill", "-o", "{}/filled.urdf", "{}/robot.urdf.xacro"),
        ("lint", "--fix", "--unsafe-fixes", "{}/robot.urdf.xacro"),
    ],
    ids=["fill", "fill -o", "lint --fix"],
)
def test_the_files_written_are_unchanged_by_the_option(robots, command):
    plain = _written(robots, *command)
    redacted = _written(robots, command[0], "--redact-env", *command[1:])
    assert redacted == plain
    assert plain["robot.urdf.xacro"] != ROBOT.encode() or "filled.urdf" in plain
    if "filled.urdf" in plain:  # xacro's semantics: the expanded robot holds the values
        assert b"hunter2tok" in plain["filled.urdf"]
