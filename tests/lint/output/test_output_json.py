"""The `json` format: one array of findings with every field."""

from __future__ import annotations

from output_kit import NO_FINDINGS, NOTE, SUMMARY, dumps, lint, no_findings


def _json_finding(code, name, severity, message, file, line, column, link, **extra):
    return {
        "code": code,
        "name": name,
        "severity": severity,
        "message": message,
        "detail": extra.get("detail"),
        "file": file,
        "line": line,
        "column": column,
        "link": link,
        "joint": None,
        "expected": extra.get("expected"),
        "help": extra.get("help"),
        "fix": None,
        "unfixable": None,
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
        detail="a stub's limit: 10 kg",
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


def test_json_exactly(robots):
    assert lint("--output-format", "json", "robots") == (1, dumps(JSON), NOTE + SUMMARY)


def test_json_without_findings(robots):
    assert no_findings("json") == (0, "[]\n", NO_FINDINGS)
