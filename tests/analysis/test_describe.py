"""analysis.describe: one describer of a shape, written for messages and for the report table."""

from __future__ import annotations

import pytest

from inertia_kit.analysis.describe import TABLE, describe_geometry, geometry_summary

SHAPES = [
    ('<box size="0.4 0.4 0.1"/>', "box (0.4 × 0.4 × 0.1 m)", "box 0.4×0.4×0.1"),
    ('<box size="abc 1 1"/>', "box (? m)", "box 'abc 1 1'"),
    (
        '<cylinder radius="0.35" length="0.4"/>',
        "cylinder (r = 0.35 m, l = 0.4 m)",
        "cylinder r0.35 l0.4",
    ),
    ('<cylinder length="0.4"/>', "cylinder (r = ? m, l = 0.4 m)", "cylinder r? l0.4"),
    ('<sphere radius="inf"/>', "sphere (r = ? m)", "sphere r'inf'"),
    ('<capsule radius="0.1" length="0.2"/>', "capsule (r = 0.1 m, l = 0.2 m)", "capsule r0.1 l0.2"),
    (
        '<mesh filename="package://a/pan.stl"/>',
        "mesh `package://a/pan.stl`",
        "mesh pan.stl (not found)",
    ),
    (
        '<mesh filename="d/pan.stl" scale="0.001 0.001 0.001"/>',
        "mesh `d/pan.stl`",
        "mesh pan.stl ×0.001 (not found)",
    ),
    (
        '<mesh filename="pan.stl" scale="1 2 1"/>',
        "mesh `pan.stl`",
        "mesh pan.stl ×1×2×1 (not found)",
    ),
    ("<cone/>", "unknown geometry", "<cone>"),
    ("", "unknown geometry", "empty geometry"),
]


@pytest.mark.parametrize(("element", "message", "table"), SHAPES)
def test_a_shape_in_both_styles(analysed, element, message, table):
    link = analysed(f'<link name="a"><visual><geometry>{element}</geometry></visual></link>')
    geometry = link.links[0].link.visuals[0].geometry
    assert describe_geometry(geometry) == message
    assert describe_geometry(geometry, TABLE) == table


def test_geometry_summary_prefers_collision_shapes(analysed):
    robot = analysed(
        """<link name="both">
          <visual><geometry><sphere radius="1"/></geometry></visual>
          <collision><geometry><box size="1 2 3"/></geometry></collision>
          <collision><geometry><sphere radius="0.5"/></geometry></collision>
        </link>
        <link name="visual"><visual><geometry><sphere radius="1"/></geometry></visual></link>
        <link name="none"/>"""
    )
    both, visual, none = (link.link for link in robot.links)
    assert geometry_summary(both) == "collision: box 1×2×3, sphere r0.5"
    assert geometry_summary(visual) == "visual only: sphere r1"
    assert geometry_summary(none) == "no geometry"
