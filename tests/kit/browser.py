"""
The review page in the real headless Chromium, for the browser tests: skipped, saying why,
where none is installed; and the colour family of a screenshot's pixels.
"""

from __future__ import annotations

import io
from pathlib import Path

import pytest

from inertia_kit.view.screenshot import Capture, capture, find_chromium

NO_BROWSER = (
    "no headless Chromium: apt-get install chromium (.ci/run does where it can) or set "
    "INERTIA_KIT_CHROMIUM"
)


def open_page(html: Path, width: int = 1280, height: int = 800, then: str | None = None) -> Capture:
    """
    Load ``html`` in headless Chromium with the network off (``then``: JavaScript to run once
    it is ready); skip the test without a Chromium.
    """
    if find_chromium() is None:
        pytest.skip(NO_BROWSER)
    return capture(html, width=width, height=height, then=then)


def boxes(loaded: Capture) -> dict[tuple[str, str], dict]:
    """The page's projected boxes by (link, "declared" | "geometry")."""
    return {(box["link"], box["kind"]): box for box in loaded.projected}


def pixels(capture_: Capture):
    """The screenshot as a Pillow RGB image."""
    from PIL import Image

    return Image.open(io.BytesIO(capture_.png)).convert("RGB")


def colour_family(rgb) -> str:
    """
    ``orange`` (red over green over blue: the declared box), ``cyan`` (green and blue over
    red: the geometry's box), else ``other`` (the grey background, grey visuals, red).
    """
    r, g, b = rgb[:3]
    if r > g + 25 and g > b + 25:
        return "orange"
    if g > r + 25 and b > r + 25:
        return "cyan"
    return "other"


def family_at(image, x: float, y: float, radius: int = 2) -> str:
    """The colour family of most pixels of the small square around (x, y)."""
    votes: dict[str, int] = {}
    for dx in range(-radius, radius + 1):
        for dy in range(-radius, radius + 1):
            family = colour_family(image.getpixel((round(x) + dx, round(y) + dy)))
            votes[family] = votes.get(family, 0) + 1
    return max(votes, key=votes.__getitem__)
