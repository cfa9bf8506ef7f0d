"""IN024 visual-collision-mismatch: size, overlap and centroid offset of the two geometries."""

from __future__ import annotations

import pytest
from kit import moving


def arm(body: str) -> str:
    return moving(body, name="arm")


def shape(kind: str, geometry: str, xyz: str = "0 0 0", rpy: str = "0 0 0") -> str:
    return f'<{kind}><origin xyz="{xyz}" rpy="{rpy}"/><geometry>{geometry}</geometry></{kind}>'


CYLINDER = '<cylinder radius="0.02" length="0.3"/>'
ALONG_X = "0 1.5707963267948966 0"


def test_identical_geometry_is_quiet(lint):
    body = shape("visual", CYLINDER, rpy=ALONG_X) + shape("collision", CYLINDER, rpy=ALONG_X)
    assert lint(arm(body), "IN024") == []


def test_simplified_box_around_a_cylinder_is_quiet(lint):
    body = shape("visual", CYLINDER, rpy=ALONG_X) + shape(
        "collision", '<box size="0.32 0.05 0.05"/>'
    )
    assert lint(arm(body), "IN024") == []


def test_collision_turned_the_other_way_fires(lint):
    """Visual along x, collision left along z: the boxes share 0.04³ of 0.3 × 0.04²."""
    body = shape("visual", CYLINDER, rpy=ALONG_X) + shape("collision", CYLINDER)
    findings = lint(arm(body), "IN024")
    assert len(findings) == 1
    assert "misplaced or turned" in findings[0].message
    pad = 0.02 * 0.3
    expected = (0.04 + pad) ** 3 / ((0.3 + pad) * (0.04 + pad) ** 2)
    assert findings[0].expected["overlap"] == pytest.approx(expected, rel=1e-2)


def test_millimetre_scale_missing_on_one_side_fires(lint):
    body = shape("visual", '<box size="0.1 0.1 0.1"/>') + shape(
        "collision", '<box size="100 100 100"/>'
    )
    findings = lint(arm(body), "IN024")
    assert len(findings) == 1
    assert findings[0].expected["size_ratio"] == pytest.approx(1000.0)
    assert "1000 times the size" in findings[0].message


def test_misplaced_collision_fires_on_the_centroid_offset(lint):
    """A sphere drawn one radius above its collision twin: overlap 50 %, offset 50 % + ε."""
    sphere = '<sphere radius="0.05"/>'
    body = shape("visual", sphere, xyz="0 0 0.06") + shape("collision", sphere)
    findings = lint(arm(body), "IN024")
    assert len(findings) == 1
    assert findings[0].expected["centroid_offset"] == pytest.approx(0.06)
    assert "centroids are 0.06 m apart" in findings[0].message


def test_options(lint):
    body = shape("visual", '<box size="0.1 0.1 0.1"/>') + shape(
        "collision", '<box size="0.25 0.25 0.25"/>'
    )
    assert lint(arm(body), "IN024") == []  # 2.5 times: within the default 3
    assert len(lint(arm(body), "IN024", options={"IN024": {"size_factor": 2.0}})) == 1
    turned = shape("visual", CYLINDER, rpy=ALONG_X) + shape("collision", CYLINDER)
    assert lint(arm(turned), "IN024", options={"IN024": {"min_overlap": 0.1}}) == []
    sphere = '<sphere radius="0.05"/>'
    shifted = shape("visual", sphere, xyz="0 0 0.04") + shape("collision", sphere)
    assert lint(arm(shifted), "IN024") == []
    assert len(lint(arm(shifted), "IN024", options={"IN024": {"max_offset": 0.3}})) == 1


def test_several_collision_shapes_covering_the_visual_are_quiet(lint):
    """A capsule-like arm drawn as one cylinder, collided as a cylinder and two end spheres."""
    body = (
        shape("visual", '<cylinder radius="0.05" length="0.4"/>')
        + shape("collision", '<cylinder radius="0.05" length="0.3"/>')
        + shape("collision", '<sphere radius="0.05"/>', xyz="0 0 0.15")
        + shape("collision", '<sphere radius="0.05"/>', xyz="0 0 -0.15")
    )
    assert lint(arm(body), "IN024") == []


def test_only_one_kind_or_an_unusable_shape_is_not_its_business(lint):
    assert lint(arm(shape("visual", CYLINDER)), "IN024") == []
    assert lint(arm(shape("collision", CYLINDER)), "IN024") == []
    missing = shape("visual", '<mesh filename="missing.stl"/>') + shape("collision", CYLINDER)
    assert lint(arm(missing), "IN024") == []
