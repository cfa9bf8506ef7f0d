"""``github``: workflow commands that GitHub Actions shows as annotations."""

from __future__ import annotations

from collections.abc import Sequence

from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.output.common import location, message

_LEVELS = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "notice"}


def render(findings: Sequence[Finding]) -> str:
    return "".join(_command(finding) + "\n" for finding in findings)


def _escape_data(text: str) -> str:
    """A workflow command's message (GitHub's ``escapeData``)."""
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def _escape_property(text: str) -> str:
    """A workflow command's property value (GitHub's ``escapeProperty``)."""
    return _escape_data(text).replace(":", "%3A").replace(",", "%2C")


def _command(finding: Finding) -> str:
    properties = [("title", f"inertia-lint ({finding.code})"), ("file", finding.path)]
    if finding.line is not None:
        properties.append(("line", str(finding.line)))
        if finding.column is not None:
            properties.append(("col", str(finding.column)))
    head = ",".join(f"{key}={_escape_property(value)}" for key, value in properties)
    where = location(finding.path, finding.line, finding.column)
    text = f"{where}: {finding.code} {message(finding)}"
    if finding.help:
        text += f"\nhelp: {finding.help}"
    return f"::{_LEVELS[finding.severity]} {head}::{_escape_data(text)}"
