"""
description.line_diff: difflib's unified diff, exactly for texts difflib aligns whole, and for
long texts a diff that rebuilds the new text, in time linear in their lines (difflib's matcher
took 33 s for a fix of each of 5000 links).
"""

from __future__ import annotations

import difflib
import random
import re

from kit import EXAMPLES, least_cpu
from kit.big import urdf

from inertia_kit.description import line_diff

TEXTS = [p.read_text() for p in sorted(EXAMPLES.rglob("*")) if p.suffix in (".urdf", ".xacro")]


def edited(lines: list[str], rng: random.Random) -> list[str]:
    """``lines`` with a few lines removed, inserted (copies of others) or changed."""
    new = list(lines)
    for _ in range(rng.randint(0, 6)):
        at = rng.randrange(len(new) + 1)
        kind = rng.random()
        if kind < 0.3 and new:
            del new[min(at, len(new) - 1)]
        elif kind < 0.6:
            new[at:at] = [rng.choice(lines) for _ in range(rng.randint(1, 5))]
        elif new:
            new[min(at, len(new) - 1)] = f"changed {rng.randint(0, 9)}\n"
    return new


def apply(diff: str, old: list[str]) -> list[str]:
    """The new lines a unified diff of ``old`` says."""
    new: list[str] = []
    at = 0
    lines = diff.splitlines(keepends=True)[2:]
    for line in lines:
        hunk = re.match(r"@@ -(\d+)(?:,(\d+))? ", line)
        if hunk:
            start = int(hunk.group(1)) - (0 if hunk.group(2) != "0" else -1)
            new.extend(old[at : start - 1])
            at = start - 1
        elif line[0] in " -":
            assert old[at] == line[1:]
            at += 1
            if line[0] == " ":
                new.append(line[1:])
        else:
            new.append(line[1:])
    return new + old[at:]


def test_the_diff_difflib_gives_for_texts_it_aligns_whole():
    rng = random.Random(1)
    for _ in range(1000):
        old = rng.choice(TEXTS).splitlines(keepends=True)
        new = edited(old, rng)
        theirs = "".join(difflib.unified_diff(old, new, "a/x", "b/x"))
        assert "".join(line_diff.unified_diff(old, new, "a/x", "b/x")) == theirs


def test_a_long_text_s_diff_rebuilds_the_new_text(monkeypatch):
    monkeypatch.setattr(line_diff, "WHOLE", 0)
    rng = random.Random(2)
    for _ in range(500):
        old = rng.choice(TEXTS).splitlines(keepends=True)
        new = edited(old, rng)
        diff = "".join(line_diff.unified_diff(old, new, "a/x", "b/x"))
        assert apply(diff, old) == new
        assert bool(diff) == (old != new)


def test_a_long_text_s_diff_is_linear_in_its_lines():
    def seconds(links: int) -> float:
        old = urdf(links, "star").splitlines(keepends=True)
        new = [line.replace('ixx="1"', 'ixx="2"') for line in old]  # in one link of three
        spent, diffs = least_cpu(lambda: "".join(line_diff.unified_diff(old, new, "a", "b")))
        assert apply(diffs[-1], old) == new
        return spent

    assert seconds(5000) / seconds(1000) < 10  # difflib's: 28
