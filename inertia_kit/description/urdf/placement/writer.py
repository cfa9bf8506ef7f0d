"""
Text edits on attributes and elements as written, for the values of a link's ``<inertial>``:
an attribute's value replaced (or the attribute added), text appended to a value, an element
inserted as a first child; checked against files outside the package and against two values
for one text.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

from inertia_kit.description.editing import Files, location
from inertia_kit.description.edits import Edit

if TYPE_CHECKING:
    from lxml import etree


def _attribute(name: str) -> re.Pattern[str]:
    return re.compile(rf"(\s){re.escape(name)}\s*=\s*(\"([^\"]*)\"|'([^']*)')")


class Writer:
    """The edits of one link's values, checked for files outside the package and clashes."""

    def __init__(self, files: Files):
        self.files = files
        self.edits: dict[tuple[str, int, int], str] = {}
        self.notes: list[str] = []

    def _put(self, path: str, start: int, end: int, content: str) -> str | None:
        if not self.files.editable(path):
            return f"{path} is {self.files.outside(path)}"
        spot = (path, start, end)
        if spot in self.edits and start != end and self.edits[spot] != content:
            return f"one text in {path} would need two values"
        self.edits[spot] = self.edits.get(spot, "") + content if start == end else content
        return None

    def set(self, element: etree._Element, attribute: str, value: str) -> str | None:
        """``attribute="value"`` on ``element``'s start tag: replaced, or added at its end."""
        from inertia_kit.description.xmlspan import element_span

        where = self.files.where(element)
        start = self.files.start(element)
        if where is None or start is None:
            return f"an element at line {element.sourceline} was not found"
        text = self.files.source(where.path).text
        span = element_span(text, start)
        tag = text[start : span.start_tag_end]
        found = _attribute(attribute).search(tag)
        if found is None:
            end = span.start_tag_end - (2 if span.empty else 1)
            while end > start and text[end - 1] in " \t\r\n":
                end -= 1
            return self._put(where.path, end, end, f' {attribute}="{value}"')
        group = 3 if found.group(3) is not None else 4
        return self._put(where.path, start + found.start(group), start + found.end(group), value)

    def append(self, element: etree._Element, attribute: str, addition: str) -> str | None:
        """``addition`` appended to the value of ``attribute`` (which must be written)."""
        from inertia_kit.description.xmlspan import element_span

        where, start = self.files.where(element), self.files.start(element)
        if where is None or start is None:
            return f"an element at line {element.sourceline} was not found"
        text = self.files.source(where.path).text
        tag = text[start : element_span(text, start).start_tag_end]
        found = _attribute(attribute).search(tag)
        if found is None:
            return f"`{attribute}` was not found at {location(where)}"
        quote = "'" if found.group(3) is not None else '"'
        offset = start + found.end(2) - 1
        return self._put(where.path, offset, offset, addition.replace("'", quote))

    def insert_first(self, parent: etree._Element, element_text: str) -> str | None:
        """``element_text`` as the first child of ``parent``, on its own line."""
        from inertia_kit.description.xmlspan import element_span, indent_unit, line_indent

        where, start = self.files.where(parent), self.files.start(parent)
        if where is None or start is None:
            return f"an element at line {parent.sourceline} was not found"
        source = self.files.source(where.path)
        span = element_span(source.text, start)
        if span.empty:
            return f"<{span.tag}> at {location(where)} is an empty element"
        indent = line_indent(source.text, start) + indent_unit(source.text)
        content = source.newline + indent + element_text
        return self._put(where.path, span.start_tag_end, span.start_tag_end, content)

    def result(self) -> tuple[Edit, ...]:
        return tuple(Edit(path, s, e, content) for (path, s, e), content in self.edits.items())
