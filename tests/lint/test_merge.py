"""The results of several linted files as one run: each finding and message once."""

from __future__ import annotations

from inertia_kit.errors import InputError
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.merge import Tally, merge
from inertia_kit.lint.runner import FileResult


def finding(path: str, line: int, message: str = "m", severity=Severity.WARNING) -> Finding:
    return Finding(path, line, 3, "IN099", "stub", severity, message)


def test_a_finding_in_a_shared_macro_file_is_told_once():
    shared = finding("macros.xacro", 7)
    a = FileResult("a.xacro", [finding("a.xacro", 2), shared], notes=["macros.xacro:1: odd"])
    b = FileResult(
        "b.xacro", [shared, finding("macros.xacro", 7, "other")], notes=["macros.xacro:1: odd"]
    )
    merged = merge([a, b])
    assert merged.findings == [
        finding("a.xacro", 2),
        shared,
        finding("macros.xacro", 7, "other"),
    ]
    assert merged.messages == [("warning", "macros.xacro:1: odd")]
    assert (merged.errors, merged.failing, merged.checked) == ([], True, 2)


def test_unreadable_files_fragments_and_disabled_files_are_not_checked():
    error = InputError("no such file", "missing.urdf")
    results = [
        FileResult("missing.urdf", error=error),
        FileResult("macros.xacro", fragment=True),
        FileResult("off.urdf", disabled=True),
        FileResult("ok.urdf", [finding("ok.urdf", 1, severity=Severity.INFO)]),
    ]
    merged = merge(results)
    assert merged.errors == [error]
    assert merged.messages == [
        ("error", str(error)),
        (
            "note",
            "macros.xacro: a xacro fragment (macros and properties only, to be included): skipped",
        ),
    ]
    assert (merged.failing, merged.checked) == (False, 1)  # an info is below fail-on warning


def test_a_finding_several_robots_report_names_them_all_once():
    import dataclasses

    shared = finding("wheels.xacro", 9)
    one = dataclasses.replace(shared, via=("a.xacro",))
    two = dataclasses.replace(shared, via=("b.xacro",))
    merged = merge([FileResult("a.xacro", [one]), FileResult("b.xacro", [two, one])])
    assert [f.via for f in merged.findings] == [("a.xacro", "b.xacro")]
    # the file linted as itself too: its own finding, told without `via`
    merged = merge([FileResult("a.xacro", [one]), FileResult("wheels.xacro", [shared])])
    assert [f.via for f in merged.findings] == [()]


def test_linted_files_and_those_that_gave_findings():
    """
    The summary's `in 2 of 4 files`: a robot whose findings are in its includes gave findings;
    a fragment linted through its robots counts when they found something in it.
    """
    results = [
        FileResult("a.xacro", [finding("macros.xacro", 7)]),
        FileResult("b.urdf"),
        FileResult("c.urdf", [finding("c.urdf", 1)]),
        FileResult("macros.xacro", [finding("macros.xacro", 7)], fragment=True, remarks=["r"]),
        FileResult("empty.xacro", fragment=True, remarks=["r"]),
        FileResult("bad.urdf", error=InputError("no such file", "bad.urdf")),
    ]
    merged = merge(results)
    assert merged.linted == ("a.xacro", "b.urdf", "c.urdf", "macros.xacro")
    assert (merged.checked, merged.flagged) == (4, 3)


def test_a_tally_counts_by_severity_rule_and_fix():
    findings = [
        finding("a.urdf", 1, severity=Severity.ERROR),
        finding("a.urdf", 2),
        finding("b.urdf", 3, severity=Severity.INFO),
    ]
    tally = Tally.of(findings)
    assert tally.total == 3
    assert dict(tally.by_severity) == {Severity.ERROR: 1, Severity.WARNING: 1, Severity.INFO: 1}
    assert dict(tally.by_rule) == {("IN099", "stub"): 3}
    assert (tally.fixable, tally.fixable_unsafe, tally.hidden) == (0, 0, 0)
    both = tally + Tally.of(findings[:1])
    assert (both.total, both.by_severity[Severity.ERROR], tally.total) == (4, 2, 3)


def test_findings_told_before_the_merge_count_as_if_they_were_merged():
    told = [finding("a.urdf", 1, severity=Severity.ERROR)]
    kept = [finding("a.urdf", 2)]
    whole = merge([FileResult("a.urdf", told + kept), FileResult("b.urdf")])
    released = FileResult("a.urdf", kept, told=1, told_failing=True)
    streamed = merge([released, FileResult("b.urdf")], Tally.of(told))
    assert streamed.findings == kept
    assert streamed.tally == whole.tally
    assert (streamed.failing, streamed.checked, streamed.flagged, streamed.linted) == (
        whole.failing,
        whole.checked,
        whole.flagged,
        whole.linted,
    )
    # every finding told: the file still counts as linted and flagged, and fails the run
    all_told = merge([FileResult("a.urdf", told=2, told_failing=True)], Tally.of(told + kept))
    assert (all_told.findings, all_told.flagged, all_told.failing) == ([], 1, True)
    assert all_told.tally.total == 2
