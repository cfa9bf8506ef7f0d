"""
The page's numbers in the link's axes: each record's ``tensor`` (the six URDF values about the
COM, in the link frame) and ``along`` (the link axis each principal moment lies along), checked
against closed forms on the JSON the page embeds, and the seed simple arm's IN062 links, whose
declared tensor is the collision cylinder's in its own axes: ixx and izz differ from the
geometry's in the link's.
"""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest
from click.testing import CliRunner
from kit import EXAMPLES, write
from kit.moments import box_moments, cylinder_moments
from kit.urdf import box, collision, cylinder, inertial, joint, link, robot

from inertia_kit.cli import main
from inertia_kit.physics.mass import MassProperties
from inertia_kit.view.boxes import equivalent_box, principal_directions
from inertia_kit.view.page import render_page
from inertia_kit.view.scene import build_scene

SIMPLE_ARM = EXAMPLES / "simple_arm" / "urdf" / "simple_arm.urdf.xacro"
NAMES = ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")


def embedded(html: str) -> dict:
    """The scene as the page carries it: the JSON of its ``scene-data`` script."""
    found = re.search(r'<script type="application/json" id="scene-data">(.*?)</script>', html, re.S)
    return json.loads(found[1])


def page_scene(tmp_path, text: str) -> dict:
    return embedded(render_page(build_scene(write(tmp_path / "robot.urdf", text))))


def record(scene: dict, name: str) -> dict:
    return next(r for r in scene["links"] if r["name"] == name)


def tensor(values: dict) -> list[float]:
    return [values[name] for name in NAMES]


def test_a_cylinder_along_x_reads_in_the_link_s_axes(tmp_path):
    # a solid cylinder turned from z onto x (rpy 0 π/2 0), its inertial written for its own
    # axes (z along it): in the link's, the geometry's small moment is ixx, the declared izz
    mass, radius, length = 2.0, 0.05, 0.4
    across, _, along = cylinder_moments(mass, radius, length)
    text = robot(
        link("base"),
        joint("base", "arm"),
        link(
            "arm",
            inertial(mass, across, across, along),
            collision(cylinder(radius, length), rpy=(0, math.pi / 2, 0)),
        ),
    )
    arm = record(page_scene(tmp_path, text), "arm")
    geometry, declared = arm["geometry"], arm["declared"]
    scale = across
    np.testing.assert_allclose(
        tensor(geometry["tensor"]), [along, across, across, 0, 0, 0], rtol=1e-9, atol=1e-12 * scale
    )
    np.testing.assert_allclose(tensor(declared["tensor"]), [across, across, along, 0, 0, 0])
    assert geometry["moments"] == pytest.approx([along, across, across], rel=1e-9)
    assert geometry["along"] == ["x", "y", "z"]
    # the same moments, the least along z: written for the cylinder's own axes
    assert declared["moments"] == pytest.approx([along, across, across], rel=1e-12)
    assert declared["along"] == ["z", "x", "y"]
    assert declared["rpy"] == [0, 0, 0]
    # the equivalent box's sides go with the moments: the long side along the cylinder
    assert geometry["box"][0] == pytest.approx(math.sqrt(6 * (2 * across - along) / mass))


def test_a_turned_box_has_products_in_the_link_s_axes(tmp_path):
    # a box turned by θ about z: R diag(A, B, C) Rᵀ gives ixx = A c² + B s², iyy = A s² + B c²,
    # ixy = (A − B) c s; the declared tensor written in the box's axes with the same <origin rpy>
    mass, size, theta = 3.0, (0.4, 0.1, 0.2), math.radians(30)
    a, b, c = box_moments(mass, size)
    cos, sin = math.cos(theta), math.sin(theta)
    expected = [a * cos**2 + b * sin**2, a * sin**2 + b * cos**2, c, (a - b) * cos * sin, 0, 0]
    text = robot(
        link("base"),
        joint("base", "arm"),
        link(
            "arm",
            inertial(mass, a, b, c, rpy=(0, 0, theta)),
            collision(box(*size), rpy=(0, 0, theta)),
        ),
    )
    arm = record(page_scene(tmp_path, text), "arm")
    for kind in ("declared", "geometry"):
        np.testing.assert_allclose(tensor(arm[kind]["tensor"]), expected, rtol=1e-9, atol=1e-12)
        # the least moment (a, about the long side) along (cos θ, sin θ, 0), the largest (b)
        # along (−sin θ, cos θ, 0): no link axis; c along z
        assert arm[kind]["moments"] == pytest.approx([a, c, b])
        assert arm[kind]["along"] == ["(0.866, 0.5, 0)", "z", "(-0.5, 0.866, 0)"]
    assert arm["declared"]["rpy"] == pytest.approx([0, 0, theta])


def _directions(moments, axes) -> list:
    body = MassProperties(1.0, (0, 0, 0), axes @ np.diag(moments) @ np.transpose(axes))
    return principal_directions(equivalent_box(body))


def test_principal_directions_name_link_axes_and_planes():
    # distinct moments along the link's axes, in moment order
    assert _directions([3, 1, 2], np.eye(3)) == ["y", "z", "x"]
    # a ball: any axis is principal
    assert _directions([2, 2, 2], np.eye(3)) == ["x", "y", "z"]
    # a cylinder along y turned a hair about y: its two equal moments are the x-z plane's,
    # whatever eigenvectors the rounding picks in it
    turn = 1e-9
    about_y = np.array(
        [[math.cos(turn), 0, math.sin(turn)], [0, 1, 0], [-math.sin(turn), 0, math.cos(turn)]]
    )
    assert _directions([5, 1, 5], about_y) == ["y", "x", "z"]
    # no link axis: the direction, its largest component positive (the first of equal ones)
    half = math.sqrt(0.5)
    turned = np.array([[half, -half, 0], [half, half, 0], [0, 0, 1]])
    assert _directions([1, 2, 3], turned) == ["(0.707, 0.707, 0)", "(0.707, -0.707, 0)", "z"]


def test_moments_that_are_not_finite_lie_along_nothing():
    body = MassProperties(1.0, (0, 0, 0), np.diag([1.0, math.nan, 1.0]))
    assert principal_directions(equivalent_box(body)) == [None, None, None]


def test_the_simple_arm_page_shows_link_1_s_wrong_axes(tmp_path):
    # IN062: the declared tensor is the collision cylinder's (r 0.02 m, l 0.3 m, 1 kg) in its
    # own axes (z along it); the cylinder lies along x in link_1's
    out = tmp_path / "arm.html"
    result = CliRunner().invoke(main, ["view", str(SIMPLE_ARM), "-o", str(out)])
    assert result.exit_code == 0, result.output
    scene = embedded(out.read_text(encoding="utf-8"))
    across, _, along = cylinder_moments(1.0, 0.02, 0.3)
    for name in ("link_1", "link_2"):
        arm = record(scene, name)
        assert "IN062" in {f["code"] for f in arm["findings"]}
        declared, geometry = arm["declared"]["tensor"], arm["geometry"]["tensor"]
        assert (declared["ixx"], declared["iyy"], declared["izz"]) == pytest.approx(
            (across, across, along), rel=1e-12
        )
        assert (geometry["ixx"], geometry["iyy"], geometry["izz"]) == pytest.approx(
            (along, across, across), rel=1e-9
        )
        assert declared["ixx"] > 30 * geometry["ixx"] and geometry["izz"] > 30 * declared["izz"]
        # the principal moments alone are the same: only the axes they lie along tell them apart
        assert arm["declared"]["moments"] == pytest.approx(arm["geometry"]["moments"], rel=1e-9)
        assert arm["declared"]["along"][0] == "z" and arm["geometry"]["along"][0] == "x"
        # and the centre of mass: declared at the joint, the geometry's half a link further
        assert arm["geometry"]["com"] == pytest.approx([0.15, 0, 0], abs=1e-12)
        assert arm["declared"]["com"] == [0, 0, 0]
