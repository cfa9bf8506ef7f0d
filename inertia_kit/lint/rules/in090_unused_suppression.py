"""IN090 unused-suppression: an ``ignore[...]`` comment, or a code in it, suppresses nothing."""

from __future__ import annotations

import re
from collections.abc import Iterator, Sequence
from typing import TYPE_CHECKING

from inertia_kit.description import lines
from inertia_kit.description.edits import Edit, read_source
from inertia_kit.description.model import Source
from inertia_kit.description.reads import digest
from inertia_kit.errors import InputError
from inertia_kit.lint.findings import Finding, Fix, Safety, Severity
from inertia_kit.lint.rules import RuleContext

if TYPE_CHECKING:
    from inertia_kit.lint import markup
    from inertia_kit.lint.comment_use import CommentUse

CODE = "IN090"
NAME = "unused-suppression"
SEVERITY = Severity.WARNING
# not a link or the robot: the suppression comments, once every other rule has run (lint.unused)
SCOPE = "suppressions"
SUMMARY = "a suppression comment, or a code in it, suppresses no finding"
# removing a comment that suppresses nothing changes no value and no other finding
TEXT_FIX = Safety.SAFE
_CODE = re.compile(r"IN[0-9]{0,3}", re.IGNORECASE)


def check(comments: Sequence[CommentUse], ctx: RuleContext) -> Iterator[Finding]:
    for use in comments:
        unused = use.unused
        if not unused:
            continue
        listed = ", ".join(f"`{s}`" for s in unused)
        every = set(unused) == set(use.selectors)
        verb = "suppresses" if len(unused) == 1 else "suppress"
        what = "the comment suppresses nothing" if every else f"{listed} in it {verb} nothing"
        over = (
            "" if use.robots == 1 else f" in any of the {use.robots} linted robots that include it"
        )
        first, last = use.lines
        span = f"line {first}" if first == last else f"lines {first}–{last}"
        fix = _fix(use.path, use.line, set(unused), use.digest)
        yield ctx.finding(
            f"`ignore[{', '.join(use.selectors)}]`: {what}",
            Source(use.path, use.line, None if fix is None else fix[1]),
            detail=f"no finding of {listed} on the element it covers ({span}){over}",
            help="remove it (the fix does, safely); if a rule should fire there, find out why "
            "it no longer does before removing the comment",
            fix=None if fix is None else fix[0],
        )


def _fix(path: str, line: int, unused: set[str], read: str | None) -> tuple[Fix, int] | None:
    """
    The edit that removes the unused selectors from the comment on ``line`` (the whole comment,
    with its line when nothing else stands on it, when none is left), and the comment's column;
    none unless the file still holds the bytes the lint read (digest ``read``).
    """
    try:
        source = read_source(path)
    except InputError:
        return None
    if read is None or digest(source.original) != read:
        return None  # the comment's line is one of another text: no edit computed on this one
    # the markup scanner (a large regular expression) only when there is a comment to edit
    from inertia_kit.lint import markup

    text = source.text
    found = markup.layout(text)
    comment = found.comment_on(line)
    brackets = None if comment is None else comment.selectors()
    if comment is None or brackets is None:
        return None
    start, end, items = brackets
    kept = [item for item in items if _selector(item) not in unused]
    column = comment.start - found.line_starts[line - 1] + 1
    if kept:
        edit = Edit(path, start, end, ", ".join(kept))
        return Fix(
            f"remove {', '.join(sorted(unused))} from the comment", (edit,), TEXT_FIX
        ), column
    return Fix(
        "remove the unused suppression comment", (_removal(path, text, comment),), TEXT_FIX
    ), column


def _selector(item: str) -> str:
    """An entry of the comment as the suppression pass names it: codes in upper case."""
    return item.upper() if _CODE.fullmatch(item) else item


def _removal(path: str, text: str, comment: markup.Comment) -> Edit:
    """The comment, with its whole line(s) when only blanks stand beside it."""
    line_start = lines.line_start(text, comment.start)
    rest = len(text) - len(text[comment.end :].lstrip(" \t"))
    ending = text[rest : rest + 2]
    newline = (
        "\r\n" if ending.startswith("\r\n") else ending[:1] if ending[:1] in ("\n", "\r") else ""
    )
    alone = not text[line_start : comment.start].strip() and (newline or rest == len(text))
    if alone:
        return Edit(path, line_start, rest + len(newline), "")
    return Edit(path, comment.start, comment.end, "")
