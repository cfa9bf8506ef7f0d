"""render_page: one self-contained offline HTML file; the scene inside it round-trips."""

from __future__ import annotations

import json
import math
import re
from html.parser import HTMLParser
from pathlib import Path

import pytest
from kit.scenes import two_box_scene

from inertia_kit.view import page
from inertia_kit.view.page import render_page

ASSETS = Path(page.__file__).parent / "assets"
REPO = Path(page.__file__).parent.parent.parent


class _Elements(HTMLParser):
    """Every start tag with its attributes, and each script's text by its id."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.tags: list[tuple[str, dict]] = []
        self.scripts: dict[str | None, str] = {}
        self._script: str | None = None

    def handle_starttag(self, tag, attrs):
        self.tags.append((tag, dict(attrs)))
        if tag == "script":
            self._script = dict(attrs).get("id") or f"#{len(self.scripts)}"
            self.scripts[self._script] = ""

    def handle_endtag(self, tag):
        if tag == "script":
            self._script = None

    def handle_data(self, data):
        if self._script is not None:
            self.scripts[self._script] += data


def parse(text: str) -> _Elements:
    parser = _Elements()
    parser.feed(text)
    parser.close()
    return parser


def test_nothing_is_fetched_and_the_csp_forbids_it():
    text = render_page(two_box_scene())
    elements = parse(text)
    for tag, attributes in elements.tags:
        assert not {"src", "href", "srcset", "action", "data"} & set(attributes), (tag, attributes)
    csp = [
        a["content"] for t, a in elements.tags if a.get("http-equiv") == "Content-Security-Policy"
    ]
    assert len(csp) == 1
    directives = dict(d.strip().split(" ", 1) for d in csp[0].split(";"))
    assert directives["default-src"] == "'none'"  # connect-src, font-src, ... fall back to it
    assert directives["script-src"] == "'unsafe-inline'"
    assert "connect-src" not in directives
    # the only address in the page is the XHTML namespace three.js creates elements in
    assert set(re.findall(r"https?://[^\s\"'`)]+", text)) == {"http://www.w3.org/1999/xhtml"}


def test_the_scene_round_trips_even_with_script_ends_in_its_strings():
    scene = two_box_scene()
    assert "</script>" in scene["links"][1]["findings"][0]["message"]
    elements = parse(render_page(scene))
    assert json.loads(elements.scripts["scene-data"]) == scene
    # the five scripts (error capture, scene, three.js, the panel, the app), none cut short
    assert len(elements.scripts) == 5
    assert "OrbitControls" in elements.scripts["#2"]


def test_the_title_is_escaped_and_defaults_to_the_robot():
    assert "<title>two_boxes: inertia review</title>" in render_page(two_box_scene())
    assert "<title>a &lt;b&gt; &amp; c</title>" in render_page(two_box_scene(), title="a <b> & c")
    scene = two_box_scene()
    scene["robot"] = "evil\u202e\n"  # a bidirectional override and a line break, as escapes
    assert "<title>evil\\u202e\\n: inertia review</title>" in render_page(scene)


def test_a_scene_with_nan_is_refused():
    scene = two_box_scene()
    scene["links"][0]["implied_density"] = math.nan
    with pytest.raises(ValueError):
        render_page(scene)


def test_three_is_the_pinned_version_with_its_licence():
    header = (ASSETS / "three.min.js").read_text(encoding="utf-8")[:400]
    script = (REPO / "scripts" / "vendor_three.py").read_text(encoding="utf-8")
    pinned = re.search(r'THREE_VERSION = "([\d.]+)"', script)[1]
    assert f"three.js {pinned} (MIT" in header
    licence = (ASSETS / "three.LICENSE").read_text(encoding="utf-8")
    assert "MIT" in licence and "three.js authors" in licence
