"""
Suppression comments for findings, as ruff's ``--add-noqa`` writes them: so that a repository
adopts the linter with its current findings suppressed, and only new ones fail.

Where a comment goes: directly before the innermost element at the finding's line and column,
in the file the finding is reported in (for an element a xacro macro made, that is the macro
call: the comment covers that call's instance only; see :mod:`inertia_kit.lint.suppress`),
indented as the element is and ended with the file's newline. A finding without a line (the
robot as a whole) goes before the root ``<robot>``. When an ``ignore[...]`` comment already
stands before the element, the new codes are added to it. Unused-suppression findings (IN090)
are never suppressed: their fix removes the comment instead.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field

from inertia_kit.description import lines
from inertia_kit.description.edits import ChangedWhileEditing, Edit, SourceText, apply_edits
from inertia_kit.description.reads import as_loaded
from inertia_kit.errors import InputError
from inertia_kit.lint import catalog, markup
from inertia_kit.lint.findings import Finding

COMMENT = "<!-- inertia-lint: ignore[{}] -->"


@dataclass
class Plan:
    """The new text of every file that gains comments, and what could not be suppressed."""

    texts: dict[str, tuple[SourceText, str]] = field(default_factory=dict)  # path -> (old, new)
    added: dict[str, int] = field(default_factory=dict)  # path -> comments written or extended
    extended: int = 0  # of those, comments already there that gained codes
    skipped: list[tuple[Finding, str]] = field(default_factory=list)  # (finding, why)


def plan(
    findings: Iterable[Finding],
    writable: Callable[[str], bool],
    reads: Mapping[str, str | None] | None = None,
) -> Plan:
    """
    The comments that suppress ``findings``; a finding in a file ``writable`` refuses (an
    installed package's macro) is listed in ``skipped`` with the reason. Each file is read as
    the lint's loads read it (``reads``: :mod:`inertia_kit.description.reads`), else
    ``ChangedWhileEditing``: the findings' lines would point into another text.
    """
    result = Plan()
    by_file: dict[str, list[Finding]] = {}
    for finding in findings:
        rule = catalog.find(finding.code)
        if rule is not None and rule.SCOPE == "suppressions":
            result.skipped.append((finding, "an unused suppression: remove it (its fix is safe)"))
        elif not finding.path:
            result.skipped.append((finding, "it has no file"))
        elif not writable(finding.path):
            result.skipped.append(
                (
                    finding,
                    f"{finding.path} is outside the paths given: lint the folder that holds "
                    "it, or add a per-file ignore to the configuration",
                )
            )
        else:
            by_file.setdefault(finding.path, []).append(finding)
    for path, found in by_file.items():
        try:
            source = as_loaded(path, reads or {})
        except ChangedWhileEditing:
            raise
        except InputError as error:
            result.skipped.extend((f, f"cannot edit: {error}") for f in found)
            continue
        edits, extended, skipped = _file_edits(source, found)
        result.skipped.extend(skipped)
        if edits:
            text, applied = apply_edits(source.text, edits)
            assert len(applied) == len(edits), "suppression comments overlap"
            result.texts[path] = (source, text)
            result.added[path] = len(edits)
            result.extended += extended
    return result


def _file_edits(
    source: SourceText, findings: list[Finding]
) -> tuple[list[Edit], int, list[tuple[Finding, str]]]:
    layout = markup.layout(source.text)
    codes: dict[int, tuple[markup.Element, set[str]]] = {}  # element start -> (element, codes)
    skipped = []
    for finding in findings:
        element = (
            layout.root if finding.line is None else layout.innermost(finding.line, finding.column)
        )
        if element is None:
            skipped.append((finding, f"no element holds line {finding.line} of {source.path}"))
            continue
        codes.setdefault(element.start, (element, set()))[1].add(finding.code)
    made, extended = [], 0
    for element, wanted in codes.values():
        edit = _edit(source, element, sorted(wanted))
        if edit is not None:
            made.append(edit)
            extended += _existing(element) is not None
    return made, extended, skipped


def _edit(source: SourceText, element: markup.Element, codes: list[str]) -> Edit | None:
    """A new comment before ``element``, or the codes added to the ``ignore[...]`` before it."""
    text = source.text
    existing = _existing(element)
    if existing is not None:
        start, end, items = existing.selectors()  # type: ignore[misc]
        known = [s for s in (catalog.normalize_selector(i) for i in items) if s is not None]
        new = [code for code in codes if not catalog.selects(known, code, _name(code))]
        if not new:
            return None
        at = start + len(text[start:end].rstrip())
        return Edit(source.path, at, at, (", " if items else "") + ", ".join(new))
    comment = COMMENT.format(", ".join(codes))
    line_start = lines.line_start(text, element.start)
    indent = text[line_start : element.start]
    if indent.strip(" \t"):  # something else stands before it on its line: the comment too
        return Edit(source.path, element.start, element.start, comment)
    return Edit(source.path, line_start, line_start, f"{indent}{comment}{source.newline}")


def _existing(element: markup.Element) -> markup.Comment | None:
    """The ``ignore[...]`` comment nearest before ``element``, if one is there."""
    return next((c for c in reversed(element.before) if c.selectors() is not None), None)


def _name(code: str) -> str:
    rule = catalog.find(code)
    return "" if rule is None else rule.NAME
