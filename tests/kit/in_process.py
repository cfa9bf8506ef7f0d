"""
Linting in the test's own process: what a test patches (stub rules as the catalogue, a
failing analysis) exists in this process only, not in ``inertia-lint -j``'s worker processes.
"""

from __future__ import annotations

from inertia_kit.lint import parallel


def lint_in_process(monkeypatch) -> None:
    """Every run in this test lints in this process, as ``-j 1`` does."""
    monkeypatch.setattr(parallel, "worker_count", lambda jobs, files: 1)


def run_split(command, args, input: str | None = None) -> tuple[int, str, str]:
    """``command`` run by click's test runner with stdout and stderr apart: ``(exit code,
    stdout, stderr)``; exceptions propagate."""
    from click.testing import CliRunner

    try:
        runner = CliRunner(mix_stderr=False)  # click < 8.2
    except TypeError:
        runner = CliRunner()
    result = runner.invoke(command, list(args), input=input, catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr
