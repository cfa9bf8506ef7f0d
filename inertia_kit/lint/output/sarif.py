"""
``sarif``: SARIF 2.1.0, for code scanning. The rules listed are those with findings, each with
its document as help; unreadable files are the invocation's notifications.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Iterator, Sequence
from pathlib import Path
from types import ModuleType
from typing import Any
from urllib.parse import quote

from inertia_kit.errors import InputError
from inertia_kit.lint import catalog, documents
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.output.common import ENTRIES, dumps_streamed, finite, message
from inertia_kit.version import __version__

SCHEMA = (
    "https://docs.oasis-open.org/sarif/sarif/v2.1.0/errata01/os/schemas/sarif-schema-2.1.0.json"
)
_LEVELS = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "note"}


def render(findings: Sequence[Finding], errors: Sequence[InputError] = ()) -> str:
    return "".join(pieces(findings, errors))


def _uri(path: str) -> str:
    """A SARIF artifact URI: relative paths stay relative (GitHub reads them from the root)."""
    if Path(path).is_absolute():
        return Path(path).as_uri()
    # the name's bytes (a name that is no UTF-8 too), percent-encoded as as_uri does
    return quote(os.fsencode(Path(path).as_posix()), safe="/")


def _physical(path: str, line: int | None, column: int | None) -> dict[str, Any]:
    physical: dict[str, Any] = {"artifactLocation": {"uri": _uri(path)}}
    if line is not None and line >= 1:
        region: dict[str, Any] = {"startLine": line}
        if column is not None and column >= 1:
            region["startColumn"] = column
        physical["region"] = region
    return {"physicalLocation": physical}


def _rule(code: str, name: str, rule: ModuleType | None) -> dict[str, Any]:
    summary = (rule.SUMMARY if rule is not None else "") or name
    entry: dict[str, Any] = {
        "id": code,
        "name": name,
        "shortDescription": {"text": summary},
    }
    if rule is not None:
        entry["defaultConfiguration"] = {"level": _LEVELS[rule.SEVERITY]}
    document = documents.rule_documents().get(code)
    if document is not None:
        text = document.read_text(encoding="utf-8")
        entry["help"] = {"text": text, "markdown": text}
    return entry


def _text(finding: Finding) -> str:
    return message(finding) + (f"\n\n{finding.detail}" if finding.detail else "")


def _log(names: dict[str, str], errors: Sequence[InputError], results: list[Any]) -> dict[str, Any]:
    """A SARIF 2.1.0 log of one run, listing the rules ``names`` (those with findings)."""
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
        "$schema": SCHEMA,
        "version": "2.1.0",
        "runs": [
            {
                "tool": {
                    "driver": {
                        "name": "inertia-lint",
                        "version": __version__,
                        "rules": [
                            _rule(code, name, catalog.find(code)) for code, name in names.items()
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


def pieces(findings: Sequence[Finding], errors: Sequence[InputError] = ()) -> Iterator[str]:
    """:func:`render`'s text in pieces, a result at a time (``findings`` is read twice: for
    the rules, listed before the results, then for the results)."""
    names = _names(findings)
    return dumps_streamed(_log(names, errors, [ENTRIES]), _results(findings, names))


def _names(findings: Iterable[Finding]) -> dict[str, str]:
    """The rules with findings, code -> name, by code: the order of their ``ruleIndex``."""
    return dict(sorted({(f.code, f.name) for f in findings}))


def _results(findings: Iterable[Finding], names: dict[str, str]) -> Iterator[dict[str, Any]]:
    index = {code: i for i, code in enumerate(names)}
    for finding in findings:
        result: dict[str, Any] = {
            "ruleId": finding.code,
            "ruleIndex": index[finding.code],
            "level": _LEVELS[finding.severity],
            # the first line is the claim SARIF viewers show as the result's summary
            "message": {"text": _text(finding)},
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
                ("expected", finite(finding.expected)),
                ("detail", finding.detail),
                ("help", finding.help),
                ("via", list(finding.via) or None),
            )
            if value is not None
        }
        result["properties"] = properties
        if finding.fix is not None:
            result["fixes"] = [_fix(finding)]
        yield result


def _fix(finding: Finding) -> dict[str, Any]:
    fix = finding.fix
    assert fix is not None
    by_path: dict[str, list[dict[str, Any]]] = {}
    places = fix.places or (None,) * len(fix.edits)
    for edit, place in zip(fix.edits, places, strict=True):
        # lines and columns for viewers that read only those (GitHub), offsets for exactness
        region: dict[str, Any] = {}
        if place is not None:
            region = {
                "startLine": place.start_line,
                "startColumn": place.start_column,
                "endLine": place.end_line,
                "endColumn": place.end_column,
            }
        region |= {"charOffset": edit.start, "charLength": edit.end - edit.start}
        by_path.setdefault(edit.path, []).append(
            {"deletedRegion": region, "insertedContent": {"text": edit.content}}
        )
    return {
        "description": {"text": fix.title},
        "artifactChanges": [
            {"artifactLocation": {"uri": _uri(path)}, "replacements": replacements}
            for path, replacements in by_path.items()
        ],
        "properties": {"safety": str(fix.safety)},
    }
