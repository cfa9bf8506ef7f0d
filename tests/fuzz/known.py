"""
Failure classes the fuzz run finds and that are still open, each with where it is to be fixed:
the items of issue 19 (and the helper working on each), and what the fuzz run found beyond the
issue's list (reported, with a reproducer, to whoever merges). The CI test (test_fuzz.py) names
every failure it excuses by this list in a warning and fails on any other; whoever merges a fix
removes its entry, and the test then proves it gone (or fails on what is left).

Each entry: (class, a glob over the signature's detail, why it is excused).
"""

from __future__ import annotations

from fnmatch import fnmatchcase

#: none open: every class the fuzz run of issue 19 found is fixed (the list stays, for the next)
KNOWN_OPEN: tuple[tuple[str, str, str], ...] = ()


def known_open(signature: str) -> str | None:
    """Why ``signature`` ("class: detail") is excused, or None."""
    kind, _, detail = signature.partition(": ")
    for known_kind, pattern, why in KNOWN_OPEN:
        if kind == known_kind and fnmatchcase(detail, pattern):
            return why
    return None
