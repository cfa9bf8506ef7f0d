"""Text from files shown safely: every character that could break or disguise a line, escaped."""

from __future__ import annotations

import pytest

from inertia_kit.printable import printable, width


@pytest.mark.parametrize(
    ("text", "shown"),
    [
        ("arm_link", "arm_link"),
        ("base\n::error file=x.py,line=1::injected", "base\\n::error file=x.py,line=1::injected"),
        ("a\r\nb\tc", "a\\r\\nb\\tc"),
        ("\x1b[31mred\x1b[0m", "\\x1b[31mred\\x1b[0m"),
        ("nul\x00del\x7f", "nul\\x00del\\x7f"),
        # C1: NEL, and CSI, which some terminals read as ESC [
        ("next\x85line\x9b31m", "next\\x85line\\x9b31m"),
        ("line\u2028paragraph\u2029", "line\\u2028paragraph\\u2029"),
        # bidirectional controls: overrides, embeddings, isolates, marks ("Trojan source")
        ("admin\u202e\u2066txt.exe\u2069\u202c", "admin\\u202e\\u2066txt.exe\\u2069\\u202c"),
        ("\u200e\u200f\u061c", "\\u200e\\u200f\\u061c"),
        # an undecodable file name, as Python reads it
        ("robot\udcff.urdf", "robot\\udcff.urdf"),
        # what is printable stays: accents, CJK, emoji, a backslash (a Windows path)
        ("bras_gauche_été 腕 🤖", "bras_gauche_été 腕 🤖"),
        ("C:\\robots\\arm.urdf", "C:\\robots\\arm.urdf"),
    ],
)
def test_printable(text, shown):
    assert printable(text) == shown


def test_every_line_breaking_character_is_escaped():
    # whatever str.splitlines (and so editors, browsers, terminals) takes for a line break
    breakers = [chr(c) for c in range(0x110000) if len(f"a{chr(c)}b".splitlines()) > 1]
    assert breakers and all(len(printable(f"a{c}b").splitlines()) == 1 for c in breakers)


def test_widths():
    assert [width(c) for c in "a腕\u0301\u200b\t"] == [1, 2, 0, 0, 2]
