"""
``json``: one array of :meth:`~inertia_kit.lint.findings.Finding.to_json` objects, then one
object of the same keys for each file that could not be linted: ``code`` ``IN000``, ``name``
``unreadable-file`` (or ``internal-error``), ``severity`` ``error``, the error's ``message``,
``file``, ``line`` and ``column`` (null where unknown), the other keys null.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence
from itertools import chain
from typing import TYPE_CHECKING, Any

from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.output.common import ENTRIES, UNLINTED, dumps_streamed, finite, unlinted_name

if TYPE_CHECKING:
    from inertia_kit.errors import InputError, InternalError


def render(findings: Sequence[Finding], errors: Sequence[InputError | InternalError] = ()) -> str:
    return "".join(pieces(findings, errors))


def pieces(
    findings: Iterable[Finding], errors: Sequence[InputError | InternalError] = ()
) -> Iterator[str]:
    """:func:`render`'s text in pieces, a finding at a time."""
    entries = chain(
        (finite(finding.to_json()) for finding in findings), (_unlinted(e) for e in errors)
    )
    return dumps_streamed([ENTRIES], entries)


def _unlinted(error: InputError | InternalError) -> dict[str, Any]:
    # a finding's JSON, so that a reader of findings reads these too
    unlinted = Finding(
        path=error.path,  # type: ignore[arg-type]  # null when the error names no file
        line=error.line,
        column=error.column,
        code=UNLINTED,
        name=unlinted_name(error),
        severity=Severity.ERROR,
        message=error.message,
    )
    return finite(unlinted.to_json())
