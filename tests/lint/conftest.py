"""Fixtures the lint tests share."""

from __future__ import annotations

import pytest
from kit.in_process import lint_in_process
from stub_rules import HEAVY, OTHER

from inertia_kit.lint import catalog


@pytest.fixture
def stub_rules(monkeypatch):
    """The two stub rules of stub_rules.py as the whole catalogue."""
    monkeypatch.setattr(catalog, "RULES", (HEAVY, OTHER))
    lint_in_process(monkeypatch)
