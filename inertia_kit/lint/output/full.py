"""
``full``: ``path:line:col: CODE [severity] message``, the source line with a caret under the
element, the macro body line for an element a xacro macro produced, and ``help``.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from inertia_kit.errors import InputError
from inertia_kit.lint.applying import applicable
from inertia_kit.lint.findings import Finding
from inertia_kit.lint.output.common import COLOURS, Style, fix_mark, location, message

_TAG = re.compile(r"<[^\s/>]*")


def render(findings: Sequence[Finding], style: Style, unsafe_fixes: bool = False) -> str:
    sources = _Sources()
    blocks = [_block(finding, style, sources, unsafe_fixes) for finding in findings]
    return "".join(block + "\n\n" for block in blocks)


class _Sources:
    """Lines of the files findings point at, read once each."""

    def __init__(self) -> None:
        self._lines: dict[str, list[str] | None] = {}

    def line(self, path: str | None, number: int | None) -> str | None:
        if not path or number is None or number < 1:
            return None
        if path not in self._lines:
            self._lines[path] = self._read(path)
        lines = self._lines[path]
        return lines[number - 1] if lines is not None and number <= len(lines) else None

    @staticmethod
    def _read(path: str) -> list[str] | None:
        from inertia_kit.description.edits import decode_source
        from inertia_kit.description.lines import BREAK
        from inertia_kit.description.safexml import read_bounded

        try:
            data = read_bounded(path)
        except InputError:
            return None
        try:  # lines as the positions count them (a lone CR ends one), in the file's encoding
            text = decode_source(data, path).text
        except InputError:
            text = data.decode("utf-8", "replace").removeprefix("\ufeff")
        return BREAK.split(text)


def _caret(text: str, column: int | None) -> tuple[str, int, int]:
    """
    The line as shown (tabs expanded), and where the caret under the element's tag starts and
    how long it is (0: no caret). Without a column, the tag the line starts with.
    """
    shown = text.expandtabs(4)
    if column is None:
        indent = len(text) - len(text.lstrip())
        column = indent + 1 if text[indent : indent + 1] == "<" else None
    if column is None or not 1 <= column <= len(text):
        return shown, 0, 0
    tag = _TAG.match(text, column - 1)
    return shown, len(text[: column - 1].expandtabs(4)), len(tag.group()) if tag else 1


def _block(finding: Finding, style: Style, sources: _Sources, unsafe_fixes: bool) -> str:
    colour = COLOURS[finding.severity]
    header = (
        f"{style(location(finding.path, finding.line, finding.column), bold=True)}: "
        f"{style(finding.code, fg=colour, bold=True)} {fix_mark(finding, unsafe_fixes)}"
        f"{style(f'[{finding.severity}]', fg=colour)} {message(finding)}"
    )
    lines = [header]
    snippets = [(finding.path, finding.line, finding.column)]
    if finding.macro_path is not None:
        snippets.append((finding.macro_path, finding.macro_line, None))
    width = max((len(str(line)) for _, line, _ in snippets if line is not None), default=1)
    gutter = " " * width
    for index, (path, number, column) in enumerate(snippets):
        if index:
            lines.append(
                f"{gutter} {style('=', bold=True)} in the macro body: "
                f"{location(path, number, None)}"
            )
        text = sources.line(path, number)
        if text is None:
            continue
        shown, offset, length = _caret(text, column)
        lines.append(f"{gutter} {style('|', bold=True)}")
        lines.append(f"{number:>{width}} {style('|', bold=True)} {shown}")
        if length:
            lines.append(
                f"{gutter} {style('|', bold=True)} "
                + " " * offset
                + style("^" * length, fg=colour, bold=True)
            )
    if finding.fix is not None and applicable(finding, unsafe_fixes):
        lines.append(
            f"{gutter} {style('=', bold=True)} {style('fix', bold=True)}: {finding.fix.title}"
        )
    elif finding.unfixable is not None:
        lines.append(f"{gutter} {style('=', bold=True)} no fix: {finding.unfixable}")
    if finding.help:
        lines.append(f"{gutter} {style('=', bold=True)} {style('help', bold=True)}: {finding.help}")
    return "\n".join(line.rstrip() for line in lines)
