"""``github``: workflow commands that GitHub Actions shows as annotations."""

from __future__ import annotations

import re
from collections.abc import Sequence
from typing import TYPE_CHECKING

from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.output.common import UNLINTED, location, message, unlinted_name
from inertia_kit.printable import UNPRINTABLE, escape

if TYPE_CHECKING:
    from inertia_kit.errors import InputError, InternalError

_LEVELS = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "notice"}


def render(findings: Sequence[Finding], errors: Sequence[InputError | InternalError] = ()) -> str:
    commands = [_command(finding) for finding in findings]
    commands += [_unlinted(error) for error in errors]
    return "".join(command + "\n" for command in commands)


def _escape_data(text: str) -> str:
    """
    A workflow command's message (GitHub's ``escapeData``). CR and LF are GitHub's to escape
    (the annotation shows them as line breaks); every other character that could break or
    disguise the log line (ESC, C1 controls, U+2028, bidirectional controls) is shown as its
    escape, as in the text formats: GitHub would write it raw into the log (where a colour
    code can hide text).
    """
    shown = UNPRINTABLE.sub(_shown, text)
    return shown.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def _shown(match: re.Match[str]) -> str:
    char = match.group()
    # a lone surrogate is a byte of a file name that is no UTF-8: written as that byte (as the
    # runner reads the file's name), where it disguises nothing
    return char if char in "\r\n" or "\ud800" <= char <= "\udfff" else escape(char)


def _escape_property(text: str) -> str:
    """A workflow command's property value (GitHub's ``escapeProperty``)."""
    return _escape_data(text).replace(":", "%3A").replace(",", "%2C")


def _head(code: str, path: str | None, line: int | None, column: int | None) -> str:
    properties = [("title", f"inertia-lint ({code})")]
    if path is not None:
        properties.append(("file", path))
        if line is not None:
            properties.append(("line", str(line)))
            if column is not None:
                properties.append(("col", str(column)))
    return ",".join(f"{key}={_escape_property(value)}" for key, value in properties)


def _command(finding: Finding) -> str:
    head = _head(finding.code, finding.path, finding.line, finding.column)
    where = location(finding.path, finding.line, finding.column)
    text = f"{where}: {finding.code} {message(finding)}"
    if finding.detail:
        text += f"\n{finding.detail}"
    if finding.help:
        text += f"\nhelp: {finding.help}"
    return f"::{_LEVELS[finding.severity]} {head}::{_escape_data(text)}"


def _unlinted(error: InputError | InternalError) -> str:
    """An annotation on the file (at its line when known) that could not be linted."""
    head = _head(UNLINTED, error.path, error.line, error.column)
    where = location(error.path, error.line, error.column) if error.path else ""
    text = f"{where}: " if where else ""
    text += f"{UNLINTED} {unlinted_name(error)}: {error.message}"
    return f"::error {head}::{_escape_data(text)}"
