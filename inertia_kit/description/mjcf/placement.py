"""
Where an MJCF body's mass properties are written: its ``<inertial>``, replaced whole by the
one for the new values (in the form its author chose: ``diaginertia`` with ``quat``, or
``fullinertia``), or, for a body MuJoCo infers from its geoms, a new ``<inertial>`` as the
body's first child. An element that makes several bodies (a ``<replicate>``, a model
``<attach>``\\ed twice) is written only when every body it makes gets the same values; a value
under ``inertiafromgeom="true"`` is not written (the compiler ignores it).
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Sequence

from inertia_kit.description import model
from inertia_kit.description.editing import Files, insert_first_child, location
from inertia_kit.description.edits import Edit
from inertia_kit.description.mjcf.writer import inertial_element
from inertia_kit.description.model import Source
from inertia_kit.description.placement import Placement, Target
from inertia_kit.description.xmlspan import children, indent_unit, line_indent


def place(targets: Sequence[Target], robot: model.Robot, files: Files) -> dict[str, Placement]:
    """The edits that write each target's values into the MJCF files (every body of
    ``robot`` is seen, to know which others an element makes too)."""
    inference = robot.inference
    if inference is not None and inference.from_geometry == "always":
        ignored = Placement(
            problem='the compiler\'s inertiafromgeom="true" ignores every <inertial>: set it '
            'to "auto" (or remove it) first'
        )
        return {target.name: ignored for target in targets}
    written = {t.name: _written(t) for t in targets}
    makers: dict[object, list[str]] = defaultdict(list)
    for link in robot.links:
        makers[files.key(_where(link))].append(link.name)
    placements = {}
    for target in targets:
        where = _where(target.link)
        others = [n for n in makers[files.key(where)] if n != target.name]
        differing = [n for n in others if written.get(n) != written[target.name]]
        if differing:
            tag = "<inertial>" if target.link.inertial is not None else "<body>"
            placements[target.name] = Placement(
                problem=f"its {tag} at {location(where)} makes {len(others) + 1} bodies "
                f"({', '.join(f'`{n}`' for n in [target.name, *others][:4])}), and "
                f"`{differing[0]}` would need other values: write each its own <inertial>"
            )
            continue
        placements[target.name] = _place(target, where, written[target.name], files)
    return placements


def _where(link: model.Link) -> Source:
    inertial = link.inertial
    return inertial.source if inertial is not None else link.source


def _written(target: Target) -> str:
    inertial = target.link.inertial
    form = (
        "fullinertia"
        if inertial is not None and inertial.tensor_form == "fullinertia"
        else "diaginertia"
    )
    return inertial_element(target.properties, form)


def _place(target: Target, where: Source, element: str, files: Files) -> Placement:
    """Replace the body's ``<inertial>`` by ``element``, or write it as its first child."""
    replace = target.link.inertial is not None
    found = files.span(where, "inertial" if replace else "body")
    if isinstance(found, str):
        return Placement(problem=found)
    source, span = found
    text = source.text
    if replace:
        if text[span.start : span.end] == element:
            return Placement()
        return Placement((Edit(source.path, span.start, span.end, element),))
    if span.empty:
        return Placement(problem=f"its <body> at {location(where)} is an empty element")
    inner = children(text, span)
    indent = (
        line_indent(text, inner[0].start)
        if inner
        else line_indent(text, span.start) + indent_unit(text)
    )
    return Placement((insert_first_child(source, span, indent + element),))
