"""
IN005 incomplete-geometry: what urdfdom refuses in a `<geometry>` is an error naming urdfdom's
words, and the link's other checks still run on what can be read.
"""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner
from kit import write
from kit.urdf import box, collision, cylinder, inertial, moving, sphere, visual

from inertia_kit.cli import lint_main
from inertia_kit.lint.findings import Severity

# the link: a million kilograms, which its geometry would show implausible
HEAVY = inertial(1e6, 1)

REPRODUCERS = {
    "sphere-without-radius": ("<sphere/>", "`<sphere>` has no `radius`", "Sphere shape must"),
    "box-without-size": ("<box/>", "`<box>` has no `size`", "Box shape has no size attribute"),
    "cylinder-without-length": (
        '<cylinder radius="0.1"/>',
        "`<cylinder>` has no `length`",
        "Cylinder shape must have both length and radius attributes",
    ),
    "unknown-element": (
        "<foo/>",
        "holds `<foo>`, no shape URDF has",
        "Unknown geometry type 'foo'",
    ),
    "empty-geometry": ("", "`<geometry>` is empty", "Geometry tag contains no child element."),
}


def lint_cli(tmp_path, text: str, *options: str):
    path = write(tmp_path / "robot.urdf", text)
    try:
        runner = CliRunner(mix_stderr=False)  # click < 8.2
    except TypeError:
        runner = CliRunner()
    result = runner.invoke(lint_main, [str(path), "--output-format", "json", *options])
    return result.exit_code, json.loads(result.stdout)


@pytest.mark.parametrize(("geometry", "what", "urdfdom"), REPRODUCERS.values(), ids=REPRODUCERS)
def test_reproducer_is_an_error_through_inertia_lint(tmp_path, geometry, what, urdfdom):
    exit_code, findings = lint_cli(tmp_path, moving(HEAVY + collision(geometry)))
    assert exit_code == 1
    (finding,) = [f for f in findings if f["code"] == "IN005"]
    assert finding["severity"] == "error" and finding["link"] == "arm"
    assert what in finding["message"] and f'(urdfdom: "{urdfdom}' in finding["detail"]
    assert "Gazebo, Drake, PyBullet and MuJoCo refuse the file" in finding["detail"]


@pytest.mark.parametrize(("geometry", "what", "urdfdom"), REPRODUCERS.values(), ids=REPRODUCERS)
def test_a_visual_shape_is_an_error_too(lint, geometry, what, urdfdom):
    (finding,) = lint(moving(HEAVY + visual(geometry) + collision(box(1, 1, 1))), "IN005")
    assert finding.severity == Severity.ERROR and what in finding.message
    assert "Gazebo, Drake and PyBullet refuse the file (MuJoCo drops visuals" in finding.detail


def test_points_at_the_shape_or_the_element_at_fault(lint):
    text = moving(HEAVY + collision('<cylinder radius="0.1"/>'))
    (finding,) = lint(text, "IN005")
    line = text.split("\n")[finding.line - 1]
    assert line[finding.column - 1 :].startswith("<cylinder")
    empty = moving(HEAVY + collision(""))
    (finding,) = lint(empty, "IN005")
    assert empty.split("\n")[finding.line - 1][finding.column - 1 :].startswith("<geometry>")


def test_no_geometry_element(lint):
    text = moving(HEAVY + "<collision><origin/></collision>")
    (finding,) = lint(text, "IN005")
    assert "its collision has no `<geometry>`" in finding.message
    assert "Could not parse collision element for Link [arm]" in finding.detail
    assert text.split("\n")[finding.line - 1][finding.column - 1 :].startswith("<collision>")


def test_every_absent_size_is_named(lint):
    (finding,) = lint(moving(HEAVY + collision("<cylinder/>")), "IN005")
    assert "has no `radius` and no `length`" in finding.message


def test_drake_shapes_are_an_info_saying_drake_reads_them(lint):
    shape = '<drake:ellipsoid a="0.1" b="0.2" c="0.3"/>'
    (finding,) = lint(moving(HEAVY + collision(shape)), "IN005")
    assert finding.severity == Severity.INFO
    assert finding.message.endswith("`<drake:ellipsoid>`, a Drake extension")
    assert finding.detail.startswith("Drake reads it; ")
    assert "Gazebo, PyBullet and MuJoCo refuse" in finding.detail


def test_pybullet_shapes_are_an_info_saying_pybullet_reads_them(lint):
    """pybullet_data's plane_implicit.urdf: `<plane normal="0 0 1"/>` loads in PyBullet."""
    (finding,) = lint(moving(HEAVY + collision('<plane normal="0 0 1"/>')), "IN005")
    assert finding.severity == Severity.INFO
    assert finding.message.endswith("a PyBullet extension")
    assert finding.detail.startswith("PyBullet reads it; ")
    assert "Unknown geometry type 'plane'" in finding.detail
    assert "Gazebo, Drake and MuJoCo refuse" in finding.detail


def test_complete_shapes_and_capsules_are_quiet(lint):
    for geometry in (box(0.1, 0.2, 0.3), cylinder(0.1, 0.2), sphere(0.1)):
        assert lint(moving(HEAVY + collision(geometry)), "IN005") == []
    capsule = '<capsule radius="0.1" length="0.2"/>'
    assert lint(moving(HEAVY + collision(capsule)), "IN005") == []


def test_sizes_that_are_not_numbers_are_in004s_not_in005s(lint):
    findings = lint(moving(HEAVY + collision('<sphere radius="abc"/>')), ("IN004", "IN005"))
    assert [f.code for f in findings] == ["IN004"]


def test_the_rest_of_the_link_is_still_checked(tmp_path):
    """A broken collision shape leaves the visual box: the million kilograms are still seen."""
    body = inertial(1e6, 1, izz=-1) + collision("<sphere/>") + visual(box(0.1, 0.1, 0.1))
    exit_code, findings = lint_cli(tmp_path, moving(body))
    codes = {f["code"] for f in findings}
    assert exit_code == 1
    # the shape, the tensor (judged without geometry), the density (against the visual box)
    assert {"IN005", "IN010", "IN022"} <= codes


def test_the_message_is_one_short_line_and_the_detail_has_the_basis(lint):
    (finding,) = lint(moving(HEAVY + collision("<cylinder/>")), "IN005")
    assert finding.message == (
        "link `arm`: its collision `<cylinder>` has no `radius` and no `length`"
    )
    assert len(finding.message) <= 100
    assert finding.detail == (
        'ROS (urdfdom: "Cylinder shape must have both length and radius attributes"), Gazebo, '
        "Drake, PyBullet and MuJoCo refuse the file; the link's mass and inertia are not checked "
        "against this shape"
    )
