"""
description.lines: a line ends at CRLF, LF or a lone CR, as XML and expat count; lxml counts only
LF, so every position read from lxml is moved to these lines (parse errors, start tags, NUL
bytes, entity declarations), in UTF-8 and UTF-16 alike.
"""

from __future__ import annotations

import pytest
from lxml import etree

from inertia_kit.description import lines
from inertia_kit.description.xmlparse import parse_xml, start_tag_positions
from inertia_kit.errors import InputError


def test_each_kind_of_break_ends_one_line():
    text = "a\r\nb\nc\rd\n\re"
    assert lines.line_starts(text) == [0, 3, 5, 7, 9, 10]
    assert lines.line_starts(text.encode()) == [0, 3, 5, 7, 9, 10]
    starts = lines.line_starts(text)
    assert [lines.line_of(starts, text.index(c)) for c in "abcde"] == [1, 2, 3, 4, 6]
    assert lines.line_start(text, text.index("d")) == text.index("d")
    assert lines.line_end(text, text.index("c")) == text.index("c") + 1
    assert lines.line_end(text, len(text) - 1) == len(text)


def test_a_libxml2_position_moves_to_xml_lines():
    data = b"<r>\r<a/>\r\n<b>\r<c>"
    with pytest.raises(etree.XMLSyntaxError) as caught:
        etree.fromstring(data)
    error = caught.value
    assert error.position[0] == 2  # libxml2: the lone CRs end no line
    assert lines.from_libxml2(data, *error.position)[0] == 4
    assert lines.from_libxml2(b"<r>\n<a>", 2, 4) == (2, 4)  # no CR: unchanged


TEXT = '<robot name="r">\r<link name="a"/>\r\n<link\rname="b"/>\r<link name="c"/></robot>'


@pytest.mark.parametrize("encoding", ["utf-8", "utf-8-sig", "utf-16", "utf-32"])
def test_start_tags_stand_at_xml_lines_in_every_encoding(encoding):
    data = TEXT.encode(encoding)
    root = parse_xml(data, "r.urdf")
    positions = start_tag_positions(data, root)
    assert positions is not None
    assert [positions[e] for e in root.iter()] == [(1, 1), (2, 1), (3, 1), (5, 1)]


def test_a_syntax_error_after_lone_crs_names_the_xml_line():
    with pytest.raises(InputError) as caught:
        parse_xml(b'<robot name="r">\r<link name="a"/>\r<link name="b">\r</robot>\r', "r.urdf")
    assert caught.value.line == 4


def test_an_entity_and_a_nul_byte_after_lone_crs_name_the_xml_line():
    with pytest.raises(InputError) as caught:
        parse_xml(b'<!DOCTYPE r [\r<!ENTITY e "x">]>\r<robot name="r"/>', "r.urdf")
    assert (caught.value.line, caught.value.column) == (2, 1)
    with pytest.raises(InputError) as caught:
        parse_xml(b'<robot name="r">\r<link name="a"/>\r\x00<link name="b"/></robot>', "r.urdf")
    assert caught.value.line == 3
