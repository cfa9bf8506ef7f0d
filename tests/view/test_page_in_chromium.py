"""
The review page in headless Chromium with the network off: no errors, a first frame, and at
each box's projected centre (as the page reports it) the box's colour in the screenshot.
"""

from __future__ import annotations

import math

import pytest
from kit.browser import colour_family, family_at, open_page, pixels
from kit.scenes import two_box_scene

from inertia_kit.view.page import render_page


@pytest.fixture(scope="module")
def loaded(tmp_path_factory):
    html = tmp_path_factory.mktemp("page") / "review.html"
    html.write_text(render_page(two_box_scene()), encoding="utf-8")
    return open_page(html)


def test_no_errors_and_a_first_frame(loaded):
    assert loaded.errors == ""
    assert math.isfinite(loaded.first_frame_ms) and loaded.first_frame_ms > 0


def test_each_box_shows_its_colour_at_its_centre(loaded):
    image = pixels(loaded)
    assert image.size == (1280, 800)
    boxes = {(box["link"], box["kind"]): box for box in loaded.projected}
    assert set(boxes) == {
        (link, kind) for link in ("base", "arm") for kind in ("declared", "geometry")
    }
    assert all(box["visible"] for box in boxes.values())
    # the arm's declared COM is 0.5 m from its geometry's centroid: two boxes apart
    declared, geometry = boxes["arm", "declared"], boxes["arm", "geometry"]
    assert math.dist((declared["x"], declared["y"]), (geometry["x"], geometry["y"])) > 50
    assert family_at(image, declared["x"], declared["y"]) == "orange"
    assert family_at(image, geometry["x"], geometry["y"]) == "cyan"
    # the base's two boxes are one: same centre on the screen
    base = boxes["base", "declared"], boxes["base", "geometry"]
    assert math.dist((base[0]["x"], base[0]["y"]), (base[1]["x"], base[1]["y"])) < 1
    assert family_at(image, base[1]["x"], base[1]["y"]) in ("orange", "cyan")
    # and not everything is a box: the corner left of the panel is the background
    assert colour_family(image.getpixel((600, 790))) == "other"


def test_the_panel_lists_links_and_findings(loaded):
    assert "base" in loaded.panel and "arm" in loaded.panel
    assert "IN020" in loaded.panel and "robot.urdf:7:5" in loaded.panel
    assert "</script>" in loaded.panel  # a message's text is text, not markup
    assert "IN001" in loaded.panel  # a finding about the robot, not one link
