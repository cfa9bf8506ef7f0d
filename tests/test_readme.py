"""The README's inertia-lint runs print what the command prints today (they cannot drift)."""

from __future__ import annotations

import re
import shlex

import pytest
from click.testing import CliRunner
from kit import REPO

from inertia_kit.cli.lint import lint_command

ROOT = REPO
README = (ROOT / "README.md").read_text()
RUNS = re.findall(r"```console\n\$ (inertia-lint [^\n]*)\n(.*?)```", README, re.DOTALL)


def test_the_readme_has_lint_runs():
    assert len(RUNS) >= 2


@pytest.mark.parametrize("command, shown", RUNS, ids=[c for c, _ in RUNS])
def test_lint_run_in_readme(command: str, shown: str, monkeypatch):
    monkeypatch.chdir(ROOT)
    result = CliRunner().invoke(lint_command, shlex.split(command)[1:])
    assert result.stdout == shown
