"""
The runner: which rules a selection runs (configuration and command line), options, severities
and per-file ignores reaching the rules, checked selectors, duplicates, findings without a place.
"""

from __future__ import annotations

import types
from pathlib import Path

import pytest
from stub_rules import HEAVY, OTHER, ROBOT, write

from inertia_kit.errors import ConfigError
from inertia_kit.lint import catalog
from inertia_kit.lint.config import Config
from inertia_kit.lint.findings import Severity
from inertia_kit.lint.paths import lint_paths
from inertia_kit.lint.runner import Selection, selection_for

pytestmark = pytest.mark.usefixtures("stub_rules")


def test_selection_from_config_and_command_line():
    config = Config(
        select=("IN09",),
        extend_select=("IN012",),
        ignore=("IN099",),
        options={"IN098": {"limit": 3.0}},
        severities={"IN098": Severity.ERROR},
    )
    selection = selection_for(config)
    assert (selection.select, selection.ignore) == (("IN09", "IN012"), ("IN099",))
    assert selection.options == {"IN098": {"limit": 3.0}}
    assert selection.severities == {"IN098": Severity.ERROR}
    assert selection.enabled([HEAVY, OTHER]) == [HEAVY]
    # --ignore adds to the configured ignores
    assert selection_for(config, ignore=("IN098",)).enabled([HEAVY, OTHER]) == []
    # --select replaces the configured select *and* ignore (ruff's rule)
    chosen = selection_for(config, select=("IN099",))
    assert (chosen.select, chosen.ignore) == (("IN099",), ())
    assert chosen.enabled([HEAVY, OTHER]) == [OTHER]
    assert chosen.options == config.options  # options and severities still apply
    assert selection_for(Config()).select == Selection().select == ("IN0",)


def test_config_options_severities_and_ignores_reach_the_rules(tmp_path):
    write(tmp_path / "robots" / "arm.urdf", ROBOT)
    write(tmp_path / "robots" / "legacy" / "old.urdf", ROBOT)

    def lint(text: str, **kw):
        write(tmp_path / "pyproject.toml", text)
        return {
            Path(r.path).name: [(f.code, str(f.severity)) for f in r.findings]
            for r in lint_paths([tmp_path / "robots"], **kw)
        }

    both = {"arm.urdf": [("IN098", "warning")], "old.urdf": [("IN098", "warning")]}
    assert lint("[tool.inertia-kit]\n") == both  # default limit 1 kg < 3 kg
    assert lint("[tool.inertia-kit.rules.IN098]\nlimit = 5\n") == {
        "arm.urdf": [],
        "old.urdf": [],
    }
    assert lint('[tool.inertia-kit.rules.stub-heavy]\nseverity = "info"\n') == {
        "arm.urdf": [("IN098", "info")],
        "old.urdf": [("IN098", "info")],
    }
    assert lint('[tool.inertia-kit.per-file-ignores]\n"robots/legacy/*" = ["IN09"]\n') == {
        "arm.urdf": [("IN098", "warning")],
        "old.urdf": [],
    }
    assert lint('[tool.inertia-kit]\nignore = ["IN098"]\n') == {"arm.urdf": [], "old.urdf": []}
    assert lint('[tool.inertia-kit]\nignore = ["IN098"]\n', select=("IN098",)) == both


def test_fail_on_from_config_and_command_line(tmp_path):
    write(tmp_path / "arm.urdf", ROBOT)
    write(tmp_path / "pyproject.toml", '[tool.inertia-kit]\nfail-on = "error"\n')
    (result,) = lint_paths([tmp_path / "arm.urdf"])
    assert result.fail_on is Severity.ERROR and result.findings and not result.failing
    (result,) = lint_paths([tmp_path / "arm.urdf"], fail_on=Severity.INFO)
    assert result.fail_on is Severity.INFO and result.failing == result.findings


def test_command_line_selectors_are_checked(tmp_path):
    with pytest.raises(ConfigError, match=r"--select: `IN98` is not a rule code.*`IN098`"):
        lint_paths([tmp_path], select=("IN98",))
    with pytest.raises(ConfigError, match=r"--ignore: `stub-heavyy` is not a rule.*stub-heavy"):
        lint_paths([tmp_path], ignore=("stub-heavyy",))


# --- the engine: what the selection does to what rules yield ----------------------------------


def test_run_rules_keeps_two_messages_at_one_place_and_drops_repeats(tmp_path):
    from inertia_kit.analysis.links import analyse
    from inertia_kit.description.loader import load
    from inertia_kit.lint.runner import run_rules

    rule = types.ModuleType("inertia_kit.lint.rules.in097_stub_twice")
    rule.CODE, rule.NAME, rule.SEVERITY, rule.SCOPE = "IN097", "stub-twice", Severity.ERROR, "robot"
    rule.SUMMARY = ""

    def check(robot, ctx):
        for message in ("first", "second", "first"):
            # escalating to error, which a configured severity overrides
            yield ctx.finding(message, robot.robot.source, severity=Severity.ERROR)
        yield ctx.finding("nowhere", None)

    rule.check = check
    analysis = analyse(load(write(tmp_path / "r.urdf", ROBOT)))
    findings = run_rules(analysis, Selection(), rules=[rule])
    assert [(f.path, f.message) for f in findings] == [
        ("", "nowhere"),
        (str(tmp_path / "r.urdf"), "first"),
        (str(tmp_path / "r.urdf"), "second"),
    ]
    quiet = run_rules(analysis, Selection(severities={"IN097": Severity.INFO}), rules=[rule])
    assert {f.severity for f in quiet} == {Severity.INFO}
    assert run_rules(analysis, Selection(ignore=("stub-twice",)), rules=[rule]) == []


def test_lint_file_places_findings_without_a_source_in_the_linted_file(tmp_path, monkeypatch):
    rule = types.ModuleType("inertia_kit.lint.rules.in097_stub_nowhere")
    rule.CODE, rule.NAME, rule.SEVERITY, rule.SCOPE = (
        "IN097",
        "stub-nowhere",
        Severity.ERROR,
        "robot",
    )
    rule.SUMMARY = ""
    rule.check = lambda robot, ctx: iter([ctx.finding("somewhere in the robot", None)])
    monkeypatch.setattr(catalog, "RULES", (rule,))
    path = write(tmp_path / "r.urdf", ROBOT)
    from inertia_kit.lint.runner import lint_file

    (finding,) = lint_file(path).findings
    assert (finding.path, finding.line) == (str(path), None)
