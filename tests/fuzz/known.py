"""
Failure classes the fuzz run finds that issue 19 already lists, each with the item of the issue
that fixes it. The CI test (test_fuzz.py) prints every failure it excuses by this list and fails
on any other; whoever merges a fix removes its entry, and the test then proves it gone.

Each entry: (class, a glob over the signature's detail, "issue 19 item N (owner): what").
"""

from __future__ import annotations

from fnmatch import fnmatchcase

KNOWN_OPEN: tuple[tuple[str, str, str], ...] = ()


def known_open(signature: str) -> str | None:
    """The issue item that excuses ``signature`` ("class: detail"), or None."""
    kind, _, detail = signature.partition(": ")
    for known_kind, pattern, why in KNOWN_OPEN:
        if kind == known_kind and fnmatchcase(detail, pattern):
            return why
    return None
