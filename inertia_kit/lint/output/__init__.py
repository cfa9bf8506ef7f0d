"""
Findings out: the output formats of ``inertia-lint``, one module each.

- ``full``: ``path:line:col: CODE [severity] message``, the source line with a caret under the
  element, the macro body line for an element a xacro macro produced, and ``help``;
- ``concise``: ``path:line:col: CODE message``, one line each, for editors;
- ``json``: one array of :meth:`Finding.to_json` objects;
- ``github``: workflow commands that GitHub Actions shows as annotations;
- ``sarif``: SARIF 2.1.0, for code scanning;
- ``junit``: JUnit XML, a test suite per file, for CI test reports;
- ``gitlab``: a GitLab Code Quality report.

Files that could not be read, and internal errors (a bug), are in every machine-read format
(json, github, sarif, junit, gitlab) as :mod:`.common`'s ``IN000`` entries; the text formats
(full, concise) leave them to the caller's ``error:`` lines on stderr.

:mod:`.summary` adds the statistics and the summary line. Paths are shown as the findings carry
them (as given on the command line, or as xacro included them). Colour is added by ``style``,
and removed by the caller when the output is no terminal. Adding a format: a module with its
``render`` (and its ``pieces`` when it is one document), a branch in :func:`pieces`, and its
name in :data:`FORMATS` and in the CLI's ``--output-format`` choices. :func:`pieces` gives a
report in pieces, for a run that writes it as it is made (from a
:class:`~inertia_kit.lint.output.spool.Spool`), in bounded memory.
"""

from __future__ import annotations

import importlib
from collections.abc import Iterable, Iterator, Sequence
from itertools import islice

from inertia_kit.errors import InputError
from inertia_kit.lint.findings import Finding
from inertia_kit.lint.output.common import Style, plain

FORMATS = ("full", "concise", "json", "github", "sarif", "junit", "gitlab")


def render(
    findings: Sequence[Finding],
    output_format: str,
    *,
    errors: Sequence[InputError] = (),
    style: Style | None = None,
    unsafe_fixes: bool = False,
    linted: Sequence[str] = (),
) -> str:
    """
    The findings in one format, ending in a newline (empty for no findings, except ``json``,
    ``sarif``, ``junit`` and ``gitlab``, which always give a document); ``[*]`` marks a finding
    whose fix ``--fix`` applies (``unsafe_fixes``: unsafe ones too). ``errors`` (unreadable
    files, internal errors) are in the machine-read formats; ``linted`` (the files linted)
    gives ``junit`` a passing test for each file without findings.
    """
    return "".join(
        pieces(
            findings,
            output_format,
            errors=errors,
            style=style,
            unsafe_fixes=unsafe_fixes,
            linted=linted,
        )
    )


#: how many findings a text format renders at a time when it is written in pieces
_BATCH = 256


def pieces(
    findings: Sequence[Finding],
    output_format: str,
    *,
    errors: Sequence[InputError] = (),
    style: Style | None = None,
    unsafe_fixes: bool = False,
    linted: Iterable[str] = (),
) -> Iterator[str]:
    """
    :func:`render`'s text in pieces, each written as soon as it is made, so that a report of
    any length is written in bounded memory when ``findings`` are read one at a time from disk
    (a :class:`~inertia_kit.lint.output.spool.Spool`).
    """
    # each format is imported when chosen: a lint run pays for its own format only
    style = style or plain
    if output_format in ("json", "sarif", "gitlab"):
        module = importlib.import_module(f"inertia_kit.lint.output.{output_format}")
        return module.pieces(findings, errors)  # type: ignore[no-any-return]
    if output_format == "junit":
        from inertia_kit.lint.output import junit

        return junit.pieces(findings, errors, linted)
    if output_format not in FORMATS:
        raise ValueError(f"unknown output format {output_format!r}; known: {', '.join(FORMATS)}")
    return _text_pieces(findings, output_format, errors, style, unsafe_fixes)


def _text_pieces(
    findings: Sequence[Finding],
    output_format: str,
    errors: Sequence[InputError],
    style: Style,
    unsafe_fixes: bool,
) -> Iterator[str]:
    """The line-by-line formats, whose text is that of each finding in turn."""
    if output_format == "github":
        from inertia_kit.lint.output import github

        for batch in _batches(findings):
            yield github.render(batch)
        yield github.render((), errors)
        return
    if output_format == "full":
        from inertia_kit.lint.output import full as module
    else:
        from inertia_kit.lint.output import concise as module
    for batch in _batches(findings):
        yield module.render(batch, style, unsafe_fixes)


def _batches(findings: Iterable[Finding]) -> Iterator[list[Finding]]:
    found = iter(findings)
    while batch := list(islice(found, _BATCH)):
        yield batch
