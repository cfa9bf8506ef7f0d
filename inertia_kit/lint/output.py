"""
Findings out: the output formats of ``inertia-lint``, its statistics and summary.

- ``full``: ``path:line:col: CODE [severity] message``, the source line with a caret under the
  element, the macro body line for an element a xacro macro produced, and ``help``;
- ``concise``: ``path:line:col: CODE message``, one line each, for editors;
- ``json``: one array of :meth:`Finding.to_json` objects;
- ``github``: workflow commands that GitHub Actions shows as annotations;
- ``sarif``: SARIF 2.1.0, for code scanning.

Paths are shown as the findings carry them (as given on the command line, or as xacro included
them). Colour is added by ``style``, and removed by the caller when the output is no terminal.
"""

from __future__ import annotations

import json
import math
import re
from collections import Counter
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from types import ModuleType
from typing import Any
from urllib.parse import quote

from inertia_kit.errors import InputError
from inertia_kit.lint import documents
from inertia_kit.lint.findings import Finding, Severity

FORMATS = ("full", "concise", "json", "github", "sarif")
SARIF_SCHEMA = (
    "https://docs.oasis-open.org/sarif/sarif/v2.1.0/errata01/os/schemas/sarif-schema-2.1.0.json"
)
_COLOURS = {Severity.ERROR: "red", Severity.WARNING: "yellow", Severity.INFO: "blue"}
_GITHUB_LEVELS = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "notice"}
_TAG = re.compile(r"<[^\s/>]*")
_SARIF_LEVELS = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "note"}

Style = Callable[..., str]


def _plain(text: str, **_: Any) -> str:
    return text


def render(
    findings: Sequence[Finding],
    output_format: str,
    *,
    errors: Sequence[InputError] = (),
    style: Style | None = None,
) -> str:
    """
    The findings in one format, ending in a newline (empty for no findings, except ``json``
    and ``sarif``, which always give a document). ``errors`` (unreadable files) go into SARIF's
    invocation; the other formats leave them to the caller's error stream.
    """
    style = style or _plain
    if output_format == "full":
        sources = _Sources()
        blocks = [_full(finding, style, sources) for finding in findings]
        return "".join(block + "\n\n" for block in blocks)
    if output_format == "concise":
        return "".join(_concise(finding, style) + "\n" for finding in findings)
    if output_format == "json":
        return _dumps([_finite(finding.to_json()) for finding in findings]) + "\n"
    if output_format == "github":
        return "".join(_github(finding) + "\n" for finding in findings)
    if output_format == "sarif":
        return _dumps(sarif(findings, errors)) + "\n"
    raise ValueError(f"unknown output format {output_format!r}; known: {', '.join(FORMATS)}")


def _dumps(value: Any) -> str:
    return json.dumps(value, indent=2, ensure_ascii=False, allow_nan=False)


def _finite(value: Any) -> Any:
    """JSON-ready: non-finite numbers (which JSON cannot hold) become ``null``."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {key: _finite(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(item) for item in value]
    return value


def location(path: str, line: int | None, column: int | None) -> str:
    """``path:line:col``, with what is known."""
    return ":".join(str(part) for part in (path, line, column) if part is not None)


# --- full and concise ------------------------------------------------------------------------


def _concise(finding: Finding, style: Style) -> str:
    where = style(location(finding.path, finding.line, finding.column), bold=True)
    code = style(finding.code, fg=_COLOURS[finding.severity], bold=True)
    return f"{where}: {code} {finding.message}"


class _Sources:
    """Lines of the files findings point at, read once each."""

    def __init__(self) -> None:
        self._lines: dict[str, list[str] | None] = {}

    def line(self, path: str | None, number: int | None) -> str | None:
        if not path or number is None or number < 1:
            return None
        if path not in self._lines:
            self._lines[path] = self._read(path)
        lines = self._lines[path]
        return lines[number - 1] if lines is not None and number <= len(lines) else None

    @staticmethod
    def _read(path: str) -> list[str] | None:
        from inertia_kit.description.safexml import read_bounded

        try:
            data = read_bounded(path)
        except InputError:
            return None
        text = data.decode("utf-8", "replace").removeprefix("\ufeff")
        return [line.rstrip("\r") for line in text.split("\n")]


def _caret(text: str, column: int | None) -> tuple[str, int, int]:
    """
    The line as shown (tabs expanded), and where the caret under the element's tag starts and
    how long it is (0: no caret). Without a column, the tag the line starts with.
    """
    shown = text.expandtabs(4)
    if column is None:
        indent = len(text) - len(text.lstrip())
        column = indent + 1 if text[indent : indent + 1] == "<" else None
    if column is None or not 1 <= column <= len(text):
        return shown, 0, 0
    tag = _TAG.match(text, column - 1)
    return shown, len(text[: column - 1].expandtabs(4)), len(tag.group()) if tag else 1


def _full(finding: Finding, style: Style, sources: _Sources) -> str:
    colour = _COLOURS[finding.severity]
    header = (
        f"{style(location(finding.path, finding.line, finding.column), bold=True)}: "
        f"{style(finding.code, fg=colour, bold=True)} "
        f"{style(f'[{finding.severity}]', fg=colour)} {finding.message}"
    )
    lines = [header]
    snippets = [(finding.path, finding.line, finding.column)]
    if finding.macro_path is not None:
        snippets.append((finding.macro_path, finding.macro_line, None))
    width = max((len(str(line)) for _, line, _ in snippets if line is not None), default=1)
    gutter = " " * width
    for index, (path, number, column) in enumerate(snippets):
        if index:
            lines.append(
                f"{gutter} {style('=', bold=True)} in the macro body: "
                f"{location(path, number, None)}"
            )
        text = sources.line(path, number)
        if text is None:
            continue
        shown, offset, length = _caret(text, column)
        lines.append(f"{gutter} {style('|', bold=True)}")
        lines.append(f"{number:>{width}} {style('|', bold=True)} {shown}")
        if length:
            lines.append(
                f"{gutter} {style('|', bold=True)} "
                + " " * offset
                + style("^" * length, fg=colour, bold=True)
            )
    if finding.help:
        lines.append(f"{gutter} {style('=', bold=True)} {style('help', bold=True)}: {finding.help}")
    return "\n".join(line.rstrip() for line in lines)


# --- github ---------------------------------------------------------------------------------


def _escape_data(text: str) -> str:
    """A workflow command's message (GitHub's ``escapeData``)."""
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def _escape_property(text: str) -> str:
    """A workflow command's property value (GitHub's ``escapeProperty``)."""
    return _escape_data(text).replace(":", "%3A").replace(",", "%2C")


def _github(finding: Finding) -> str:
    properties = [("title", f"inertia-lint ({finding.code})"), ("file", finding.path)]
    if finding.line is not None:
        properties.append(("line", str(finding.line)))
        if finding.column is not None:
            properties.append(("col", str(finding.column)))
    head = ",".join(f"{key}={_escape_property(value)}" for key, value in properties)
    where = location(finding.path, finding.line, finding.column)
    message = f"{where}: {finding.code} {finding.message}"
    if finding.help:
        message += f"\nhelp: {finding.help}"
    return f"::{_GITHUB_LEVELS[finding.severity]} {head}::{_escape_data(message)}"


# --- sarif ----------------------------------------------------------------------------------


def _uri(path: str) -> str:
    """A SARIF artifact URI: relative paths stay relative (GitHub reads them from the root)."""
    if Path(path).is_absolute():
        return Path(path).as_uri()
    return quote(Path(path).as_posix(), safe="/")


def _physical(path: str, line: int | None, column: int | None) -> dict[str, Any]:
    physical: dict[str, Any] = {"artifactLocation": {"uri": _uri(path)}}
    if line is not None and line >= 1:
        region: dict[str, Any] = {"startLine": line}
        if column is not None and column >= 1:
            region["startColumn"] = column
        physical["region"] = region
    return {"physicalLocation": physical}


def _sarif_rule(code: str, name: str, rule: ModuleType | None) -> dict[str, Any]:
    summary = getattr(rule, "SUMMARY", None) or name
    entry: dict[str, Any] = {
        "id": code,
        "name": name,
        "shortDescription": {"text": summary},
    }
    if rule is not None:
        entry["defaultConfiguration"] = {"level": _SARIF_LEVELS[rule.SEVERITY]}
    document = documents.rule_documents().get(code)
    if document is not None:
        text = document.read_text(encoding="utf-8")
        entry["help"] = {"text": text, "markdown": text}
    return entry


def sarif(findings: Sequence[Finding], errors: Sequence[InputError] = ()) -> dict[str, Any]:
    """A SARIF 2.1.0 log of one run; the rules listed are those with findings."""
    from inertia_kit.lint import catalog
    from inertia_kit.version import __version__

    names = dict(sorted({(f.code, f.name) for f in findings}))
    index = {code: i for i, code in enumerate(names)}
    results = []
    for finding in findings:
        result: dict[str, Any] = {
            "ruleId": finding.code,
            "ruleIndex": index[finding.code],
            "level": _SARIF_LEVELS[finding.severity],
            "message": {"text": finding.message},
            "locations": [_physical(finding.path, finding.line, finding.column)],
        }
        if finding.macro_path is not None:
            related = _physical(finding.macro_path, finding.macro_line, None)
            related.update(id=0, message={"text": "the element in the macro body"})
            result["relatedLocations"] = [related]
        properties = {
            key: value
            for key, value in (
                ("severity", str(finding.severity)),
                ("link", finding.link),
                ("joint", finding.joint),
                ("expected", _finite(finding.expected)),
                ("help", finding.help),
            )
            if value is not None
        }
        result["properties"] = properties
        if finding.fix is not None:
            result["fixes"] = [_sarif_fix(finding)]
        results.append(result)
    notifications = [
        {
            "level": "error",
            "message": {"text": error.message},
            "locations": [_physical(error.path, error.line, error.column)],
        }
        if error.path
        else {"level": "error", "message": {"text": str(error)}}
        for error in errors
    ]
    return {
        "$schema": SARIF_SCHEMA,
        "version": "2.1.0",
        "runs": [
            {
                "tool": {
                    "driver": {
                        "name": "inertia-lint",
                        "version": __version__,
                        "rules": [
                            _sarif_rule(code, name, catalog.find(code))
                            for code, name in names.items()
                        ],
                    }
                },
                "invocations": [
                    {
                        "executionSuccessful": not errors,
                        "toolExecutionNotifications": notifications,
                    }
                ],
                "columnKind": "unicodeCodePoints",
                "results": results,
            }
        ],
    }


def _sarif_fix(finding: Finding) -> dict[str, Any]:
    fix = finding.fix
    assert fix is not None
    by_path: dict[str, list[dict[str, Any]]] = {}
    for edit in fix.edits:
        by_path.setdefault(edit.path, []).append(
            {
                "deletedRegion": {"charOffset": edit.start, "charLength": edit.end - edit.start},
                "insertedContent": {"text": edit.content},
            }
        )
    return {
        "description": {"text": fix.title},
        "artifactChanges": [
            {"artifactLocation": {"uri": _uri(path)}, "replacements": replacements}
            for path, replacements in by_path.items()
        ],
        "properties": {"safety": str(fix.safety)},
    }


# --- statistics and summary -----------------------------------------------------------------


def statistics(findings: Iterable[Finding], as_json: bool = False) -> str:
    """``count  CODE  name`` per rule, most frequent first (or a JSON array)."""
    counts = Counter((f.code, f.name) for f in findings)
    rows = sorted(counts.items(), key=lambda item: (-item[1], item[0][0]))
    if as_json:
        return _dumps([{"code": code, "name": name, "count": n} for (code, name), n in rows]) + "\n"
    width = max((len(str(n)) for n in counts.values()), default=1)
    return "".join(f"{n:>{width}}  {code}  {name}\n" for (code, name), n in rows)


def _count(n: int, word: str, plural: str | None = None) -> str:
    return f"{n} {word if n == 1 else plural or word + 's'}"


def summary(findings: Sequence[Finding], checked: int, unreadable: int = 0) -> str:
    """``Found 3 errors, 1 warning in 2 files.`` or ``No findings in 4 files.``"""
    if findings:
        by_severity = Counter(f.severity for f in findings)
        words = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "info"}
        parts = [
            _count(by_severity[level], word, "info" if level is Severity.INFO else None)
            for level, word in words.items()
            if by_severity[level]
        ]
        files = len({f.path for f in findings})
        text = f"Found {', '.join(parts)} in {_count(files, 'file')}"
    else:
        text = f"No findings in {_count(checked, 'file')}"
    if unreadable:
        text += f"; {_count(unreadable, 'file')} could not be read"
    return text + "."
