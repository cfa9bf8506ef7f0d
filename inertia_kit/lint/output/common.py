"""
What the output formats share: where a finding is (``path:line:col``), its colour, the style
hook that colours text, JSON that holds no non-finite number, and what the machine-read
formats call a file that could not be linted.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Iterator
from typing import TYPE_CHECKING, Any

from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.printable import UNPRINTABLE_ABOVE_C0

if TYPE_CHECKING:
    from inertia_kit.errors import InputError, InternalError

# a file that could not be linted, in the machine-read formats: a code no rule has (ruff's E902
# io-error); `--select` and `--ignore` cannot turn it off, as it is why the exit code is 2
UNLINTED = "IN000"

COLOURS = {Severity.ERROR: "red", Severity.WARNING: "yellow", Severity.INFO: "blue"}

# click.style's signature: (text, fg=..., bold=...) -> text with terminal escapes
Style = Callable[..., str]


def plain(text: str, **_: Any) -> str:
    """The style that adds nothing."""
    return text


def location(path: str, line: int | None, column: int | None) -> str:
    """``path:line:col``, with what is known."""
    return ":".join(str(part) for part in (path, line, column) if part is not None)


def message(finding: Finding) -> str:
    """The finding's message, with the robots that produced it for a file they include."""
    if not finding.via:
        return finding.message
    return f"{finding.message} (via {', '.join(finding.via)})"


def dumps(value: Any) -> str:
    """
    JSON as the machine-read formats write it: UTF-8 text, with every character that
    :func:`~inertia_kit.printable.printable` escapes written as a ``\\uXXXX`` escape (JSON
    escapes C0 itself): the exact text, and a document that is safe to print in a CI log (no
    C1 control, line separator or bidirectional control raw in it), which a lone surrogate (an
    undecodable file name) cannot make unwritable.
    """
    import json  # the machine-read formats only: not imported by a run that prints text

    text = json.dumps(value, indent=2, ensure_ascii=False, allow_nan=False)
    # outside strings JSON is ASCII: every such character stands inside a string
    return UNPRINTABLE_ABOVE_C0.sub(lambda match: f"\\u{ord(match.group()):04x}", text)


#: stands for the entries of a list written one by one (:func:`dumps_streamed`): a string no
#: report holds (XML, where every name and value comes from, cannot hold a NUL)
ENTRIES = "\x00inertia-kit:entries"


def dumps_streamed(document: Any, entries: Iterable[Any]) -> Iterator[str]:
    """
    ``dumps(document) + "\n"`` in pieces, where the one list ``[ENTRIES]`` in ``document``
    (:data:`ENTRIES`) stands for ``entries``, each dumped as it comes: the same text, without
    every entry in memory at once.
    """
    import json

    text = dumps(document) + "\n"
    quoted = json.dumps(ENTRIES)
    at = text.index(quoted)
    start = text.rindex("\n", 0, at)  # the list's opening bracket ends the line before
    indent = text[start + 1 : at]
    head, tail = text[:start], text[at + len(quoted) :]
    separator = "\n"
    for entry in entries:
        yield head + separator + indent + dumps(entry).replace("\n", "\n" + indent)
        head, separator = "", ",\n"
    if head:  # no entries: the empty list, as dumps writes it
        yield text[:start] + "]" + tail[tail.index("]") + 1 :]
    else:
        yield tail


def finite(value: Any) -> Any:
    """JSON-ready: non-finite numbers (which JSON cannot hold) become ``null``."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {key: finite(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [finite(item) for item in value]
    return value


def fix_mark(finding: Finding, unsafe_fixes: bool) -> str:
    """``"[*] "`` for a finding whose fix ``--fix`` applies (ruff's mark), else nothing."""
    from inertia_kit.lint.applying import applicable

    return "[*] " if applicable(finding, unsafe_fixes) else ""


def unlinted_name(error: InputError | InternalError) -> str:
    """``unreadable-file``, or ``internal-error`` for a bug in inertia-kit."""
    from inertia_kit.errors import InternalError

    return "internal-error" if isinstance(error, InternalError) else "unreadable-file"
