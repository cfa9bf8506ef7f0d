"""The `gitlab` format: a GitLab Code Quality report whose fingerprints survive line moves."""

from __future__ import annotations

import json

from output_kit import NO_FINDINGS, NOTE, SUMMARY, lint, no_findings

from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.output import render

SEVERITIES = {"info", "minor", "major", "critical", "blocker"}


def issues(stdout: str) -> list[dict]:
    """The report, each issue checked for what GitLab requires."""
    report = json.loads(stdout)
    assert isinstance(report, list)
    for issue in report:
        assert set(issue) == {"description", "check_name", "fingerprint", "severity", "location"}
        assert issue["severity"] in SEVERITIES
        assert isinstance(issue["location"]["path"], str)
        assert issue["location"]["lines"]["begin"] >= 1
    assert len({issue["fingerprint"] for issue in report}) == len(report)
    return report


def test_gitlab_issues(robots, monkeypatch):
    monkeypatch.delenv("CI_PROJECT_DIR", raising=False)
    code, stdout, stderr = lint("--output-format", "gitlab", "robots")
    assert (code, stderr) == (1, NOTE + SUMMARY)
    assert [
        (i["check_name"], i["severity"], i["location"]["path"], i["location"]["lines"]["begin"])
        for i in issues(stdout)
    ] == [
        ("IN097", "major", "robots/arm.urdf", 10),
        ("IN098", "minor", "robots/arm.urdf", 20),
        ("IN099", "info", "robots/cart.urdf.xacro", 6),
        ("IN097", "major", "robots/cart.urdf.xacro", 10),
    ]
    # GitLab shows no check_name: the description starts with the code, as ruff's does
    assert issues(stdout)[0]["description"] == "IN097: link `upper`: mass = 0 kg is not positive"


def test_gitlab_without_findings(robots):
    assert no_findings("gitlab") == (0, "[]\n", NO_FINDINGS)


def test_gitlab_fingerprints_are_stable_across_runs_and_line_moves(robots, monkeypatch):
    monkeypatch.delenv("CI_PROJECT_DIR", raising=False)
    before = issues(lint("--output-format", "gitlab", "robots")[1])
    assert issues(lint("--output-format", "gitlab", "robots")[1]) == before
    arm = robots / "robots" / "arm.urdf"
    arm.write_text(arm.read_text().replace("<robot", "<!-- moved -->\n\n<robot", 1))
    after = issues(lint("--output-format", "gitlab", "robots")[1])
    assert [i["fingerprint"] for i in after] == [i["fingerprint"] for i in before]
    assert [i["location"]["lines"]["begin"] for i in after[:2]] == [12, 22]


def test_gitlab_paths_are_relative_to_the_project_dir(robots, monkeypatch):
    """GitLab matches paths from its checkout, $CI_PROJECT_DIR, however they were given."""
    monkeypatch.setenv("CI_PROJECT_DIR", str(robots))
    monkeypatch.chdir(robots / "robots")
    paths = {i["location"]["path"] for i in issues(lint("--output-format", "gitlab", ".")[1])}
    assert paths == {"robots/arm.urdf", "robots/cart.urdf.xacro"}
    given = str(robots / "robots" / "arm.urdf")
    paths = {i["location"]["path"] for i in issues(lint("--output-format", "gitlab", given)[1])}
    assert paths == {"robots/arm.urdf"}
    relative = issues(lint("--output-format", "gitlab", "arm.urdf")[1])
    assert {i["location"]["path"] for i in relative} == {"robots/arm.urdf"}


def test_gitlab_tells_apart_findings_that_share_code_file_and_link(monkeypatch):
    monkeypatch.delenv("CI_PROJECT_DIR", raising=False)
    same = [
        Finding("a.urdf", n, 1, "IN097", "n", Severity.ERROR, f"m{n}", link="x") for n in (1, 2)
    ]
    other = Finding("a.urdf", 1, 1, "IN097", "n", Severity.ERROR, "m", link="y")
    report = issues(render([*same, other], "gitlab"))
    assert len({i["fingerprint"] for i in report}) == 3
    # the first of a pair keeps the fingerprint it has alone
    assert report[0]["fingerprint"] == issues(render(same[:1], "gitlab"))[0]["fingerprint"]
    # a robot-wide finding (no line) starts at line 1
    robot = Finding("a.urdf", None, None, "IN040", "n", Severity.ERROR, "m")
    assert issues(render([robot], "gitlab"))[0]["location"]["lines"]["begin"] == 1
