"""
Which box is whose, in headless Chromium: the panel's declared and geometry values side by side
in the link's axes (the cells that differ highlighted), the link's name on hover and on
selection, the selected link's boxes standing out, isolate / show all / a link hidden alone.
"""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner
from kit import EXAMPLES
from kit.browser import boxes, family_at, open_page, pixels
from kit.scenes import two_box_scene

from inertia_kit.cli import main
from inertia_kit.view.page import render_page

SIMPLE_ARM = EXAMPLES / "simple_arm" / "urdf" / "simple_arm.urdf.xacro"

# synthetic pointer events have no real pointer for OrbitControls to capture: the capture is
# left out, the events go through the page's handlers as a mouse's would
NO_CAPTURE = """const canvas = document.querySelector("#view canvas");
canvas.setPointerCapture = () => {}; canvas.releasePointerCapture = () => {};"""


def pointer(types, x, y) -> str:
    return "".join(
        f"canvas.dispatchEvent(new PointerEvent({kind!r}, {{clientX: {x}, clientY: {y}, "
        "bubbles: true, pointerId: 1}));"
        for kind in types
    )


#: what the page shows of the labels, the selection and the links shown
STATE = """({
  hover: document.getElementById("hover-label").hidden ? null
         : document.getElementById("hover-label").textContent,
  selection: document.getElementById("selection-label").hidden ? null
             : document.getElementById("selection-label").textContent,
  at: (() => { const r = document.getElementById("selection-label").getBoundingClientRect();
               return [r.left + r.width / 2, r.bottom]; })(),
  selected: [...document.querySelectorAll(".link.selected")].map(e => e.dataset.link),
  shown: [...document.querySelectorAll(".link input.shown")].map(e => e.checked),
  hidden: [...document.querySelectorAll(".link.hidden-link")].map(e => e.dataset.link),
  isolate: document.getElementById("isolate").disabled,
  showAll: document.getElementById("show-all").disabled,
  status: document.querySelector("#tools .status").textContent,
})"""


def then(*steps: str) -> str:
    """Run ``steps`` (JavaScript statements), then give the page's :data:`STATE` two frames on."""
    frames = "await new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)));"
    return "(async () => {" + NO_CAPTURE + "".join(steps) + frames + "return " + STATE + "; })()"


def click_card(name: str) -> str:
    return f"document.querySelector('.link[data-link=\"{name}\"]').click();"


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    html = tmp_path_factory.mktemp("controls") / "review.html"
    html.write_text(render_page(two_box_scene()), encoding="utf-8")
    return html


@pytest.fixture(scope="module")
def loaded(page):
    return open_page(page)


# --- the panel: declared and geometry in the link's axes --------------------------------------

#: each row of a link's table: [row, declared text, geometry text, declared differs, geometry
#: differs]
ROWS = """((name) => [...document.querySelectorAll(
    `.link[data-link="${name}"] table.inertia tr[data-row]`)].map(row => {
  const [declared, geometry] = row.querySelectorAll("td.declared, td.geometry");
  return [row.dataset.row, declared.innerText, geometry.innerText,
          declared.classList.contains("differs"), geometry.classList.contains("differs")];
}))"""


def table(html, name: str) -> dict[str, list]:
    loaded = open_page(html, then=f"{ROWS}({json.dumps(name)})")
    assert loaded.errors == ""
    return {row[0]: row[1:] for row in loaded.result}


@pytest.fixture(scope="module")
def simple_arm(tmp_path_factory):
    html = tmp_path_factory.mktemp("arm") / "arm.html"
    result = CliRunner().invoke(main, ["view", str(SIMPLE_ARM), "-o", str(html)])
    assert result.exit_code == 0, result.output
    return html


def test_the_simple_arm_s_wrong_axes_show_in_ixx_and_izz(simple_arm):
    rows = table(simple_arm, "link_1")
    # the cylinder's tensor in its own axes (z along it) against the geometry's in the link's
    # (x along it): m(3r² + l²)/12 = 0.0076 across, mr²/2 = 0.0002 along
    assert rows["ixx"] == ["0.0076", "0.0002", True, True]
    assert rows["izz"] == ["0.0002", "0.0076", True, True]
    assert rows["iyy"] == ["0.0076", "0.0076", False, False]
    for product in ("ixy", "ixz", "iyz"):
        assert rows[product] == ["0", "0", False, False]  # the geometry's 1e-16 is rounding
    assert rows["mass (kg)"] == ["1", "1", False, False]
    assert rows["COM x (m)"] == ["0", "0.15", True, True]
    # the principal moments, each with the link axis it lies along
    declared, geometry = rows["principal"][:2]
    assert declared.splitlines()[0] == "0.0002 along z"
    assert geometry.splitlines()[0] == "0.0002 along x"


def test_the_base_whose_values_agree_has_no_highlighted_cell(simple_arm):
    rows = table(simple_arm, "base_link")
    assert rows["izz"][:2] == ["0.01", "0.01"]
    assert not any(row[2] or row[3] for row in rows.values()), rows


def test_a_com_off_by_half_a_metre_is_highlighted(page):
    rows = table(page, "arm")
    assert rows["COM x (m)"] == ["0.5", "0", True, True]
    assert not any(row[2] or row[3] for name, row in rows.items() if name != "COM x (m)")


# --- 3D: which box is whose ---------------------------------------------------------------


def test_hovering_a_box_names_its_link(page, loaded):
    box = boxes(loaded)["arm", "declared"]
    hovered = open_page(page, then=then(pointer(["pointermove"], box["x"], box["y"])))
    assert hovered.errors == ""
    assert hovered.result["hover"] == "arm: declared inertia"
    assert hovered.result["selection"] is None
    # off the robot (the corner left of the panel) the label goes
    away = then(
        pointer(["pointermove"], box["x"], box["y"]),
        "await new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)));",
        "if (document.getElementById('hover-label').hidden) throw new Error('no label');",
        pointer(["pointermove"], 600, 790),
    )
    assert open_page(page, then=away).result["hover"] is None


def test_hovering_a_card_names_its_link_in_3d(page):
    hover = "document.querySelector('.link[data-link=\"base\"]')"
    hover += ".dispatchEvent(new MouseEvent('mouseenter'));"
    assert open_page(page, then=then(hover)).result["hover"] == "base"


def test_clicking_a_box_selects_and_labels_its_link_and_dims_the_others(page, loaded):
    arm, base = boxes(loaded)["arm", "declared"], boxes(loaded)["base", "declared"]
    selected = open_page(page, then=then(pointer(["pointerdown", "pointerup"], arm["x"], arm["y"])))
    assert selected.errors == ""
    state = selected.result
    assert state["selected"] == ["arm"] and state["selection"] == "arm"
    assert state["isolate"] is False and state["status"] == "arm selected"
    # the label sits just above the arm's declared COM, which the camera did not move
    after = boxes(selected)["arm", "declared"]
    assert math.dist((after["x"], after["y"]), (arm["x"], arm["y"])) < 1
    assert math.dist(state["at"], (arm["x"], arm["y"] - 10)) < 3
    # its box keeps its colour; the base's dims to the background's grey
    image = pixels(selected)
    assert family_at(image, arm["x"], arm["y"]) == "orange"
    assert family_at(pixels(loaded), base["x"], base["y"]) in ("orange", "cyan")
    assert family_at(image, base["x"], base["y"]) == "other"


def test_a_click_on_nothing_or_escape_clears_the_selection(page):
    cleared = open_page(
        page, then=then(click_card("arm"), pointer(["pointerdown", "pointerup"], 600, 790))
    )
    assert cleared.result["selected"] == [] and cleared.result["selection"] is None
    escape = "window.dispatchEvent(new KeyboardEvent('keydown', {key: 'Escape'}));"
    assert open_page(page, then=then(click_card("arm"), escape)).result["selected"] == []


def test_isolate_shows_the_selected_link_alone_and_show_all_brings_the_others_back(page):
    before = open_page(page, then=then())
    assert before.result["isolate"] is True and before.result["showAll"] is True  # nothing to do
    isolated = open_page(
        page, then=then(click_card("base"), "document.getElementById('isolate').click();")
    )
    assert isolated.errors == ""
    state = isolated.result
    assert state["shown"] == [True, False] and state["hidden"] == ["arm"]
    assert state["showAll"] is False and state["status"] == "base selected · 1 of 2 links shown"
    projected = boxes(isolated)
    assert projected["base", "declared"]["shown"] and not projected["arm", "declared"]["shown"]
    # the arm's boxes are gone from the picture, the base's fill the view
    image = pixels(isolated)
    arm = projected["arm", "geometry"]
    if 0 <= arm["x"] < 920 and 0 <= arm["y"] < 800:
        assert family_at(image, arm["x"], arm["y"]) == "other"
    base = projected["base", "declared"]
    assert family_at(image, base["x"], base["y"]) in ("orange", "cyan")
    assert base["rect"][2] - base["rect"][0] > 300
    # and back: every link shown, the arm's box in its colour where it is now
    back = open_page(
        page,
        then=then(
            click_card("base"),
            "document.getElementById('isolate').click();",
            "document.getElementById('show-all').click();",
        ),
    )
    assert back.result["shown"] == [True, True] and back.result["hidden"] == []
    assert back.result["status"] == "base selected"
    arm = boxes(back)["arm", "geometry"]
    assert arm["shown"]
    if arm["visible"]:
        assert family_at(pixels(back), arm["x"], arm["y"]) in ("orange", "cyan")


def test_the_keys_isolate_and_show_all(page):
    key = "window.dispatchEvent(new KeyboardEvent('keydown', {{key: '{}'}}));".format
    isolated = open_page(page, then=then(click_card("arm"), key("i")))
    assert isolated.result["shown"] == [False, True]
    assert open_page(page, then=then(click_card("arm"), key("i"), key("a"))).result["shown"] == [
        True,
        True,
    ]


def test_a_link_hidden_alone_is_not_drawn_nor_picked(page, loaded):
    untick = "document.querySelector('.link[data-link=\"arm\"] input.shown').click();"
    arm = boxes(loaded)["arm", "declared"]
    hidden = open_page(
        page,
        then=then(untick, pointer(["pointermove", "pointerdown", "pointerup"], arm["x"], arm["y"])),
    )
    assert hidden.errors == ""
    state = hidden.result
    # ticking the box selects nothing; the arm under the pointer is not there to hover or pick
    assert state["shown"] == [True, False] and state["hidden"] == ["arm"]
    assert state["selected"] == [] and state["hover"] is None
    assert state["status"].endswith("1 of 2 links shown")
    assert family_at(pixels(hidden), arm["x"], arm["y"]) != "orange"
