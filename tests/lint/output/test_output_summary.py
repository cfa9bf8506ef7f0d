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
    def finding(severity, path="a.urdf"):
        return Finding(path, 1, 1, "IN097", "n", severity, "m")

    assert summary([], 3) == "No findings in 3 files."
    assert summary([], 1, 1) == "No findings in 1 file; 1 file could not be read."
    assert summary([finding(Severity.ERROR)], 1) == "Found 1 error in 1 file."
    assert (
        summary([finding(Severity.INFO), finding(Severity.INFO, "b.urdf")], 2)
        == "Found 2 info in 2 files."
    )
    assert (
        summary([finding(Severity.WARNING), finding(Severity.ERROR)] * 2, 5, 2)
        == "Found 2 errors, 2 warnings in 1 file; 2 files could not be read."
    )


def test_statistics_align_counts():
    findings = [Finding("a", 1, i, "IN097", "n", Severity.ERROR, "m") for i in range(12)]
    findings.append(Finding("a", 1, 1, "IN098", "h", Severity.ERROR, "m"))
    assert statistics(findings) == "12  IN097  n\n 1  IN098  h\n"
    assert statistics([]) == ""
