"""``concise``: ``path:line:col: CODE message``, one line a finding, for editors to parse."""

from __future__ import annotations

from collections.abc import Sequence

from inertia_kit.lint.findings import Finding
from inertia_kit.lint.output.common import COLOURS, Style, location, message


def render(findings: Sequence[Finding], style: Style) -> str:
    return "".join(_line(finding, style) + "\n" for finding in findings)


def _line(finding: Finding, style: Style) -> str:
    where = style(location(finding.path, finding.line, finding.column), bold=True)
    code = style(finding.code, fg=COLOURS[finding.severity], bold=True)
    return f"{where}: {code} {message(finding)}"
