"""
Text from files, made safe to print for people: the one place deciding how a name, a path or a
value that came from a robot file (or the file system) is shown in a terminal or a CI log.

A link name may hold a newline (``&#10;``), so a name printed as it is can start a line of its
own: a GitHub workflow command (``::error file=...::``), a line a reader takes for inertia-lint's,
a shell line pasted from a report. Other characters rewrite what the reader sees: CR returns to
the start of the line, C1 controls (``U+009B`` is an 8-bit CSI) drive terminals, U+2028 and
U+2029 end lines in editors and browsers, and the bidirectional controls reorder the text around
them ("Trojan source"). :func:`printable` shows each as an escape (``\\n``, ``\\x9b``,
``\\u202e``), so that every such text stays on its line and reads as written.

Escaped: C0 controls (tab too: in a name it is data a reader cannot tell from spaces; a source
line's tabs are layout and expanded before), DEL, C1 controls (NEL included), U+2028 and U+2029,
the characters of Unicode's Bidi_Control property (U+061C, U+200E, U+200F, U+202A–U+202E,
U+2066–U+2069), and lone surrogates (an undecodable file name, as Python reads it). A backslash
is not escaped: the escapes are for reading, not for reversing (the machine-read formats carry
the exact text), and Windows paths stay as they are.
"""

from __future__ import annotations

import re
import unicodedata

_ABOVE_C0 = "\x7f-\x9f\u061c\u200e\u200f\u2028\u2029\u202a-\u202e\u2066-\u2069\ud800-\udfff"
#: the characters :func:`printable` escapes
UNPRINTABLE = re.compile(f"[\x00-\x1f{_ABOVE_C0}]")
#: those of them beyond the C0 controls (which JSON and XML writers escape themselves)
UNPRINTABLE_ABOVE_C0 = re.compile(f"[{_ABOVE_C0}]")
_NAMED = {"\n": "\\n", "\r": "\\r", "\t": "\\t"}


def escape(char: str) -> str:
    """One character as :func:`printable` shows it: ``\\n``, ``\\x1b``, ``\\u2028``."""
    named = _NAMED.get(char)
    if named is not None:
        return named
    code = ord(char)
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def printable(text: str) -> str:
    """``text`` with every character that could break or disguise a line shown as an escape."""
    if UNPRINTABLE.search(text) is None:  # the common case: nothing to copy
        return text
    return UNPRINTABLE.sub(lambda match: escape(match.group()), text)


def is_unprintable(char: str) -> bool:
    """Whether :func:`printable` escapes ``char``."""
    return UNPRINTABLE.match(char) is not None


def width(char: str) -> int:
    """How many terminal columns ``char`` takes: 2 for wide East Asian characters, 0 for
    combining marks and invisible format characters, else 1 (a character :func:`printable`
    escapes: its escape's length)."""
    if is_unprintable(char):
        return len(escape(char))
    if unicodedata.combining(char) or unicodedata.category(char) == "Cf":
        return 0
    return 2 if unicodedata.east_asian_width(char) in ("W", "F") else 1
