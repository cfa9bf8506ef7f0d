"""The files every output-format test lints, with the stub rules as the catalogue."""

from __future__ import annotations

import pytest
from kit.in_process import lint_in_process
from output_kit import FILES, STUBS

from inertia_kit.lint import catalog


@pytest.fixture
def robots(tmp_path, monkeypatch):
    """The fixture files in the current folder, and the stub rules as the registry."""
    for name, text in FILES.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(catalog, "RULES", STUBS)
    lint_in_process(monkeypatch)
    monkeypatch.delenv("FORCE_COLOR", raising=False)
    return tmp_path
