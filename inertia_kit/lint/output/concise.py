"""``concise``: ``path:line:col: CODE message``, one line a finding, for editors to parse."""

from __future__ import annotations

from collections.abc import Sequence

from inertia_kit.lint.findings import Finding
from inertia_kit.lint.output.common import COLOURS, Style, fix_mark, location, message
from inertia_kit.printable import printable


def render(findings: Sequence[Finding], style: Style, unsafe_fixes: bool = False) -> str:
    return "".join(_line(finding, style, unsafe_fixes) + "\n" for finding in findings)


def _line(finding: Finding, style: Style, unsafe_fixes: bool) -> str:
    # names, paths and values escaped: the finding stays on its one line
    where = style(location(printable(finding.path), finding.line, finding.column), bold=True)
    code = style(finding.code, fg=COLOURS[finding.severity], bold=True)
    return f"{where}: {code} {fix_mark(finding, unsafe_fixes)}{printable(message(finding))}"
