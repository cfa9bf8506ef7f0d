"""
Where elements and comments stand in a file's text (character offsets and lines), so that a
suppression comment can be inserted before an element, extended, or removed, leaving every
other byte alone. Lines are counted as XML counts them (:mod:`inertia_kit.description.lines`),
and :mod:`inertia_kit.lint.suppress` reads comments through this module, so a comment written
here covers what that module says it covers.
"""

from __future__ import annotations

import bisect
import re
from dataclasses import dataclass, field

from inertia_kit.description.lines import line_starts
from inertia_kit.description.xmlspan import tokens

# `inertia-lint: ignore[...]`: group 1 is what stands between the brackets
_IGNORE = re.compile(r"\s*inertia-lint\s*:\s*ignore\s*\[([^\]]*)\]", re.DOTALL)


@dataclass(frozen=True)
class Comment:
    """``<!--body-->`` at ``text[start:end]``, beginning on ``line``."""

    start: int
    end: int
    line: int
    body: str

    def selectors(self) -> tuple[int, int, list[str]] | None:
        """
        For an ``ignore[...]`` comment: the offsets of what stands between its brackets and the
        entries there as written (stripped, empty ones left out); ``None`` for other comments.
        """
        match = _IGNORE.match(self.body)
        if match is None:
            return None
        first = self.start + len("<!--") + match.start(1)
        items = [item.strip() for item in match.group(1).split(",") if item.strip()]
        return first, first + len(match.group(1)), items


@dataclass
class Element:
    """
    An element at ``text[start:end]``, on lines ``first`` to ``last``; ``before`` the comments
    between it and the markup before it (its previous sibling or its parent's start tag).
    """

    start: int
    end: int
    first: int
    last: int
    parent: Element | None
    before: list[Comment] = field(default_factory=list)


@dataclass
class Layout:
    """A file's elements (document order) and comments."""

    text: str
    elements: list[Element]
    comments: list[Comment]
    line_starts: list[int]
    _starts: list[int] = field(default_factory=list, repr=False)
    _on_line: dict[int, Element | None] = field(default_factory=dict, repr=False)

    def __post_init__(self) -> None:
        self._starts = [element.start for element in self.elements]

    @property
    def root(self) -> Element | None:
        return self.elements[0] if self.elements else None

    def innermost(self, line: int, column: int | None = None) -> Element | None:
        """
        The innermost element at ``line`` and ``column`` (1-based, the ``<`` of its start tag or
        a place inside it); without a column, or with one no element holds, the smallest
        element whose lines hold ``line`` (the first such in document order).

        Found among the few that can be (the last element starting before the place and its
        ancestors; the elements starting on the line), not all: ``--add-noqa`` asks it of
        each finding.
        """
        if column is not None and 1 <= line <= len(self.line_starts):
            found = self._holding(self.line_starts[line - 1] + column - 1)
            if found is not None:
                return found
        if line not in self._on_line:
            self._on_line[line] = self._smallest_on(line)
        return self._on_line[line]

    def _holding(self, offset: int) -> Element | None:
        """The innermost element whose text holds ``offset``."""
        index = bisect.bisect_right(self._starts, offset) - 1
        element = self.elements[index] if index >= 0 else None
        while element is not None and not element.start <= offset < element.end:
            element = element.parent
        return element

    def _smallest_on(self, line: int) -> Element | None:
        if not 1 <= line <= len(self.line_starts):
            return None
        begin = self.line_starts[line - 1]
        end = self.line_starts[line] if line < len(self.line_starts) else len(self.text)
        first = bisect.bisect_left(self._starts, begin)
        last = bisect.bisect_left(self._starts, end)
        candidates = {id(e): e for e in self.elements[first:last]}  # starting on the line
        above = self._holding(begin)
        while above is not None:  # and what holds the line's start, out to the root
            candidates[id(above)] = above
            above = above.parent
        holding = sorted(
            (e for e in candidates.values() if e.first <= line <= e.last), key=lambda e: e.start
        )
        return min(holding, key=lambda e: e.last - e.first, default=None)

    def comment_on(self, line: int) -> Comment | None:
        """The first comment that begins on ``line``."""
        return next((c for c in self.comments if c.line == line), None)

    def line_of(self, offset: int) -> int:
        return bisect.bisect_right(self.line_starts, offset)


def layout(text: str) -> Layout:
    """The elements and comments of ``text`` (well-formed XML: the loader has parsed it)."""
    starts = line_starts(text)

    def line(offset: int) -> int:
        return bisect.bisect_right(starts, offset)

    elements: list[Element] = []
    comments: list[Comment] = []
    open_: list[Element] = []
    pending: list[Comment] = []
    for token in tokens(text):
        piece = token.group(0)
        if piece.startswith("<!--"):
            comment = Comment(token.start(), token.end(), line(token.start()), piece[4:-3])
            comments.append(comment)
            pending.append(comment)
        elif token.group(2) is not None:  # a start tag
            parent = open_[-1] if open_ else None
            element = Element(token.start(), token.end(), line(token.start()), 0, parent, pending)
            elements.append(element)
            pending = []
            if token.group(4):  # <x/>: ends where its tag ends
                element.last = line(token.end() - 1)
            else:
                open_.append(element)
        elif token.group(1) is not None and open_:  # an end tag
            element = open_.pop()
            element.end, element.last = token.end(), line(token.start())
            pending = []
    return Layout(text, elements, comments, starts)
