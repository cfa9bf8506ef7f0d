"""
A unified diff of two texts that mostly agree, in time near-linear in their lines: the output of
``difflib.unified_diff``, whose matcher slows down as the square of the lines when changes are
spread over a file (a fix of each of 5000 links: 33 s of ``--diff`` for 25 000 lines).

Texts of up to :data:`WHOLE` lines are aligned by difflib whole, as before (its output exactly).
In longer ones, lines that occur once in each text anchor the match, in order (the longest
increasing run of them: patience diff), and ``difflib.SequenceMatcher`` aligns what lies
between two anchors, which a fix keeps to a few lines; where several alignments are as good,
it may show another than difflib would. Where no line anchors (a text of repeated lines),
difflib aligns the whole stretch, as before.
"""

from __future__ import annotations

import bisect
import difflib
from collections import Counter
from collections.abc import Iterator, Sequence

Opcode = tuple[str, int, int, int, int]

#: Texts of at most this many lines are aligned by difflib whole: it takes milliseconds there.
WHOLE = 2000


def unified_diff(
    a: Sequence[str], b: Sequence[str], fromfile: str, tofile: str, n: int = 3
) -> Iterator[str]:
    """``difflib.unified_diff(a, b, fromfile, tofile, n=n)`` (lines with their endings)."""
    started = False
    for group in _grouped(_opcodes(a, b), n):
        if not started:
            started = True
            yield f"--- {fromfile}\n"
            yield f"+++ {tofile}\n"
        first, last = group[0], group[-1]
        yield (f"@@ -{_range(first[1], last[2])} +{_range(first[3], last[4])} @@\n")
        for tag, i1, i2, j1, j2 in group:
            if tag == "equal":
                yield from (" " + line for line in a[i1:i2])
                continue
            if tag in ("replace", "delete"):
                yield from ("-" + line for line in a[i1:i2])
            if tag in ("replace", "insert"):
                yield from ("+" + line for line in b[j1:j2])


def _range(start: int, stop: int) -> str:
    """difflib's ``_format_range_unified``."""
    beginning, length = start + 1, stop - start
    if length == 1:
        return f"{beginning}"
    if not length:
        beginning -= 1
    return f"{beginning},{length}"


def _opcodes(a: Sequence[str], b: Sequence[str]) -> list[Opcode]:
    """Opcodes turning ``a`` into ``b``, as ``SequenceMatcher.get_opcodes`` gives them."""
    if max(len(a), len(b)) <= WHOLE:
        return difflib.SequenceMatcher(None, a, b).get_opcodes()
    found: list[Opcode] = []
    i = j = 0
    for ai, bj in [*_anchors(a, b), (len(a), len(b))]:
        if ai > i or bj > j:
            matcher = difflib.SequenceMatcher(None, a[i:ai], b[j:bj], autojunk=False)
            for tag, i1, i2, j1, j2 in matcher.get_opcodes():
                _add(found, (tag, i + i1, i + i2, j + j1, j + j2))
        if ai < len(a):
            _add(found, ("equal", ai, ai + 1, bj, bj + 1))
        i, j = ai + 1, bj + 1
    return found


def _add(found: list[Opcode], opcode: Opcode) -> None:
    """Append ``opcode``, joining it to the last one when both are equal runs."""
    if found and found[-1][0] == "equal" == opcode[0]:
        tag, i1, _, j1, _ = found[-1]
        found[-1] = (tag, i1, opcode[2], j1, opcode[4])
    else:
        found.append(opcode)


def _anchors(a: Sequence[str], b: Sequence[str]) -> list[tuple[int, int]]:
    """``(i, j)`` of lines occurring once in ``a`` and once in ``b`` with ``a[i] == b[j]``, the
    longest run of them increasing in both (patience sorting, ``O(k log k)``)."""
    count_a, count_b = Counter(a), Counter(b)
    where_b = {line: j for j, line in enumerate(b) if count_b[line] == 1}
    pairs = [
        (i, where_b[line]) for i, line in enumerate(a) if count_a[line] == 1 and line in where_b
    ]
    tails: list[int] = []  # the j ending the best run of each length
    ends: list[int] = []  # the index in ``pairs`` of that run's end
    before: list[int] = []  # each pair's predecessor in its best run
    for index, (_, j) in enumerate(pairs):
        length = bisect.bisect_left(tails, j)
        if length == len(tails):
            tails.append(j)
            ends.append(index)
        else:
            tails[length], ends[length] = j, index
        before.append(ends[length - 1] if length else -1)
    run: list[tuple[int, int]] = []
    index = ends[-1] if ends else -1
    while index >= 0:
        run.append(pairs[index])
        index = before[index]
    return run[::-1]


def _grouped(opcodes: list[Opcode], n: int) -> Iterator[list[Opcode]]:
    """``SequenceMatcher.get_grouped_opcodes(n)`` for ``opcodes``."""
    codes = list(opcodes)
    if not codes:
        codes = [("equal", 0, 1, 0, 1)]
    if codes[0][0] == "equal":
        tag, i1, i2, j1, j2 = codes[0]
        codes[0] = tag, max(i1, i2 - n), i2, max(j1, j2 - n), j2
    if codes[-1][0] == "equal":
        tag, i1, i2, j1, j2 = codes[-1]
        codes[-1] = tag, i1, min(i2, i1 + n), j1, min(j2, j1 + n)
    wide = n + n
    group: list[Opcode] = []
    for tag, i1, i2, j1, j2 in codes:
        if tag == "equal" and i2 - i1 > wide:
            group.append((tag, i1, min(i2, i1 + n), j1, min(j2, j1 + n)))
            yield group
            group = []
            i1, j1 = max(i1, i2 - n), max(j1, j2 - n)
        group.append((tag, i1, i2, j1, j2))
    if group and not (len(group) == 1 and group[0][0] == "equal"):
        yield group
