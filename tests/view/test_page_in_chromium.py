"""
The review page in headless Chromium with the network off: no errors, a first frame, and at
each box's projected centre (as the page reports it) the box's colour in the screenshot.
"""

from __future__ import annotations

import math

import pytest
from kit.browser import boxes, colour_family, family_at, open_page, pixels
from kit.scenes import link, solid_box, translation, two_box_scene

from inertia_kit.view.page import render_page


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    html = tmp_path_factory.mktemp("page") / "review.html"
    html.write_text(render_page(two_box_scene()), encoding="utf-8")
    return html


@pytest.fixture(scope="module")
def loaded(page):
    return open_page(page)


def width(box) -> float:
    return box["rect"][2] - box["rect"][0]


def test_no_errors_a_first_frame_and_no_request_but_the_page(page, loaded):
    assert loaded.errors == ""
    assert math.isfinite(loaded.first_frame_ms) and loaded.first_frame_ms > 0
    assert loaded.requests == [page.resolve().as_uri()]


def test_a_request_would_be_seen(tmp_path):
    # the check above can fail: a page that asks for an image is caught asking (and the CSP
    # and the dead network refuse it)
    html = tmp_path / "review.html"
    text = render_page(two_box_scene()).replace(
        '<pre id="page-errors"', '<img src="https://example.com/x.png"><pre id="page-errors"'
    )
    html.write_text(text, encoding="utf-8")
    assert "https://example.com/x.png" in open_page(html).requests


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


@pytest.mark.parametrize("scale", [0.02, 1.0, 30.0])
def test_the_robot_fills_the_view_whatever_its_size(tmp_path, scale):
    html = tmp_path / "review.html"
    html.write_text(render_page(two_box_scene(scale)), encoding="utf-8")
    loaded = open_page(html)
    rects = [box["rect"] for box in loaded.projected]
    left, right = min(r[0] for r in rects), max(r[2] for r in rects)
    top, bottom = min(r[1] for r in rects), max(r[3] for r in rects)
    # the 3D view is 920 × 800 (the panel takes 360 px): the robot spans a good part of it
    assert max(right - left, bottom - top) > 300
    assert left >= 0 and right <= 920 and top >= 0 and bottom <= 800


def test_a_joint_slider_moves_the_links_after_it(page, loaded):
    moved = open_page(
        page,
        then="""(() => {
          const slider = document.querySelector('#joints input[data-joint="shoulder"]');
          slider.value = "1"; slider.dispatchEvent(new Event("input"));
          return slider.value; })()""",
    )
    assert moved.errors == "" and moved.result == "1"
    before, after = boxes(loaded), boxes(moved)
    # the arm's declared COM is 0.5 m off the z axis it turns about: it moves on the screen
    arm = before["arm", "declared"], after["arm", "declared"]
    assert math.dist((arm[0]["x"], arm[0]["y"]), (arm[1]["x"], arm[1]["y"])) > 30
    # its geometry box is on that axis, and the base does not move at all
    for key in (("arm", "geometry"), ("base", "declared")):
        assert (
            math.dist((before[key]["x"], before[key]["y"]), (after[key]["x"], after[key]["y"])) < 1
        )


def test_clicking_a_link_in_the_panel_focuses_it(page, loaded):
    focused = open_page(
        page, then="""document.querySelector('.link[data-link="base"]').click(), 1"""
    )
    assert focused.errors == ""
    before, after = boxes(loaded)["base", "declared"], boxes(focused)["base", "declared"]
    # the camera turns to it (the middle of the 920 × 800 view) and comes closer
    assert (
        math.dist((after["x"], after["y"]), (460, 400))
        < 5
        < math.dist((before["x"], before["y"]), (460, 400))
    )
    assert width(after) > 1.5 * width(before)


def test_clicking_a_box_in_3d_selects_its_link_in_the_panel(page, loaded):
    box = boxes(loaded)["arm", "declared"]
    click = f"""(() => {{
      const canvas = document.querySelector("#view canvas");
      for (const type of ["pointerdown", "pointerup"]) {{
        canvas.dispatchEvent(new PointerEvent(type, {{clientX: {box["x"]}, clientY: {box["y"]},
                                                      bubbles: true}}));
      }}
      return [...document.querySelectorAll(".link.selected")].map(e => e.dataset.link);
    }})()"""
    assert open_page(page, then=click).result == ["arm"]


def test_an_error_in_the_page_is_recorded_and_fails_the_png(tmp_path):
    from inertia_kit.view.screenshot import RendererError, screenshot

    scene = two_box_scene()
    del scene["meshes"]  # page.js reads scene.meshes: a TypeError
    html = tmp_path / "broken.html"
    html.write_text(render_page(scene), encoding="utf-8")
    loaded = open_page(html)
    assert "TypeError" in loaded.errors
    with pytest.raises(RendererError, match=r"the page reported errors in Chromium: .*TypeError"):
        screenshot(html, tmp_path / "broken.png")
    assert not (tmp_path / "broken.png").exists()


def test_a_joint_whose_limits_exclude_zero_still_opens_in_the_zero_pose(tmp_path):
    scene = two_box_scene()
    scene["links"][1]["joint"].update(lower=0.5, upper=1.0)
    html = tmp_path / "review.html"
    html.write_text(render_page(scene), encoding="utf-8")
    read = """(() => { const s = document.querySelector('#joints input[data-joint="shoulder"]');
                       return [s.min, s.max, s.value]; })()"""
    assert open_page(html, then=read).result == ["0", "1", "0"]


# --- names that are Object.prototype's keys ---------------------------------------------------

#: names a page that keys plain objects by link or joint names breaks on: its joint sliders threw
#: a TypeError and the robot no longer posed
PROTOTYPE_NAMES = ("__proto__", "constructor", "toString", "hasOwnProperty", "valueOf")


def prototype_scene() -> dict:
    """
    A chain ``__proto__`` -(``constructor``)-> ``toString`` -(``hasOwnProperty``)-> ``valueOf``
    of revolute joints about z, each link's declared box 0.5 m along x from its frame (so a
    turn moves it on the screen), and a link ``constructor`` on a joint ``valueOf`` whose type is
    ``toString`` (no type the page moves: no slider).
    """
    size = (0.2, 0.2, 0.2)
    box = solid_box(2.0, size, (0.5, 0, 0))

    def joint(name, kind="revolute"):
        axis = [0, 0, 1]
        return {"name": name, "type": kind, "origin": translation(0, 0, 0.4), "axis": axis,
                "lower": -1.0, "upper": 1.0}  # fmt: skip

    def record(name, parent=None, joint_record=None, height=0.0):
        return link(name, parent, joint=joint_record, world=translation(0, 0, height),
                    size=size, declared=box, geometry=dict(box, density=250.0))  # fmt: skip

    scene = two_box_scene()
    scene["links"] = [
        record("__proto__"),
        record("toString", "__proto__", joint("constructor"), 0.4),
        record("valueOf", "toString", joint("hasOwnProperty"), 0.8),
        record("constructor", "__proto__", joint("valueOf", "toString"), 0.4),
    ]
    return scene


@pytest.fixture(scope="module")
def prototype_page(tmp_path_factory):
    html = tmp_path_factory.mktemp("prototype") / "review.html"
    html.write_text(render_page(prototype_scene()), encoding="utf-8")
    return html


def _turn(joint: str) -> str:
    return f"""(() => {{
      const slider = document.querySelector('#joints input[data-joint="{joint}"]');
      slider.value = "1"; slider.dispatchEvent(new Event("input"));
      return [...document.querySelectorAll("#joints input")].map(s => s.dataset.joint); }})()"""


def _moved(before, after, link: str) -> float:
    a, b = before[link, "declared"], after[link, "declared"]
    return math.dist((a["x"], a["y"]), (b["x"], b["y"]))


def test_prototype_names_draw_without_error(prototype_page):
    loaded = open_page(prototype_page)
    assert loaded.errors == ""
    assert {link for link, _ in boxes(loaded)} == {
        "__proto__", "toString", "valueOf", "constructor"
    }  # fmt: skip
    assert all(name in loaded.panel for name in PROTOTYPE_NAMES[:3])


def test_a_slider_named_constructor_moves_its_child_and_what_follows(prototype_page):
    before = boxes(open_page(prototype_page))
    turned = open_page(prototype_page, then=_turn("constructor"))
    # sliders for the two revolute joints only: `valueOf` is of type `toString`
    assert turned.errors == "" and turned.result == ["constructor", "hasOwnProperty"]
    after = boxes(turned)
    assert _moved(before, after, "toString") > 30 and _moved(before, after, "valueOf") > 30
    assert _moved(before, after, "__proto__") < 1 and _moved(before, after, "constructor") < 1


def test_a_slider_named_has_own_property_moves_its_child_only(prototype_page):
    before = boxes(open_page(prototype_page))
    turned = open_page(prototype_page, then=_turn("hasOwnProperty"))
    assert turned.errors == ""
    after = boxes(turned)
    assert _moved(before, after, "valueOf") > 30
    for still in ("__proto__", "toString", "constructor"):
        assert _moved(before, after, still) < 1


@pytest.mark.parametrize("name", ["__proto__", "constructor"])
def test_selecting_a_link_named_after_a_prototype_key(prototype_page, name):
    select = f"""(() => {{
      document.querySelector('.link[data-link="{name}"]').click();
      return [...document.querySelectorAll(".link.selected")].map(e => e.dataset.link); }})()"""
    selected = open_page(prototype_page, then=select)
    assert selected.errors == "" and selected.result == [name]


# --- names with characters that rewrite what the reader sees ----------------------------------


def test_bidirectional_controls_and_line_breaks_in_names_show_as_escapes(tmp_path):
    # "Trojan source": U+202E reverses what follows on the screen; the panel shows it as the
    # terminal output does (inertia_kit.printable), the link still selectable by its exact name
    name, joint_name = "arm\u202eevil", "shoulder\n::error::x"
    scene = two_box_scene()
    scene["links"][1]["name"] = name
    scene["links"][1]["joint"]["name"] = joint_name
    scene["links"][1]["findings"][0]["message"] = f"link {name} is \u2066odd\u2069 \U0001f916"
    html = tmp_path / "review.html"
    html.write_text(render_page(scene), encoding="utf-8")
    select = f"""(() => {{
      const card = [...document.querySelectorAll(".link")].find(e => e.dataset.link === {name!r});
      card.click();
      const label = document.querySelector("#joints label");
      return [document.querySelectorAll(".link.selected").length, label.title]; }})()"""
    loaded = open_page(html, then=select)
    assert loaded.errors == ""
    assert "arm\\u202eevil" in loaded.panel and "\u202e" not in loaded.panel
    assert "\\u2066odd\\u2069" in loaded.panel and "\U0001f916" in loaded.panel  # pairs kept
    assert loaded.result == [1, "shoulder\\n::error::x (revolute)"]
