"""The expanded xacro tree is written with escaping of our own, exactly as xml.sax.saxutils
escapes (importing saxutils pulls in urllib.request, http.client, email and ssl)."""

from __future__ import annotations

import itertools
from xml.sax.saxutils import escape, quoteattr

from inertia_kit.description.urdf.xacro_source_map import _escape, _quoteattr


def test_escape_and_quoteattr_match_saxutils_on_every_short_string():
    alphabet = "a&<>\"'\n\r\t"
    for length in range(5):
        for letters in itertools.product(alphabet, repeat=length):
            text = "".join(letters)
            assert _escape(text) == escape(text), repr(text)
            assert _quoteattr(text) == quoteattr(text), repr(text)
