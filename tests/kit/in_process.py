"""
Linting in the test's own process: what a test patches (stub rules as the catalogue, a
failing analysis) exists in this process only, not in ``inertia-lint -j``'s worker processes.
"""

from __future__ import annotations

from inertia_kit.lint import parallel


def lint_in_process(monkeypatch) -> None:
    """Every run in this test lints in this process, as ``-j 1`` does."""
    monkeypatch.setattr(parallel, "worker_count", lambda jobs, files: 1)
