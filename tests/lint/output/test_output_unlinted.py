"""
A file that could not be read is in every machine-read format (issue 13: `github` printed
nothing for it and `json` `[]`), with the file and line its error carries; the text formats
tell it on stderr, as before.
"""

from __future__ import annotations

import json

import pytest
from kit.junit import valid
from output_kit import lint

BROKEN = '<?xml version="1.0"?>\n<robot name="b">\n  <link name="a">\n</robot>\n'
ERROR = "not well-formed XML: Opening and ending tag mismatch: link line 3 and robot"
STDERR = (
    f"error: robots/broken.urdf:4:9: {ERROR}\nNo findings in 1 file; 1 file could not be read.\n"
)


@pytest.fixture
def broken(robots):
    (robots / "robots" / "broken.urdf").write_text(BROKEN)


def run(output_format: str) -> str:
    """A broken file and a clean one: exit 2, the error on stderr; the report."""
    code, stdout, stderr = lint(
        "--output-format",
        output_format,
        "--select",
        "IN098",
        "robots/broken.urdf",
        "robots/cart.urdf.xacro",
    )
    assert (code, stderr) == (2, STDERR)
    return stdout


def test_json_has_an_entry_with_the_keys_of_a_finding(broken):
    (entry,) = json.loads(run("json"))
    assert entry == {
        "code": "IN000",
        "name": "unreadable-file",
        "severity": "error",
        "message": ERROR,
        "detail": None,
        "file": "robots/broken.urdf",
        "line": 4,
        "column": 9,
        "link": None,
        "joint": None,
        "expected": None,
        "help": None,
        "fix": None,
        "unfixable": None,
        "macro": None,
    }


def test_github_annotates_the_file_at_its_line(broken):
    assert run("github") == (
        "::error title=inertia-lint (IN000),file=robots/broken.urdf,line=4,col=9::"
        f"robots/broken.urdf:4:9: IN000 unreadable-file: {ERROR}\n"
    )


def test_sarif_lists_it_in_the_invocation(broken):
    (invocation,) = json.loads(run("sarif"))["runs"][0]["invocations"]
    assert invocation["executionSuccessful"] is False
    (note,) = invocation["toolExecutionNotifications"]
    region = note["locations"][0]["physicalLocation"]["region"]
    assert (note["message"]["text"], region) == (ERROR, {"startLine": 4, "startColumn": 9})


def test_junit_has_a_test_in_error(broken):
    broken_suite, clean_suite = valid(run("junit"))
    assert (broken_suite.get("name"), broken_suite.get("errors")) == ("robots/broken.urdf", "1")
    (case,) = broken_suite
    assert (case.get("name"), case.get("line"), case.get("column")) == (
        "IN000 unreadable-file",
        "4",
        "9",
    )
    assert case[0].tag == "error" and case[0].get("message") == ERROR
    assert clean_suite[0].get("name") == "no findings"


def test_gitlab_has_a_critical_issue(broken, monkeypatch):
    monkeypatch.delenv("CI_PROJECT_DIR", raising=False)
    (issue,) = json.loads(run("gitlab"))
    assert issue["check_name"] == "IN000" and issue["severity"] == "critical"
    assert issue["description"] == f"IN000: unreadable-file: {ERROR}"
    assert issue["location"] == {"path": "robots/broken.urdf", "lines": {"begin": 4}}


@pytest.mark.parametrize("output_format", ["full", "concise"])
def test_text_formats_leave_it_to_stderr(broken, output_format):
    assert run(output_format) == ""


def test_a_missing_file_has_no_line(robots):
    code, stdout, stderr = lint("--output-format", "json", "robots/none.urdf")
    (entry,) = json.loads(stdout)
    assert code == 2 and "robots/none.urdf" in stderr
    assert (entry["file"], entry["line"], entry["column"]) == ("robots/none.urdf", None, None)
    code, stdout, _ = lint("--output-format", "github", "robots/none.urdf")
    assert stdout.startswith("::error title=inertia-lint (IN000),file=robots/none.urdf::")
