"""IN024 visual-collision-mismatch: size, overlap and centroid offset of the two geometries."""

from __future__ import annotations

import pytest
from kit.urdf import box, collision, cylinder, mesh, moving, sphere, visual

CYLINDER = cylinder(0.02, 0.3)
ALONG_X = "0 1.5707963267948966 0"


def test_identical_geometry_is_quiet(lint):
    body = visual(CYLINDER, rpy=ALONG_X) + collision(CYLINDER, rpy=ALONG_X)
    assert lint(moving(body), "IN024") == []


def test_simplified_box_around_a_cylinder_is_quiet(lint):
    body = visual(CYLINDER, rpy=ALONG_X) + collision(box(0.32, 0.05, 0.05))
    assert lint(moving(body), "IN024") == []


def test_collision_turned_the_other_way_fires(lint):
    """Visual along x, collision left along z: the boxes share 0.04³ of 0.3 × 0.04²."""
    body = visual(CYLINDER, rpy=ALONG_X) + collision(CYLINDER)
    findings = lint(moving(body), "IN024")
    assert len(findings) == 1
    assert "misplaced or turned" in findings[0].message
    pad = 0.02 * 0.3
    expected = (0.04 + pad) ** 3 / ((0.3 + pad) * (0.04 + pad) ** 2)
    assert findings[0].expected["overlap"] == pytest.approx(expected, rel=1e-2)


def test_millimetre_scale_missing_on_one_side_fires(lint):
    body = visual(box(0.1, 0.1, 0.1)) + collision(box(100, 100, 100))
    findings = lint(moving(body), "IN024")
    assert len(findings) == 1
    assert findings[0].expected["size_ratio"] == pytest.approx(1000.0)
    assert "1000 times the size" in findings[0].message


def test_misplaced_collision_fires_on_the_centroid_offset(lint):
    """A sphere drawn one radius above its collision twin: overlap 50 %, offset 50 % + ε."""
    ball = sphere(0.05)
    body = visual(ball, xyz="0 0 0.06") + collision(ball)
    findings = lint(moving(body), "IN024")
    assert len(findings) == 1
    assert findings[0].expected["centroid_offset"] == pytest.approx(0.06)
    assert "centroids are 0.06 m apart" in findings[0].message


def test_options(lint):
    body = visual(box(0.1, 0.1, 0.1)) + collision(box(0.25, 0.25, 0.25))
    assert lint(moving(body), "IN024") == []  # 2.5 times: within the default 3
    assert len(lint(moving(body), "IN024", options={"IN024": {"size_factor": 2.0}})) == 1
    turned = visual(CYLINDER, rpy=ALONG_X) + collision(CYLINDER)
    assert lint(moving(turned), "IN024", options={"IN024": {"min_overlap": 0.1}}) == []
    ball = sphere(0.05)
    shifted = visual(ball, xyz="0 0 0.04") + collision(ball)
    assert lint(moving(shifted), "IN024") == []
    assert len(lint(moving(shifted), "IN024", options={"IN024": {"max_offset": 0.3}})) == 1


def test_several_collision_shapes_covering_the_visual_are_quiet(lint):
    """A capsule-like arm drawn as one cylinder, collided as a cylinder and two end spheres."""
    body = (
        visual(cylinder(0.05, 0.4))
        + collision(cylinder(0.05, 0.3))
        + collision(sphere(0.05), xyz="0 0 0.15")
        + collision(sphere(0.05), xyz="0 0 -0.15")
    )
    assert lint(moving(body), "IN024") == []


def test_only_one_kind_or_an_unusable_shape_is_not_its_business(lint):
    assert lint(moving(visual(CYLINDER)), "IN024") == []
    assert lint(moving(collision(CYLINDER)), "IN024") == []
    missing = visual(mesh("missing.stl")) + collision(CYLINDER)
    assert lint(moving(missing), "IN024") == []
