"""
lint.markup places elements and comments in the text; the lines it gives each element are the
lines a suppression comment before it covers (lint.suppress, read through lxml), so that a
comment --add-noqa writes covers what it was written for.
"""

from __future__ import annotations

import pytest
from kit import EXAMPLES
from lxml import etree

from inertia_kit.lint import markup
from inertia_kit.lint.suppress import _last_line

FILES = sorted(p for p in EXAMPLES.rglob("*") if p.suffix in (".urdf", ".xacro"))
ODD = (
    '<?xml version="1.0"?>\r\n<!-- a -->\r\n<robot name="r"><link\r\n  name="a"\r\n/>'
    '<link name="b"><inertial>\r\n<mass value="1"\r\n/></inertial></link>\r\n</robot>\r\n'
)


@pytest.mark.parametrize(
    "text", [ODD] + [p.read_text() for p in FILES], ids=["odd"] + [p.name for p in FILES]
)
def test_element_lines_are_the_lines_a_comment_before_them_covers(text):
    root = etree.fromstring(text.encode())
    elements = [e for e in root.iter() if isinstance(e.tag, str)]
    found = markup.layout(text)
    assert len(found.elements) == len(elements)
    for element, placed in zip(elements, found.elements, strict=True):
        name = etree.QName(element).localname
        qname = f"{element.prefix}:{name}" if element.prefix else name
        assert text[placed.start :].startswith(f"<{qname}")
        assert placed.last == _last_line(element)
        # the line its start tag begins on (lxml gives where it ends)
        assert placed.first == text.count("\n", 0, placed.start) + 1


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
