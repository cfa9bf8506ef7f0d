"""Element spans found by scanning the original text."""

import pytest

from inertia_kit.description.xmlspan import children, element_span, indent_unit, line_indent

TEXT = """<robot name="r">
  <!-- <link name="commented"> -->
  <link name='a' note="x > y">
    <inertial>
      <mass value="1"/>
    </inertial>
    <![CDATA[</link>]]>
    <link name="nested-oddity"/>
  </link>
  <link name="b"/>
</robot>
"""


def test_span_of_an_element_with_comments_cdata_and_quoted_gt():
    start = TEXT.index("<link name='a'")
    span = element_span(TEXT, start)
    assert TEXT[span.start : span.end].endswith("</link>")
    assert TEXT[span.end :].startswith('\n  <link name="b"/>')
    assert [c.tag for c in children(TEXT, span)] == ["inertial", "link"]


def test_empty_element():
    span = element_span(TEXT, TEXT.index('<link name="b"/>'))
    assert span.empty and TEXT[span.start : span.end] == '<link name="b"/>'


def test_errors():
    with pytest.raises(ValueError, match="no start tag"):
        element_span(TEXT, 1)
    with pytest.raises(ValueError, match="never closed"):
        element_span("<a><b></b>", 0)


@pytest.mark.parametrize(
    ("text", "unit"),
    [
        ("<a>\n  <b>\n    <c/>\n  </b>\n</a>", "  "),
        ("<a>\n\t<b/>\n</a>", "\t"),
        ("<a><b/></a>", "  "),
        ("<a>\n    <b>\n        <c/>\n    </b>\n</a>", "    "),
    ],
)
def test_indent_unit(text, unit):
    assert indent_unit(text) == unit


def test_line_indent():
    assert line_indent(TEXT, TEXT.index("<mass")) == "      "
