"""
``inertia-kit view`` end to end on the seed examples, in headless Chromium: the mrm arm's CAD
tensors (about each link's origin) put its declared boxes away from its geometry's, and its
findings are in the panel; the pan-tilt's inertials match its geometry: the boxes coincide.
Skipped until inertia_kit.view.scene (the scene builder) is installed.
"""

from __future__ import annotations

import json
import re

from click.testing import CliRunner
from kit import EXAMPLES
from kit.browser import open_page

from inertia_kit.cli import main

MRM = EXAMPLES / "mrm_description/urdf/mrm.xacro"
PAN_TILT = EXAMPLES / "pan_tilt_description/urdf/pan_tilt.urdf"


def review(robot, tmp_path):
    """The page of ``robot`` through the command, its scene, and the page loaded in Chromium."""
    out = tmp_path / "review.html"
    result = CliRunner().invoke(main, ["view", str(robot), "-o", str(out)])
    assert result.exit_code == 0, result.output
    text = out.read_text(encoding="utf-8")
    found = re.search(r'<script type="application/json" id="scene-data">(.*?)</script>', text, re.S)
    return json.loads(found[1]), open_page(out)


def pairs(loaded) -> dict[str, dict[str, dict]]:
    """Each link's projected boxes, for the links that have both."""
    out: dict[str, dict[str, dict]] = {}
    for box in loaded.projected:
        out.setdefault(box["link"], {})[box["kind"]] = box
    return {link: kinds for link, kinds in out.items() if len(kinds) == 2}


def apart(kinds: dict[str, dict]) -> float:
    """How far the two boxes' rectangles on the screen are apart: the largest corner distance."""
    declared, geometry = kinds["declared"]["rect"], kinds["geometry"]["rect"]
    return max(abs(a - b) for a, b in zip(declared, geometry, strict=True))


def test_mrm_boxes_differ_and_its_findings_are_in_the_panel(tmp_path):
    scene, loaded = review(MRM, tmp_path)
    assert loaded.errors == ""
    # its tensors about the link origins make declared boxes larger than the geometry's
    assert [link for link, kinds in pairs(loaded).items() if apart(kinds) > 10], pairs(loaded)
    codes = {f["code"] for link in scene["links"] for f in link["findings"]}
    assert codes
    for code in codes:
        assert code in loaded.panel
    # what to do, as inertia-lint's help line says it, next to each finding that has one
    helps = [f["help"] for link in scene["links"] for f in link["findings"] if f.get("help")]
    assert helps
    for text in helps:
        assert "help: " + text[:60] in loaded.panel
    for link in scene["links"]:
        assert link["name"] in loaded.panel


def test_pan_tilt_boxes_coincide(tmp_path):
    _, loaded = review(PAN_TILT, tmp_path)
    assert loaded.errors == ""
    assert pairs(loaded)
    for link, kinds in pairs(loaded).items():
        assert apart(kinds) < 2, (link, kinds)
