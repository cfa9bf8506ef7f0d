"""``inertia-kit rules`` (every catalogue rule, read from the rule modules) and
``python -m inertia_kit`` (the ``inertia-kit`` command, lean at start-up)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

from click.testing import CliRunner

from inertia_kit.cli import main
from inertia_kit.lint import catalog
from inertia_kit.lint.findings import Safety

WORKTREE = str(Path(__file__).resolve().parents[2])


def expected_fix(rule) -> str:
    """The fix column from the module itself: FIX's safety (a slip undone, safe only for an
    exact fit: safe/unsafe), else TEXT_FIX, else none."""
    if hasattr(rule, "FIX"):
        slip = rule.FIX.how == "slip" and rule.FIX.safety is Safety.SAFE
        return "safe/unsafe" if slip else rule.FIX.safety.value
    if hasattr(rule, "TEXT_FIX"):
        return rule.TEXT_FIX.value
    return "none"


def test_json_lists_every_catalogue_rule_with_its_module_values():
    result = CliRunner().invoke(main, ["rules", "--output-format", "json"])
    assert result.exit_code == 0, result.output
    rows = json.loads(result.stdout)
    assert [row["code"] for row in rows] == [rule.CODE for rule in catalog.RULES]
    for row, rule in zip(rows, catalog.RULES, strict=True):
        assert row == {
            "code": rule.CODE,
            "name": rule.NAME,
            "severity": rule.SEVERITY.name.lower(),
            "fix": expected_fix(rule),
            "engine": getattr(rule, "ENGINE", None),
            "formats": ",".join(getattr(rule, "DESCRIPTION_FORMATS", ("urdf", "mjcf"))),
        }


def test_the_listing_covers_each_kind_of_fix_and_the_engine_rules():
    """The catalogue has rules of every kind, so the columns above are exercised."""
    fixes = {expected_fix(rule) for rule in catalog.RULES}
    assert {Safety.SAFE.value, Safety.UNSAFE.value, "none"} <= fixes
    assert any(hasattr(rule, "TEXT_FIX") for rule in catalog.RULES)
    assert any(hasattr(rule, "ENGINE") for rule in catalog.RULES)


def test_text_has_one_aligned_row_per_rule():
    result = CliRunner().invoke(main, ["rules"])
    assert result.exit_code == 0, result.output
    header, *rows = result.stdout.splitlines()
    assert header.split() == ["code", "name", "severity", "fix", "engine", "formats"]
    assert len(rows) == len(catalog.RULES)
    for line, rule in zip(rows, catalog.RULES, strict=True):
        engine = getattr(rule, "ENGINE", None) or "-"
        assert line.split() == [
            rule.CODE,
            rule.NAME,
            rule.SEVERITY.name.lower(),
            expected_fix(rule),
            engine,
            ",".join(getattr(rule, "DESCRIPTION_FORMATS", ("urdf", "mjcf"))),
        ]
        assert line.index(rule.NAME) == header.index("name")  # aligned columns


def test_unknown_output_format_is_a_usage_error():
    result = CliRunner().invoke(main, ["rules", "--output-format", "xml"])
    assert result.exit_code == 2 and "Traceback" not in result.output


def run_module(*args: str) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": WORKTREE}
    return subprocess.run(
        [sys.executable, "-m", "inertia_kit", *args],
        capture_output=True,
        text=True,
        env=env,
        check=False,
    )


def test_python_dash_m_runs_the_inertia_kit_command():
    listed = run_module("rules", "--output-format", "json")
    assert listed.returncode == 0, listed.stderr
    assert [row["code"] for row in json.loads(listed.stdout)] == [r.CODE for r in catalog.RULES]
    helped = run_module("--help")
    assert helped.returncode == 0 and helped.stdout.startswith("Usage: inertia-kit ")
    wrong = run_module("no-such-command")
    assert wrong.returncode == 2 and "No such command" in wrong.stderr


def test_python_dash_m_imports_no_command_and_nothing_heavy():
    code = (
        "import sys, runpy\n"
        "sys.argv = ['inertia_kit', '--version']\n"
        "try:\n"
        "    runpy.run_module('inertia_kit', run_name='__main__')\n"
        "except SystemExit as exit:\n"
        "    assert exit.code in (0, None), exit.code\n"
        "heavy = {'numpy', 'trimesh', 'lxml', 'xacro', 'inertia_kit.lint.catalog'}\n"
        "heavy |= {m for m in sys.modules if m.startswith('inertia_kit.cli.') and\n"
        "          m not in ('inertia_kit.cli.guard', 'inertia_kit.cli.options')}\n"
        "assert not heavy & set(sys.modules), heavy & set(sys.modules)\n"
    )
    env = {**os.environ, "PYTHONPATH": WORKTREE}
    subprocess.run([sys.executable, "-c", code], check=True, env=env)


def test_a_slip_fix_is_listed_as_unsafe_too_where_the_seed_arm_gets_an_unsafe_one():
    """The seed simple arm's IN062 fix joins IN021's centre of mass: unsafe with
    --unsafe-fixes; the listing no longer calls IN062's fix simply safe."""
    import json as json_module

    from inertia_kit.cli import main

    listing = CliRunner().invoke(main, ["rules", "--output-format", "json"])
    (row,) = [r for r in json_module.loads(listing.output) if r["code"] == "IN062"]
    assert row["fix"] == "safe/unsafe"
    arm = str(Path(WORKTREE) / "examples/simple_arm/urdf/simple_arm.urdf.xacro")
    found = CliRunner().invoke(
        main, ["lint", "--unsafe-fixes", "--select", "IN062,IN021", "--output-format", "json", arm]
    )
    safeties = {f["fix"]["safety"] for f in json_module.loads(found.stdout) if f["code"] == "IN062"}
    assert safeties == {"unsafe"}
