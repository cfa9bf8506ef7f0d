"""
``json``: one array of :meth:`~inertia_kit.lint.findings.Finding.to_json` objects, then one
object of the same keys for each file that could not be linted: ``code`` ``IN000``, ``name``
``unreadable-file`` (or ``internal-error``), ``severity`` ``error``, the error's ``message``,
``file``, ``line`` and ``column`` (null where unknown), the other keys null.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.output.common import UNLINTED, dumps, finite, unlinted_name

if TYPE_CHECKING:
    from inertia_kit.errors import InputError, InternalError


def render(findings: Sequence[Finding], errors: Sequence[InputError | InternalError] = ()) -> str:
    entries = [finite(finding.to_json()) for finding in findings]
    entries += [_unlinted(error) for error in errors]
    return dumps(entries) + "\n"


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
