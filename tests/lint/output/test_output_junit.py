"""The `junit` format: a test suite per file, as ruff writes it, read as CI reports read it."""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner
from kit.junit import valid
from output_kit import NO_FINDINGS, NOTE, SUMMARY, lint, no_findings

from inertia_kit.cli import main
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.output import render

JUNIT = """\
<?xml version="1.0" encoding="UTF-8"?>
<testsuites name="inertia-lint" tests="4" failures="4" errors="0">
    <testsuite name="robots/arm.urdf" tests="2" disabled="0" errors="0" failures="2" \
package="org.inertia-kit">
        <testcase name="IN097 stub-non-positive" classname="robots/arm" file="robots/arm.urdf" \
line="10" column="7">
            <failure message="link `upper`: mass = 0 kg is not positive" type="error">\
line 10, col 7, link `upper`: mass = 0 kg is not positive
help: give the link's real mass</failure>
        </testcase>
        <testcase name="IN098 stub-heavy" classname="robots/arm" file="robots/arm.urdf" \
line="20" column="7">
            <failure message="link `fore`: 25 kg, more than 10 kg" type="warning">\
line 20, col 7, link `fore`: 25 kg, more than 10 kg
a stub's limit: 10 kg</failure>
        </testcase>
    </testsuite>
    <testsuite name="robots/cart.urdf.xacro" tests="2" disabled="0" errors="0" failures="2" \
package="org.inertia-kit">
        <testcase name="IN099 stub-light" classname="robots/cart" file="robots/cart.urdf.xacro" \
line="6" column="7">
            <failure message="0.005 kg" type="info">line 6, col 7, 0.005 kg</failure>
        </testcase>
        <testcase name="IN097 stub-non-positive" classname="robots/cart" \
file="robots/cart.urdf.xacro" line="10" column="3">
            <failure message="link `left_wheel`: mass = -1 kg is not positive" type="error">\
line 10, col 3, link `left_wheel`: mass = -1 kg is not positive
help: give the link's real mass</failure>
        </testcase>
    </testsuite>
</testsuites>
"""


def test_junit_exactly(robots):
    assert lint("--output-format", "junit", "robots") == (1, JUNIT, NOTE + SUMMARY)
    valid(JUNIT)


def test_junit_a_clean_file_is_a_passing_test(robots):
    code, stdout, stderr = no_findings("junit")
    assert (code, stderr) == (0, NO_FINDINGS)
    (suite,) = valid(stdout)
    assert suite.get("name") == "robots/cart.urdf.xacro"
    (case,) = suite
    assert (case.get("name"), case.get("classname"), list(case)) == (
        "no findings",
        "robots/cart",
        [],
    )


def test_junit_files_with_and_without_findings(robots):
    code, stdout, _ = lint("--output-format", "junit", "--select", "IN098", "robots")
    root = valid(stdout)
    assert code == 1
    assert [(s.get("name"), s.get("tests"), s.get("failures")) for s in root] == [
        ("robots/arm.urdf", "1", "1"),
        ("robots/cart.urdf.xacro", "1", "0"),
    ]


def test_junit_with_no_file_still_is_a_report(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "empty").mkdir()
    code, stdout, _ = lint("--output-format", "junit", "empty")
    (suite,) = valid(stdout)
    assert (code, suite.get("name"), suite[0].get("name")) == (0, "inertia-lint", "no findings")


def test_junit_escapes_markup_and_shows_what_xml_cannot_hold():
    finding = Finding("a&b.urdf", 3, None, "IN097", "n", Severity.ERROR, 'x <y> "z"\x01 &')
    root = valid(render([finding], "junit", linted=["a&b.urdf"]))
    (case,) = root[0]
    assert (
        case.get("file") == "a&b.urdf" and case.get("line") == "3" and "column" not in case.attrib
    )
    # XML 1.0 cannot hold U+0001, even as a reference: shown as its escape
    assert case[0].get("message") == 'x <y> "z"\\x01 &'
    assert case[0].text == 'line 3, x <y> "z"\\x01 &'


def test_junit_names_the_class_of_a_hidden_file_by_its_dotted_stem():
    """A file whose name starts with a dot (and ``-``'s stand-in) is a class, not a crash."""
    findings = [
        Finding(path, 3, 1, "IN097", "n", Severity.ERROR, "m")
        for path in ("robots/.arm.urdf", ".cart.urdf.xacro", "..urdf")
    ]
    root = valid(render(findings, "junit"))
    classes = [suite[0].get("classname") for suite in root]
    assert classes == ["..urdf", ".cart", "robots/.arm"]


def test_junit_reads_a_robot_from_stdin(robots, monkeypatch):
    """The stand-in of ``-`` is a hidden file beside the one it stands for (fuzz input 11)."""
    robot = (Path("robots") / "arm.urdf").read_bytes()
    runner = CliRunner()
    result = runner.invoke(main, ["lint", "--output-format", "junit", "-"], input=robot)
    assert result.exit_code in (0, 1) and "internal error" not in result.output
    valid(result.stdout)
