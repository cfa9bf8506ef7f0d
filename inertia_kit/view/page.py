"""
One self-contained HTML file from a scene (:mod:`inertia_kit.view.scene`'s contract): three.js,
our page scripts and style, and the scene as JSON, all inline. A Content-Security-Policy that
allows inline scripts and styles and nothing else keeps the page from fetching anything, so it
reads the same offline, from a CI artifact or a pull request.
"""

from __future__ import annotations

import html
import json
import re
from functools import cache
from importlib.resources import files
from typing import Any

#: nothing can be fetched: no connect-src, no remote script, style, image, font or frame
CSP = (
    "default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; "
    "img-src data: blob:; base-uri 'none'; form-action 'none'"
)

# a script's content ends at the first "</script" whatever its case: an asset holding one would
# cut the page short (the scene JSON escapes every "<" instead)
_SCRIPT_END = re.compile(r"</script", re.IGNORECASE)

TEMPLATE = """\
<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta http-equiv="Content-Security-Policy" content="{csp}">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta name="generator" content="inertia-kit {version}">
<title>{title}</title>
<style>
{css}</style>
</head>
<body>
<pre id="page-errors" hidden></pre>
<script>
{capture}</script>
<script type="application/json" id="scene-data">{scene}</script>
<script>
{three}</script>
<script>
{panel}</script>
<script>
{app}</script>
</body>
</html>
"""


@cache
def _asset(name: str) -> str:
    text = files("inertia_kit.view").joinpath("assets", name).read_text(encoding="utf-8")
    if _SCRIPT_END.search(text):
        raise ValueError(f"view asset {name} holds '</script', which would end its script early")
    return text


def scene_json(scene: dict[str, Any]) -> str:
    """
    ``scene`` as JSON to put inside a ``<script>`` element: every ``<`` escaped as ``\\u003c``
    (``</script>`` or ``<!--`` in a link name or message cannot end it), NaN refused; C1
    controls, line separators, bidirectional controls and lone surrogates (a file name that is
    no UTF-8, which the page could not even be written in) as ``\\uXXXX`` escapes too.
    """
    from inertia_kit.printable import UNPRINTABLE_ABOVE_C0

    text = json.dumps(scene, separators=(",", ":"), ensure_ascii=False, allow_nan=False)
    text = text.replace("<", "\\u003c")
    return UNPRINTABLE_ABOVE_C0.sub(lambda match: f"\\u{ord(match.group()):04x}", text)


def render_page(scene: dict[str, Any], *, title: str | None = None) -> str:
    """The review page of ``scene`` as one HTML document (a string, to write as UTF-8)."""
    from inertia_kit.printable import printable
    from inertia_kit.version import __version__

    if title is None:
        title = f"{scene.get('robot') or 'robot'}: inertia review"
    return TEMPLATE.format(
        csp=CSP,
        version=html.escape(__version__),
        title=html.escape(printable(title)),
        css=_asset("page.css"),
        capture=_asset("capture.js"),
        scene=scene_json(scene),
        three=_asset("three.min.js"),
        panel=_asset("panel.js"),
        app=_asset("page.js"),
    )
