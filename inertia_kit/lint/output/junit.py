"""
``junit``: JUnit XML, as ruff writes it, for the test reports of CI dashboards (GitLab's
``artifacts:reports:junit``, GitHub test-report actions). A ``<testsuite>`` per file, named by
its path; in it a ``<testcase>`` per finding with a ``<failure>`` (the finding's severity as its
``type``), a passing ``<testcase>`` for a linted file without findings, and a ``<testcase>`` with
an ``<error>`` for a file that could not be linted. Test cases carry ``file``, ``line`` and
``column``, which report viewers use to link to the source.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from collections.abc import Iterable, Iterator, Sequence
from pathlib import PurePath
from typing import TYPE_CHECKING

from inertia_kit.lint.findings import Finding
from inertia_kit.lint.output.common import UNLINTED, message, unlinted_name
from inertia_kit.printable import UNPRINTABLE_ABOVE_C0, escape

if TYPE_CHECKING:
    from inertia_kit.errors import InputError, InternalError

PACKAGE = "org.inertia-kit"
CLEAN = "no findings"
# characters XML 1.0 cannot hold, even escaped (ElementTree writes them as they are): shown as
# escapes (``\x1b``), the nearest to the exact name XML allows
_NOT_XML = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ufffe\uffff\ud800-\udfff]")
# line breaks in a finding's text stand for these (characters _content has replaced) until
# written as references: ElementTree writes them raw, and a raw line feed in a message starts a
# line of the report that a CI log reads on its own (a link name "\n::error ..." a command)
_BREAKS = {"\n": ("\x00", "&#10;"), "\r": ("\x01", "&#13;")}


def render(
    findings: Sequence[Finding],
    errors: Sequence[InputError | InternalError] = (),
    linted: Sequence[str] = (),
) -> str:
    return "".join(pieces(findings, errors, linted))


def pieces(
    findings: Sequence[Finding],
    errors: Sequence[InputError | InternalError] = (),
    linted: Iterable[str] = (),
) -> Iterator[str]:
    """
    :func:`render`'s text in pieces, a test suite (a file) at a time: the suites come sorted by
    path with the totals before them, so the findings are first only counted, by path, then
    read by position (``findings`` is indexed) as each suite is written.
    """
    at: dict[str, list[int]] = {}
    for position, finding in enumerate(findings):
        at.setdefault(finding.path, []).append(position)
    unlinted: dict[str, list[InputError | InternalError]] = {}
    for error in errors:
        unlinted.setdefault(error.path or "", []).append(error)
    paths = set(at) | set(unlinted) | set(linted)
    if not paths:  # nothing linted: one passing test, so that a report exists (ruff's)
        paths = {"inertia-lint"}
    tests = sum(max(1, len(at.get(p, ())) + len(unlinted.get(p, ()))) for p in paths)
    report = ET.Element(
        "testsuites",
        name="inertia-lint",
        tests=str(tests),
        failures=str(len(findings)),
        errors=str(len(errors)),
    )
    opening = ET.tostring(report, "unicode").removesuffix(" />") + ">"
    yield '<?xml version="1.0" encoding="UTF-8"?>\n' + opening
    for path in sorted(paths):
        cases = [_failure(findings[i]) for i in at.get(path, ())]
        cases += [_error(error) for error in unlinted.get(path, ())]
        suite = _suite(path, cases or [_case(CLEAN, path)])
        _writable(suite)
        ET.indent(suite, space="    ", level=1)
        yield "\n    " + _safe(ET.tostring(suite, "unicode"))
    yield "\n</testsuites>\n"


def _safe(text: str) -> str:
    """Written XML with line breaks and what a CI log must not print raw as references."""
    for stand_in, reference in _BREAKS.values():
        text = text.replace(stand_in, reference)
    # C1 controls, line separators and bidirectional controls as references too (the same
    # text once read), so that the report is safe to print in a CI log
    return UNPRINTABLE_ABOVE_C0.sub(lambda match: f"&#x{ord(match.group()):x};", text)


def _held(text: str) -> str:
    return _NOT_XML.sub(lambda match: escape(match.group()), text)


def _content(text: str) -> str:
    """A finding's text (message, help) for text content: as XML can hold it, its line breaks
    stand-ins for their references (a break of our own, between message and help, stays)."""
    text = _held(text)
    for char, (stand_in, _) in _BREAKS.items():
        text = text.replace(char, stand_in)
    return text


def _writable(report: ET.Element) -> None:
    """Every attribute of ``report`` as XML can hold it (ElementTree writes line breaks in
    attributes as references itself)."""
    for element in report.iter():
        element.attrib = {key: _held(value) for key, value in element.attrib.items()}


def _suite(path: str, cases: list[ET.Element]) -> ET.Element:
    suite = ET.Element("testsuite", name=path)
    failures = sum(case.find("failure") is not None for case in cases)
    errors = sum(case.find("error") is not None for case in cases)
    suite.attrib |= {
        "tests": str(len(cases)),
        "disabled": "0",
        "errors": str(errors),
        "failures": str(failures),
        "package": PACKAGE,
    }
    suite.extend(cases)
    return suite


def _case(name: str, path: str, line: int | None = None, column: int | None = None) -> ET.Element:
    # classname: the path without its suffixes, as ruff's (robots/arm.urdf.xacro -> robots/arm);
    # a hidden file keeps its leading dots (robots/.arm.urdf -> robots/.arm)
    pure = PurePath(path)
    hidden = len(pure.name) - len(pure.name.lstrip("."))
    stem = pure.name[:hidden] + pure.name[hidden:].split(".")[0]
    classname = pure.with_name(stem).as_posix() if stem.strip(".") else path
    case = ET.Element("testcase", name=name, classname=classname, file=path)
    if line is not None:
        case.set("line", str(line))
        if column is not None:
            case.set("column", str(column))
    return case


def _where(line: int | None, column: int | None) -> str:
    parts = [f"line {line}" if line is not None else "", f"col {column}" if column else ""]
    return "".join(f"{part}, " for part in parts if part)


def _failure(finding: Finding) -> ET.Element:
    case = _case(f"{finding.code} {finding.name}", finding.path, finding.line, finding.column)
    failure = ET.SubElement(case, "failure", message=message(finding), type=str(finding.severity))
    failure.text = _where(finding.line, finding.column) + _content(message(finding))
    if finding.detail:
        failure.text += f"\n{_content(finding.detail)}"
    if finding.help:
        failure.text += f"\nhelp: {_content(finding.help)}"
    return case


def _error(error: InputError | InternalError) -> ET.Element:
    name = unlinted_name(error)
    case = _case(f"{UNLINTED} {name}", error.path or "", error.line, error.column)
    failed = ET.SubElement(case, "error", message=error.message, type=name)
    failed.text = _where(error.line, error.column) + _content(error.message)
    return case
