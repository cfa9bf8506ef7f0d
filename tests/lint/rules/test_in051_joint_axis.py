"""IN051 joint-axis: zero and non-unit axes of moving joints."""

from __future__ import annotations

import pytest

from inertia_kit.lint.findings import Severity

LIMIT = '<limit lower="-1" upper="1" effort="10" velocity="2"/>'


def robot(axis: str | None, kind: str = "revolute") -> str:
    element = "" if axis is None else f'<axis xyz="{axis}"/>'
    limit = LIMIT if kind in ("revolute", "prismatic") else ""
    return f"""<robot name="r">
  <link name="base"/>
  <joint name="j" type="{kind}">
    <parent link="base"/><child link="arm"/>{element}{limit}
  </joint>
  <link name="arm"/>
</robot>"""


@pytest.mark.parametrize("axis", ["0 0 1", "0 0.7071 0.7071", "0 -1 0", None])
def test_unit_or_absent_axes_are_quiet(lint, axis):
    assert lint(robot(axis), "IN051") == []


@pytest.mark.parametrize("kind", ["revolute", "continuous", "prismatic", "planar"])
def test_zero_axis_is_an_error(lint, kind):
    findings = lint(robot("0 0 0", kind), "IN051")
    assert len(findings) == 1 and findings[0].severity == Severity.ERROR
    assert findings[0].message == "joint `j`: axis `0 0 0` has no direction"
    assert "axis too small" in findings[0].detail


def test_non_unit_axis_warns_with_the_unit_vector(lint):
    findings = lint(robot("0 1 1"), "IN051")
    assert len(findings) == 1
    finding = findings[0]
    assert finding.severity == Severity.WARNING and finding.joint == "j"
    assert finding.message == "joint `j`: axis `0 1 1` has length 1.414, not 1"
    assert len(finding.message) <= 100
    assert "PyBullet" in finding.detail and "1.414 times as far" in finding.detail
    assert finding.help == 'write the unit vector: <axis xyz="0 0.707107 0.707107"/>'
    assert finding.expected["axis"] == pytest.approx([0, 0.5**0.5, 0.5**0.5])


@pytest.mark.parametrize("kind", ["fixed", "floating"])
def test_joints_that_ignore_the_axis_are_quiet(lint, kind):
    assert lint(robot("0 0 0", kind), "IN051") == []


def test_tolerance_option(lint):
    assert lint(robot("0 0 1.01"), "IN051") != []
    assert lint(robot("0 0 1.01"), "IN051", options={"IN051": {"tolerance": 0.05}}) == []
    assert lint(robot("0 0 1.0001"), "IN051") == []


def test_non_numeric_axis_is_left_to_in004(lint):
    assert lint(robot("0 0 x"), "IN051") == []
