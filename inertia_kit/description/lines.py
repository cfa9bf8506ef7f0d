"""
Lines as XML counts them, in one place: ``\\r\\n``, ``\\n`` and a lone ``\\r`` each end a line
(XML 1.0 §2.11 reads each as one ``\\n``). Expat (so xacro's positions) and editors count so;
libxml2 does not: lxml's ``sourceline`` and its error positions count only ``\\n``, so a file
with a lone ``\\r`` has fewer lines for lxml than for everyone else. Every line we report, and
every line we turn back into an offset, is therefore counted here from offsets in the text,
never taken from lxml.
"""

from __future__ import annotations

import bisect
import re
from typing import AnyStr

BREAK = re.compile(r"\r\n?|\n")
_BYTES_BREAK = re.compile(rb"\r\n?|\n")


def line_starts(text: str | bytes) -> list[int]:
    """The offset where each line begins: ``[0, ...]``, one entry per line."""
    pattern = _BYTES_BREAK if isinstance(text, bytes) else BREAK
    return [0, *(match.end() for match in pattern.finditer(text))]  # type: ignore[arg-type]


def line_of(starts: list[int], offset: int) -> int:
    """The 1-based line holding ``offset``, given :func:`line_starts`."""
    return bisect.bisect_right(starts, offset)


def line_start(text: AnyStr, offset: int) -> int:
    """The offset where the line holding ``offset`` begins."""
    newline, carriage = ("\n", "\r") if isinstance(text, str) else (b"\n", b"\r")
    return max(text.rfind(newline, 0, offset), text.rfind(carriage, 0, offset)) + 1  # type: ignore[arg-type]


def line_end(text: AnyStr, offset: int) -> int:
    """The offset where the line holding ``offset`` ends (its break, or the end of the text)."""
    pattern = BREAK if isinstance(text, str) else _BYTES_BREAK
    found = pattern.search(text, offset)  # type: ignore[arg-type]
    return len(text) if found is None else found.start()


def from_libxml2(data: bytes, line: int, column: int) -> tuple[int, int]:
    """
    A position libxml2 reported in ``data`` (lines counted by ``\\n`` only) as lines are
    counted here; the column is kept as libxml2 counts it, from the start of the line.
    """
    if b"\r" not in data or line < 1:
        return line, column
    starts = [0, *(match.end() for match in re.finditer(rb"\n", data))]
    if line > len(starts):
        return line, column
    offset = min(starts[line - 1] + max(column - 1, 0), len(data))
    own = line_starts(data)
    at = line_of(own, offset)
    return at, offset - own[at - 1] + 1
