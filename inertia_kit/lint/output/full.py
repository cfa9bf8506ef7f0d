"""
``full``: ``path:line:col: CODE [severity] message``, the source line with a caret under the
element, the macro body line for an element a xacro macro produced, the ``detail``, the fix and
``help``.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from inertia_kit.errors import InputError
from inertia_kit.lint.applying import applicable
from inertia_kit.lint.findings import Finding
from inertia_kit.lint.output.common import COLOURS, Style, fix_mark, location, message
from inertia_kit.printable import printable, width

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


#: the most characters of a source line shown: a longer line (a minified one-line file) is shown
#: as an excerpt around the element, so that the output grows with the findings, not with
#: findings × line length
EXCERPT = 120
#: of them, at most this many before the element's column
BEFORE = 40
_CUT = "…"
_INDENT = re.compile(r"\s*")


def _caret(text: str, column: int | None) -> tuple[str, int, int]:
    """
    The line as shown, and where the caret under the element's tag starts and how long it is
    (0: no caret), in terminal columns. Without a column, the tag the line starts with. A line
    longer than :data:`EXCERPT` is cut around the column (``…`` where it is cut); tabs are
    expanded, and characters that would break or disguise the line are shown as escapes
    (:func:`~inertia_kit.printable.printable`).
    """
    if column is None:
        indent = _INDENT.match(text, 0, EXCERPT).end()  # type: ignore[union-attr]
        column = indent + 1 if text[indent : indent + 1] == "<" else None
    if column is None or not 1 <= column <= len(text):
        column = None
        start = 0
    else:
        start = max(0, min(column - 1 - BEFORE, len(text) - EXCERPT))
    end = min(len(text), start + EXCERPT)
    shown = _Shown(_CUT if start else "")
    if column is None:
        shown.add(text, start, end)
        return shown.end(_CUT if end < len(text) else ""), 0, 0
    tag = _TAG.match(text, column - 1, end)
    tag_end = tag.end() if tag else column
    shown.add(text, start, column - 1)
    offset = shown.columns
    shown.add(text, column - 1, max(tag_end, column))
    length = shown.columns - offset
    shown.add(text, max(tag_end, column), end)
    return shown.end(_CUT if end < len(text) else ""), offset, length


class _Shown:
    """A source line being shown, and the terminal columns it takes so far."""

    def __init__(self, start: str):
        self.parts = [start]
        self.columns = len(start)

    def add(self, text: str, start: int, end: int) -> None:
        for char in text[start:end]:
            # a tab is layout: to the next tab stop of 4
            shown = " " * (4 - self.columns % 4) if char == "\t" else printable(char)
            self.parts.append(shown)
            self.columns += width(char) if shown == char else len(shown)

    def end(self, cut: str) -> str:
        return "".join(self.parts) + cut


def _block(finding: Finding, style: Style, sources: _Sources, unsafe_fixes: bool) -> str:
    colour = COLOURS[finding.severity]
    # every text from the files is escaped here (names, paths, values): it stays on its line
    header = (
        f"{style(location(printable(finding.path), finding.line, finding.column), bold=True)}: "
        f"{style(finding.code, fg=colour, bold=True)} {fix_mark(finding, unsafe_fixes)}"
        f"{style(f'[{finding.severity}]', fg=colour)} {printable(message(finding))}"
    )
    lines = [header]
    snippets = [(finding.path, finding.line, finding.column)]
    if finding.macro_path is not None:
        snippets.append((finding.macro_path, finding.macro_line, None))
    digits = max((len(str(line)) for _, line, _ in snippets if line is not None), default=1)
    gutter = " " * digits
    for index, (path, number, column) in enumerate(snippets):
        if index:
            lines.append(
                f"{gutter} {style('=', bold=True)} in the macro body: "
                f"{location(printable(path), number, None)}"
            )
        text = sources.line(path, number)
        if text is None:
            continue
        shown, offset, length = _caret(text, column)
        lines.append(f"{gutter} {style('|', bold=True)}")
        lines.append(f"{number:>{digits}} {style('|', bold=True)} {shown}")
        if length:
            lines.append(
                f"{gutter} {style('|', bold=True)} "
                + " " * offset
                + style("^" * length, fg=colour, bold=True)
            )
    if finding.detail:
        detail = printable(finding.detail)
        lines.append(f"{gutter} {style('=', bold=True)} {style('detail', bold=True)}: {detail}")
    if finding.fix is not None and applicable(finding, unsafe_fixes):
        title = printable(finding.fix.title)
        lines.append(f"{gutter} {style('=', bold=True)} {style('fix', bold=True)}: {title}")
    elif finding.unfixable is not None:
        lines.append(f"{gutter} {style('=', bold=True)} no fix: {printable(finding.unfixable)}")
    if finding.help:
        help_text = printable(finding.help)
        lines.append(f"{gutter} {style('=', bold=True)} {style('help', bold=True)}: {help_text}")
    return "\n".join(line.rstrip() for line in lines)
