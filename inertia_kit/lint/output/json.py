"""``json``: one array of :meth:`~inertia_kit.lint.findings.Finding.to_json` objects."""

from __future__ import annotations

from collections.abc import Sequence

from inertia_kit.lint.findings import Finding
from inertia_kit.lint.output.common import dumps, finite


def render(findings: Sequence[Finding]) -> str:
    return dumps([finite(finding.to_json()) for finding in findings]) + "\n"
