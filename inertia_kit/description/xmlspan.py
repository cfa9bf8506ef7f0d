"""
Where an element stands in the original text: from the ``<`` of its start tag to just after its
end tag, by scanning the markup (comments, CDATA, processing instructions and quoted attribute
values are skipped whole). With it, an edit can replace or insert one element and leave every
other byte alone.
"""

from __future__ import annotations

import functools
import re
from dataclasses import dataclass

from inertia_kit.description.lines import line_start

_NAME = r"[A-Za-z_:][-A-Za-z0-9_.:]*"
_TOKEN = re.compile(
    r"<!--.*?-->"  # comment
    r"|<!\[CDATA\[.*?\]\]>"  # CDATA
    r"|<\?.*?\?>"  # processing instruction
    r"|<!DOCTYPE(?:[^\[>]*\[.*?\])?[^>]*>"  # DOCTYPE
    rf"|</\s*({_NAME})\s*>"  # end tag: group 1
    rf"|<({_NAME})((?:\s+{_NAME}\s*=\s*(?:\"[^\"]*\"|'[^']*'))*)\s*(/?)>",  # start tag: 2, 3, 4
    re.DOTALL,
)


_INDENT = re.compile(r"[ \t]*")


@dataclass(frozen=True)
class Span:
    """An element in the text: ``text[start:end]`` is the whole element."""

    start: int
    end: int
    start_tag_end: int  # just after the start tag's ">"
    end_tag_start: int  # where "</tag>" begins (== end for an empty-element tag)
    tag: str
    empty: bool  # written as <tag .../>


def tokens(text: str):
    """Every markup token of ``text`` in order (comments, start and end tags, ...), as matches."""
    return _TOKEN.finditer(text)


def element_span(text: str, start: int) -> Span:
    """
    The span of the element whose start tag begins at ``start`` (the offset of its ``<``).

    Raises ``ValueError`` if there is no well-formed element there.
    """
    first = _TOKEN.match(text, start)
    if first is None or first.group(2) is None:
        raise ValueError(f"no start tag at offset {start}")
    tag = first.group(2)
    if first.group(4):
        return Span(start, first.end(), first.end(), first.end(), tag, True)
    depth = 1
    position = first.end()
    while True:
        token = _TOKEN.search(text, position)
        if token is None:
            raise ValueError(f"<{tag}> at offset {start} is never closed")
        position = token.end()
        if token.group(2) is not None and not token.group(4):
            depth += 1
        elif token.group(1) is not None:
            depth -= 1
            if depth == 0:
                if token.group(1) != tag:
                    raise ValueError(f"<{tag}> at offset {start} is closed by </{token.group(1)}>")
                return Span(start, token.end(), first.end(), token.start(), tag, False)


def children(text: str, span: Span) -> list[Span]:
    """The element children of ``span``, in order."""
    if span.empty:
        return []
    found = []
    position = span.start_tag_end
    while position < span.end_tag_start:
        token = _TOKEN.search(text, position, span.end_tag_start)
        if token is None:
            break
        if token.group(2) is not None:
            child = element_span(text, token.start())
            found.append(child)
            position = child.end
        else:
            position = token.end()
    return found


def line_indent(text: str, offset: int) -> str:
    """The whitespace that begins the line holding ``offset``."""
    return _INDENT.match(text, line_start(text, offset)).group(0)  # type: ignore[union-attr]


@functools.lru_cache(maxsize=16)
def indent_unit(text: str) -> str:
    """
    One level of the file's indentation: the most common step between a line and the next
    deeper one (two spaces, four spaces, a tab); two spaces for a file with no indentation.

    Read once per text (a fix of each of 5000 links asks it of the same file; a string's hash
    is computed once, so asking again costs nothing).
    """
    steps: dict[str, int] = {}
    previous = ""
    for line in re.split(r"\r\n|\n|\r", text):
        if not line.strip():
            continue
        indent = re.match(r"[ \t]*", line).group(0)  # type: ignore[union-attr]
        if len(indent) > len(previous) and indent.startswith(previous):
            step = indent[len(previous) :]
            steps[step] = steps.get(step, 0) + 1
        previous = indent
    return max(steps, key=lambda s: (steps[s], -len(s))) if steps else "  "
