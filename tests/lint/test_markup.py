"""
lint.markup places elements and comments in the text; lint.suppress reads comments through it,
so a comment --add-noqa writes covers what it was written for. Its lines are XML's (a lone CR
ends one), as expat counts them: the oracle here, since lxml counts only LF.
"""

from __future__ import annotations

from xml.parsers import expat

import pytest
from kit import EXAMPLES

from inertia_kit.lint import markup

FILES = sorted(p for p in EXAMPLES.rglob("*") if p.suffix in (".urdf", ".xacro"))
ODD = (
    '<?xml version="1.0"?>\r\n<!-- a -->\r\n<robot name="r"><link\r\n  name="a"\r\n/>'
    '<link name="b"><inertial>\r\n<mass value="1"\r\n/></inertial></link>\r\n</robot>\r\n'
)


def expat_lines(text: str) -> list[tuple[str, int, int]]:
    """``(name, line of its start tag's <, line of its end tag's </)`` of every element."""
    found: list[list] = []
    open_: list[list] = []
    parser = expat.ParserCreate()

    def start(name, attributes):
        open_.append([name, parser.CurrentLineNumber, 0])
        found.append(open_[-1])

    def end(name):
        open_.pop()[2] = parser.CurrentLineNumber

    parser.StartElementHandler, parser.EndElementHandler = start, end
    parser.Parse(text, True)
    return [tuple(entry) for entry in found]


LONE_CR = ODD.replace("\r\n", "\r").replace("<inertial>", "<inertial>\r")


@pytest.mark.parametrize(
    "text",
    [ODD, LONE_CR, ODD.replace("\r\n", "\n\r")] + [p.read_text() for p in FILES],
    ids=["odd", "lone-cr", "lf-cr"] + [p.name for p in FILES],
)
def test_element_lines_are_xml_lines(text):
    expected = expat_lines(text)
    found = markup.layout(text)
    assert len(found.elements) == len(expected)
    for (name, first, last), placed in zip(expected, found.elements, strict=True):
        assert text[placed.start :].startswith(f"<{name}")
        assert (placed.first, placed.last) == (first, last), name


def test_comments_and_what_stands_before_an_element():
    found = markup.layout(ODD)
    (comment,) = found.comments
    assert (comment.line, comment.body) == (2, " a ")
    assert found.root is not None and found.root.before == [comment]
    # line 5 is `/><link name="b"><inertial>`: without a column, the smallest element holding
    # the line (the first of link a, link b, inertial: two lines each); with one, the element there
    assert ODD[found.innermost(5).start :].startswith('<link\r\n  name="a"')
    assert ODD[found.innermost(5, 3).start :].startswith('<link name="b">')
    assert ODD[found.innermost(5, 20).start :].startswith("<inertial>")


def brute_innermost(found, line, column):
    """What innermost gives, by looking at every element (as it once did)."""
    if column is not None and 1 <= line <= len(found.line_starts):
        offset = found.line_starts[line - 1] + column - 1
        holding = [e for e in found.elements if e.start <= offset < e.end]
        if holding:
            return max(holding, key=lambda e: e.start)
    holding = [e for e in found.elements if e.first <= line <= e.last]
    return min(holding, key=lambda e: e.last - e.first, default=None)


@pytest.mark.parametrize(
    "text",
    [ODD, LONE_CR] + [p.read_text() for p in FILES],
    ids=["odd", "lone-cr"] + [p.name for p in FILES],
)
def test_innermost_is_the_smallest_holding_element(text):
    found = markup.layout(text)
    lines = len(found.line_starts)
    for line in range(0, lines + 2):
        width = 1 + (len(text) if line > lines else 120)
        for column in (None, *range(1, min(width, 120))):
            assert found.innermost(line, column) is brute_innermost(found, line, column)
