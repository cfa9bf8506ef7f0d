"""What --redact-env keeps out: values as text, their printed forms, JSON values and findings."""

from __future__ import annotations

import json
import math

import pytest
from kit import write

from inertia_kit.description.loader import load
from inertia_kit.description.redaction import MARK, Redaction, recordable
from inertia_kit.description.urdf.xacro_expand import expand
from inertia_kit.description.xacro_limits import XacroLimits
from inertia_kit.errors import InputError
from inertia_kit.lint.findings import Finding, Severity


def test_text_every_occurrence_longest_first():
    redaction = Redaction().with_values(["hunter2", "hunter2-prod"])
    assert redaction.text("link `arm_hunter2-prod`, mesh /x/hunter2/m.stl") == (
        f"link `arm_{MARK}`, mesh /x/{MARK}/m.stl"
    )


def test_short_values_and_booleans_are_not_redacted():
    redaction = Redaction().with_values(["1", "0.5", "arm", "true", "False", "on", " no "])
    assert not redaction
    assert (
        redaction.text("IN001 line 1: 0.5 kg on arm, true") == "IN001 line 1: 0.5 kg on arm, true"
    )
    assert [recordable(v) for v in (True, None, 3, 2.5, 31337, "abcd")] == [
        None, None, None, None, "31337", "abcd"
    ]  # fmt: skip


def test_a_value_with_a_control_character_is_redacted_as_printed_too():
    redaction = Redaction().with_values(["tok\nen"])
    assert redaction.text("a tok\nen b") == f"a {MARK} b"
    assert redaction.text("a tok\\nen b") == f"a {MARK} b"  # as printable() shows it


def test_a_numeric_value_in_the_forms_numbers_are_printed_in():
    redaction = Redaction().with_values(["31337.25"])
    message = "mass 31337.25 kg (31337 kg; 3.134e+04; 31337.2 in the report)"
    assert redaction.text(message) == f"mass {MARK} kg ({MARK} kg; {MARK}; {MARK} in the report)"
    # a JSON number equal to it: null (a string would change the type)
    assert redaction.apply({"mass": 31337.25, "line": 31337, "other": 2.5}) == {
        "mass": None,
        "line": 31337,
        "other": 2.5,
    }


def test_json_values_but_not_keys():
    redaction = Redaction().with_values(["code", "message-secret"])
    data = {"code": "IN001", "message": "link `message-secret`", "list": ["code", ("code",)]}
    assert redaction.apply(data) == {
        "code": "IN001",
        "message": f"link `{MARK}`",
        "list": [MARK, (MARK,)],
    }
    json.dumps(redaction.apply(data))


def test_findings_and_errors_are_copies_with_every_text_redacted():
    redaction = Redaction().with_values(["/opt/secret", "tok3n"])
    finding = Finding(
        "/opt/secret/r.xacro", 3, 4, "IN030", "mesh-not-found", Severity.ERROR,
        "link `tok3n`: mesh `/opt/secret/m.stl` not found", link="tok3n",
        expected={"searched": ["/opt/secret/m.stl"]}, via=("/opt/secret/robot.xacro",),
    )  # fmt: skip
    redacted = redaction.apply(finding)
    assert redacted.path == f"{MARK}/r.xacro" and redacted.link == MARK
    assert redacted.message == f"link `{MARK}`: mesh `{MARK}/m.stl` not found"
    assert redacted.expected == {"searched": [f"{MARK}/m.stl"]}
    assert redacted.via == (f"{MARK}/robot.xacro",) and finding.link == "tok3n"
    error = InputError("cannot read /opt/secret/x.xacro", "/opt/secret/r.xacro", 2)
    shown = redaction.apply(error)
    assert str(shown) == f"{MARK}/r.xacro:2: cannot read {MARK}/x.xacro"
    assert isinstance(shown, InputError) and str(error).startswith("/opt/secret")


def test_nothing_to_redact_is_the_value_itself():
    finding = Finding("r.urdf", 1, 1, "IN001", "n", Severity.ERROR, "m")
    assert Redaction().apply(finding) is finding
    assert Redaction().text("x") == "x"
    assert math.isnan(Redaction().with_values(["abcd"]).apply(float("nan")))


# --- what an expansion records ----------------------------------------------------------------

ROBOT = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="cfg" value="${xacro.load_yaml('secrets.yaml')}"/>
  <link name="base_$(env SECRET_NAME)"/>
  <link name="arm_${cfg['name']}_$(optenv UNSET_VARIABLE fromfile)">
    <inertial><mass value="$(optenv SECRET_MASS 1)"/></inertial>
  </link>
  <link name="$(arg frame)"/>
</robot>
"""
YAML = "name: hunter2-yaml\nlimits: {mass: 31337.25, on: true, list: [alpha-value, 7]}\n"


@pytest.mark.parametrize("limits", [XacroLimits(), XacroLimits(0, 0, 0)], ids=["fork", "here"])
def test_an_expansion_records_what_the_environment_gave(tmp_path, monkeypatch, limits):
    monkeypatch.setenv("SECRET_NAME", "tok3n-env")
    monkeypatch.setenv("SECRET_MASS", "4242.5")
    write(tmp_path / "secrets.yaml", YAML)
    path = write(tmp_path / "r.urdf.xacro", ROBOT)
    expanded = expand(path, args={"frame": "given-by-argument"}, limits=limits)
    # env, optenv (set); YAML's values, not its keys; not an optenv default, an argument, a
    # boolean or a short number
    assert set(expanded.environment_values) == {
        "tok3n-env", "4242.5", "hunter2-yaml", "31337.25", "alpha-value"
    }  # fmt: skip
    assert load(path, xacro_args={"frame": "f"}, xacro_limits=limits).environment_values


def test_a_failed_expansion_still_says_what_the_environment_gave(tmp_path, monkeypatch):
    monkeypatch.setenv("SECRET_DIR", "/opt/s3cret")
    path = write(
        tmp_path / "r.urdf.xacro",
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="$(env SECRET_DIR)/arm.xacro"/><link name="a"/></robot>',
    )
    with pytest.raises(InputError) as caught:
        expand(path)
    assert "/opt/s3cret" in str(caught.value)
    assert caught.value.environment_values == ("/opt/s3cret",)


def test_an_error_is_copied_even_where_a_library_registers_a_reducer_for_exceptions():
    """tblib (installed by Dask's distributed) registers a copyreg reducer that hands a copy the
    original's own __dict__: the redacted error must still be a copy."""
    import copyreg

    def shared(error):
        return _rebuilt, (type(error), error.__dict__, error.args)

    original = copyreg.dispatch_table.get(InputError)
    copyreg.pickle(InputError, shared)
    try:
        error = InputError("cannot read /opt/secret/x.xacro", "/opt/secret/r.xacro", 2)
        shown = Redaction().with_values(["/opt/secret"]).apply(error)
    finally:
        if original is None:
            del copyreg.dispatch_table[InputError]
        else:
            copyreg.dispatch_table[InputError] = original
    assert str(shown) == f"{MARK}/r.xacro:2: cannot read {MARK}/x.xacro"
    assert str(error) == "/opt/secret/r.xacro:2: cannot read /opt/secret/x.xacro"


def _rebuilt(cls, attributes, args):
    error = cls.__new__(cls)
    error.__dict__ = attributes  # the original's own dict, as tblib's reducer does
    error.args = args
    return error
