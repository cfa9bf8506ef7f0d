"""`--statistics` and the summary line."""

from __future__ import annotations

from output_kit import NOTE, SUMMARY, dumps, lint

from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.output.summary import statistics, summary


def test_statistics(robots):
    assert lint("--statistics", "robots") == (
        1,
        "2  IN097  stub-non-positive\n1  IN098  stub-heavy\n1  IN099  stub-light\n",
        NOTE + SUMMARY,
    )
    assert lint("--statistics", "--output-format", "json", "robots") == (
        1,
        dumps(
            [
                {"code": "IN097", "name": "stub-non-positive", "count": 2},
                {"code": "IN098", "name": "stub-heavy", "count": 1},
                {"code": "IN099", "name": "stub-light", "count": 1},
            ]
        ),
        NOTE + SUMMARY,
    )


def test_summary_wording():
    """One shape: `N files` always counts the files linted, findings say in how many of them."""

    def finding(severity, path="a.urdf"):
        return Finding(path, 1, 1, "IN097", "n", severity, "m")

    assert summary([], 3) == "No findings in 3 files."
    assert summary([], 1, 1) == "No findings in 1 file; 1 file could not be read."
    assert summary([finding(Severity.ERROR)], 1) == "Found 1 error in 1 file."
    assert (
        summary([finding(Severity.INFO), finding(Severity.INFO, "b.urdf")], 6)
        == "Found 2 info in 2 of 6 files."
    )
    assert (
        summary([finding(Severity.WARNING), finding(Severity.ERROR)] * 2, 5, 2)
        == "Found 2 errors, 2 warnings in 1 of 5 files; 2 files could not be read."
    )
    assert summary([finding(Severity.ERROR)], 4, 0, 1) == (
        "Found 1 error in 1 of 4 files; an internal error in 1 file."
    )


def test_summary_counts_the_linted_files_that_gave_findings():
    """
    A robot whose findings are in the files it includes is one file with findings (`flagged`),
    however many files those are; and never more files with findings than linted.
    """
    included = [Finding(p, 1, 1, "IN097", "n", Severity.ERROR, "m") for p in ("a.xacro", "b")]
    assert summary(included, 3, flagged=1) == "Found 2 errors in 1 of 3 files."
    assert summary(included, 0) == "Found 2 errors in 2 files."


def test_fix_summary_has_the_same_shape():
    warning = Finding("a.urdf", 1, 1, "IN098", "n", Severity.WARNING, "m")
    assert summary([warning], 6, fixed=5, flagged=1) == (
        "Fixed 5 findings; 1 warning remains in 1 of 6 files."
    )
    assert summary([warning] * 2, 6, fixed=1, flagged=1) == (
        "Fixed 1 finding; 2 warnings remain in 1 of 6 files."
    )
    assert summary([], 6, fixed=1) == "Fixed 1 finding; no findings remain in 6 files."
    assert summary([], 6, fixable=2, hidden=1) == (
        "No findings in 6 files.\n[*] 2 fixable with the --fix option (1 hidden fix can be "
        "enabled with the --unsafe-fixes option)."
    )


def test_summary_through_the_command(robots):
    """Two robots linted, the fragment they include is not counted; both have findings."""
    assert lint("--quiet", "robots")[2] == ""
    assert lint("robots")[2].endswith("in 2 files.\n")
    assert lint("--select", "IN098", "robots")[2] == NOTE + "Found 1 warning in 1 of 2 files.\n"


def test_statistics_align_counts():
    findings = [Finding("a", 1, i, "IN097", "n", Severity.ERROR, "m") for i in range(12)]
    findings.append(Finding("a", 1, 1, "IN098", "h", Severity.ERROR, "m"))
    assert statistics(findings) == "12  IN097  n\n 1  IN098  h\n"
    assert statistics([]) == ""
