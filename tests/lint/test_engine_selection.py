"""
Engine rules (IN07x) run only when their engine is chosen: `--engine` (comma-separated,
repeatable, `all`), or `engines = [...]` in the configuration; never by `--select`/`select`.
"""

from __future__ import annotations

import json
import types

import pytest
from click.testing import CliRunner

from inertia_kit.cli import lint_main
from inertia_kit.engines.vocabulary import ENGINES, Verdict
from inertia_kit.lint.findings import Severity, severity_of
from inertia_kit.lint.runner import Selection

# the root link carries 5 kg: MuJoCo fixes it to the world and drops them (IN070, a warning);
# IN041 says the same for KDL, so the tests select IN002 (quiet here) to see IN070 alone
ROBOT = """<robot name="r">
  <link name="base">
    <inertial><mass value="5"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
  </link>
  <joint name="j" type="revolute">
    <parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <link name="arm">
    <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
    </inertial>
  </link>
</robot>
"""


def run(tmp_path, *args: str):
    path = tmp_path / "robot.urdf"
    path.write_text(ROBOT)
    result = CliRunner().invoke(
        lint_main, [*args, "--select", "IN002", "--output-format", "json", str(path)]
    )
    codes = [f["code"] for f in json.loads(result.stdout)] if result.exit_code != 2 else None
    return result, codes


def _stub(code: str, engine: str | None) -> types.ModuleType:
    rule = types.ModuleType(f"inertia_kit.lint.rules.{code.lower()}_stub")
    rule.CODE, rule.NAME = code, f"stub-{code.lower()}"
    if engine is not None:
        rule.ENGINE = engine
    return rule


def test_selection_runs_engine_rules_only_by_engine():
    plain, mujoco, gazebo = _stub("IN010", None), _stub("IN070", "mujoco"), _stub("IN071", "gazebo")
    rules = [plain, mujoco, gazebo]
    assert Selection().enabled(rules) == [plain]  # the default select IN0 runs no engine
    assert Selection(select=("IN07",)).enabled(rules) == []
    assert Selection(engines=("mujoco",)).enabled(rules) == [plain, mujoco]
    assert Selection(select=(), engines=ENGINES).enabled(rules) == [mujoco, gazebo]
    assert Selection(engines=ENGINES, ignore=("IN070",)).enabled(rules) == [plain, gazebo]


def test_verdict_severity():
    assert severity_of(Verdict.REFUSES) is Severity.ERROR
    assert severity_of(Verdict.CHANGES) is Severity.WARNING
    assert severity_of(Verdict.LOADS) is None


def test_default_runs_no_engine_rule(tmp_path):
    result, codes = run(tmp_path)
    assert result.exit_code == 0 and codes == []


@pytest.mark.parametrize(
    "args",
    [
        ("--engine", "mujoco"),
        ("--engine", "gazebo,mujoco"),
        ("--engine", "kdl", "--engine", "mujoco"),
        ("--engine", "all"),
    ],
)
def test_engine_option(tmp_path, args):
    result, codes = run(tmp_path, *args)
    # the other engines' rules (IN071-IN074) may have their own say on this robot
    assert "IN070" in codes and all(code.startswith("IN07") for code in codes)
    assert result.exit_code == 1  # a warning fails at the default --fail-on


def test_select_does_not_enable_an_engine_rule(tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_text(ROBOT)
    result = CliRunner().invoke(
        lint_main, ["--select", "IN070", "--output-format", "json", str(path)]
    )
    assert result.exit_code == 0 and json.loads(result.stdout) == []


def test_ignore_disables_an_engine_rule(tmp_path):
    _, codes = run(tmp_path, "--engine", "mujoco", "--ignore", "IN070")
    assert codes == []


def test_unknown_engine_exits_2_with_the_known_ones(tmp_path):
    result, _ = run(tmp_path, "--engine", "mujoco,isaac")
    assert result.exit_code == 2
    assert result.stderr.strip() == (
        "error: --engine: unknown engine `isaac`; known: mujoco, gazebo, drake, pybullet, kdl "
        "(or `all`)"
    )


def test_help_documents_the_option():
    result = CliRunner().invoke(lint_main, ["--help"])
    assert "--engine NAMES" in result.stdout and "pybullet, kdl or all" in result.stdout


def test_configuration_engines(tmp_path):
    (tmp_path / ".inertia-kit.toml").write_text('engines = ["mujoco"]\n')
    _, codes = run(tmp_path)
    assert codes == ["IN070"]
    # --engine replaces the configured list
    _, codes = run(tmp_path, "--engine", "gazebo")
    assert "IN070" not in codes


@pytest.mark.parametrize(
    ("value", "message"),
    [
        ('"mujoco"', 'expected a list of engine names, e.g. ["mujoco"]'),
        ('["mujoco", "isaac"]', "unknown engine `isaac`; known: mujoco, gazebo, drake"),
    ],
)
def test_bad_configuration_engines_exit_2(tmp_path, value, message):
    (tmp_path / ".inertia-kit.toml").write_text(f"engines = {value}\n")
    result, _ = run(tmp_path)
    assert result.exit_code == 2
    assert "`engines`: " + message in result.stderr
