"""IN050 joint-limits: missing, incomplete or impossible <limit>s."""

from __future__ import annotations

import pytest

from inertia_kit.lint.findings import Severity


def robot(kind: str, inner: str) -> str:
    return f"""<robot name="r">
  <link name="base"/>
  <joint name="j" type="{kind}">
    <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>{inner}
  </joint>
  <link name="arm"/>
</robot>"""


GOOD = '<limit lower="-1" upper="1" effort="10" velocity="2"/>'


@pytest.mark.parametrize("kind", ["revolute", "prismatic", "continuous"])
def test_complete_limits_are_quiet(lint, kind):
    assert lint(robot(kind, GOOD), "IN050") == []


def test_continuous_and_fixed_need_no_limit(lint):
    assert lint(robot("continuous", ""), "IN050") == []
    assert lint(robot("fixed", ""), "IN050") == []


@pytest.mark.parametrize(
    ("kind", "quoted"),
    [
        ("revolute", "Joint [j] is of type REVOLUTE but it does not specify limits"),
        ("prismatic", "Joint [j] is of type PRISMATIC without limits"),
    ],
)
def test_missing_limit_is_an_error(lint, kind, quoted):
    findings = lint(robot(kind, ""), "IN050")
    assert len(findings) == 1
    assert findings[0].severity == Severity.ERROR and quoted in findings[0].detail
    assert findings[0].message == f"joint `j`: {kind} joint has no <limit>"
    assert findings[0].joint == "j" and findings[0].link == "arm"


@pytest.mark.parametrize("kind", ["revolute", "continuous"])
@pytest.mark.parametrize("missing", ["effort", "velocity"])
def test_missing_effort_or_velocity_is_an_error(lint, kind, missing):
    attributes = {"lower": "-1", "upper": "1", "effort": "10", "velocity": "2"}
    del attributes[missing]
    limit = "<limit " + " ".join(f'{k}="{v}"' for k, v in attributes.items()) + "/>"
    findings = lint(robot(kind, limit), "IN050")
    assert len(findings) == 1 and findings[0].severity == Severity.ERROR
    assert f'"joint limit: no {missing}"' in findings[0].detail


def test_lower_above_upper_is_an_error(lint):
    limit = '<limit lower="1" upper="-1" effort="10" velocity="2"/>'
    findings = lint(robot("prismatic", limit), "IN050")
    assert len(findings) == 1 and findings[0].severity == Severity.ERROR
    assert "lower = 1 m is above upper = -1 m" in findings[0].message
    assert "no limits" in findings[0].detail


def test_negative_effort_is_an_error(lint):
    limit = '<limit lower="-1" upper="1" effort="-5" velocity="2"/>'
    findings = lint(robot("revolute", limit), "IN050")
    assert len(findings) == 1 and findings[0].severity == Severity.ERROR
    assert "effort = -5 N·m is negative" in findings[0].message


def test_zero_effort_and_velocity_warn_once(lint):
    limit = '<limit lower="-1" upper="1" effort="0" velocity="0"/>'
    findings = lint(robot("revolute", limit), "IN050")
    assert len(findings) == 1 and findings[0].severity == Severity.WARNING
    assert findings[0].message.startswith("joint `j`: effort = 0 N·m and velocity = 0 rad/s")
    limit = '<limit lower="-1" upper="1" effort="0" velocity="1"/>'
    (finding,) = lint(robot("prismatic", limit), "IN050")
    assert "effort = 0 N:" in finding.message and "velocity" not in finding.message.split(":")[1]


def test_zero_on_a_mimic_joint_is_quiet(lint):
    limit = '<limit lower="-1" upper="1" effort="0" velocity="0"/><mimic joint="other"/>'
    assert lint(robot("revolute", limit), "IN050") == []


def test_allow_zero_option(lint):
    limit = '<limit lower="-1" upper="1" effort="0" velocity="0"/>'
    assert lint(robot("revolute", limit), "IN050", options={"IN050": {"allow_zero": True}}) == []


def test_missing_lower_and_upper_warn(lint):
    findings = lint(robot("revolute", '<limit effort="10" velocity="2"/>'), "IN050")
    assert len(findings) == 1 and findings[0].severity == Severity.WARNING
    assert "no lower and upper" in findings[0].message
    assert findings[0].detail == "lower and upper: both default to 0 in urdfdom"
    findings = lint(robot("revolute", '<limit lower="-1" effort="10" velocity="2"/>'), "IN050")
    assert len(findings) == 1 and "moves in [-1, 0] rad" in findings[0].message


def test_non_numeric_values_are_left_to_in004(lint):
    limit = '<limit lower="a" upper="1" effort="x" velocity="2"/>'
    assert lint(robot("revolute", limit), "IN050") == []


def test_the_message_is_one_short_line_and_the_detail_has_the_basis(lint):
    limit = '<limit lower="-1" upper="1" effort="0" velocity="0"/>'
    (finding,) = lint(robot("revolute", limit), "IN050")
    assert finding.message == (
        "joint `j`: effort = 0 N·m and velocity = 0 rad/s: nothing can drive it"
    )
    assert len(finding.message) <= 100
    assert finding.detail.startswith("Gazebo clamps the joint's force to ±effort")
    assert "MoveIt reads 0 as unlimited" in finding.detail
