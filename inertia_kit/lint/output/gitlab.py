"""
``gitlab``: a GitLab Code Quality report (a JSON array of issues: ``description``,
``check_name``, ``fingerprint``, ``severity``, ``location`` with ``path`` and ``lines.begin``),
as ruff writes it. Paths are relative to ``$CI_PROJECT_DIR`` (GitLab's checkout) when set, else
to the current folder; GitLab matches them against the merge request's files.

The fingerprint is how GitLab tells a new issue from one it already knows: it hashes the code,
the path and the link (or joint) the finding is about, not the line or the numbers in the
message, so a finding stays the same issue when lines move or a value changes. Findings that
would share one are told apart by hashing again with the one before (as ruff does).
"""

from __future__ import annotations

import hashlib
import os
from collections.abc import Iterable, Iterator, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.output.common import (
    ENTRIES,
    UNLINTED,
    dumps_streamed,
    message,
    unlinted_name,
)

if TYPE_CHECKING:
    from inertia_kit.errors import InputError, InternalError

# GitLab's levels: info, minor, major, critical, blocker; a file that could not be linted at all
# is worse than any one finding in it
_SEVERITIES = {Severity.ERROR: "major", Severity.WARNING: "minor", Severity.INFO: "info"}
UNLINTED_SEVERITY = "critical"


def render(findings: Sequence[Finding], errors: Sequence[InputError | InternalError] = ()) -> str:
    return "".join(pieces(findings, errors))


def pieces(
    findings: Iterable[Finding], errors: Sequence[InputError | InternalError] = ()
) -> Iterator[str]:
    """:func:`render`'s text in pieces, a finding at a time."""
    return dumps_streamed([ENTRIES], _issues(findings, errors))


def _issues(
    findings: Iterable[Finding], errors: Sequence[InputError | InternalError]
) -> Iterator[dict[str, Any]]:
    root = os.environ.get("CI_PROJECT_DIR") or os.getcwd()
    seen: dict[tuple[str, str, str], str] = {}
    for finding in findings:
        subject = finding.link or finding.joint or ""
        yield _issue(
            finding.code,
            f"{finding.code}: {message(finding)}",
            _SEVERITIES[finding.severity],
            relative(finding.path, root),
            finding.line,
            subject,
            seen,
        )
    for error in errors:
        path = relative(error.path, root) if error.path else ""
        name = unlinted_name(error)
        text = f"{UNLINTED}: {name}: {error.message}"
        yield _issue(UNLINTED, text, UNLINTED_SEVERITY, path, error.line, name, seen)


def relative(path: str, root: str) -> str:
    """``path`` relative to ``root``, with forward slashes (as given when that fails)."""
    try:
        shown = os.path.relpath(os.path.abspath(path), os.path.abspath(root))
    except ValueError:  # another drive (Windows)
        shown = path
    return Path(shown).as_posix()


def _issue(
    code: str,
    description: str,
    severity: str,
    path: str,
    line: int | None,
    subject: str,
    seen: dict[tuple[str, str, str], str],
) -> dict[str, Any]:
    # the k-th finding alike (code, file, subject) gets the k-th link of a hash chain: stable
    # while their order is; the chain's last link is kept, so 5000 alike cost 5000 hashes
    key = (code, path, subject)
    last = seen.get(key)
    fingerprint = _fingerprint("" if last is None else last, code, path, subject)
    seen[key] = fingerprint
    return {
        "description": description,
        "check_name": code,
        "fingerprint": fingerprint,
        "severity": severity,
        # GitLab needs a line; a finding about the whole robot has none: its first line
        "location": {"path": path, "lines": {"begin": line if line and line >= 1 else 1}},
    }


def _fingerprint(salt: str, code: str, path: str, subject: str) -> str:
    text = "\0".join((salt, code, path, subject))
    return hashlib.sha256(text.encode("utf-8", "surrogateescape")).hexdigest()[:32]
