"""
Shared fixtures: lint a robot text, and a private mesh cache for every test.

This file sits at the root of tests/, which has no ``__init__.py``: pytest's default import mode
puts this folder on ``sys.path``, so ``from kit import ...`` works in every subfolder, and each
test module is imported by its file name, which must therefore be unique across the folders.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings
from kit import write

from inertia_kit.lint.findings import Finding
from inertia_kit.lint.runner import Selection, lint_file

# Hypothesis (tests/test_properties.py): in CI a fixed set of examples, the same every run and
# bounded in time; INERTIA_KIT_HYPOTHESIS_EXAMPLES=N runs N random examples per test instead,
# and keeps failing ones in .hypothesis/ to replay them
_QUIET = [HealthCheck.function_scoped_fixture, HealthCheck.too_slow, HealthCheck.data_too_large]
settings.register_profile(
    "ci", max_examples=200, derandomize=True, database=None, deadline=None,
    suppress_health_check=_QUIET, print_blob=True,
)  # fmt: skip
settings.register_profile(
    "long", max_examples=int(os.environ.get("INERTIA_KIT_HYPOTHESIS_EXAMPLES") or 0) or 1,
    deadline=None, suppress_health_check=_QUIET, print_blob=True,
)  # fmt: skip
settings.load_profile("long" if os.environ.get("INERTIA_KIT_HYPOTHESIS_EXAMPLES") else "ci")


def lint_text(
    text: str, tmp_path: Path, select: tuple[str, ...] = ("IN0",), name: str = "robot.urdf", **kw
) -> list[Finding]:
    """Lint ``text`` written to ``tmp_path/name``; raise if the file is unreadable."""
    path = write(tmp_path / name, text)
    result = lint_file(path, Selection(select=select, **kw))
    if result.error is not None:
        raise result.error
    return result.findings


@pytest.fixture(autouse=True)
def _private_mesh_cache(tmp_path_factory, monkeypatch):
    """Tests never write to the user's ~/.cache: each session gets its own mesh cache."""
    monkeypatch.setenv("INERTIA_KIT_CACHE_DIR", str(tmp_path_factory.getbasetemp() / "mesh-cache"))


@pytest.fixture
def lint(tmp_path):
    """``lint(text, select=("IN020",), options={...})`` → the findings of those rules."""

    def run(text: str, select: tuple[str, ...] | str = ("IN0",), **kw) -> list[Finding]:
        if isinstance(select, str):
            select = (select,)
        return lint_text(text, tmp_path, select, **kw)

    return run
