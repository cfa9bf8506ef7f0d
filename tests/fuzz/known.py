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

STDIN_FRAGMENT = (
    "found by the fuzz run, not in issue 19: `inertia-fill -` (and `inertia-lint --fix -`) "
    "writes the fixes that land in an included fragment into that file on disk"
)

KNOWN_OPEN: tuple[tuple[str, str, str], ...] = (
    ("changed-input", "fill - changed *.xacro", STDIN_FRAGMENT),
    ("changed-input", "lint --fix - changed *.xacro", STDIN_FRAGMENT),
)


def known_open(signature: str) -> str | None:
    """Why ``signature`` ("class: detail") is excused, or None."""
    kind, _, detail = signature.partition(": ")
    for known_kind, pattern, why in KNOWN_OPEN:
        if kind == known_kind and fnmatchcase(detail, pattern):
            return why
    return None
