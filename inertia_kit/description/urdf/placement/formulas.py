"""
A tensor entry written as the formula it comes from: for a link of one cylinder, sphere or box
whose dimensions and mass are written as numbers or whole ``${...}`` expressions, the entry is
written in terms of them (``${wheel_mass * (3 * wheel_radius**2 + wheel_width**2) / 12}``), so
that the link stays parametric: change ``wheel_radius`` and the inertia follows.

Only when the shape's axes, seen from the ``<inertial>``'s, are the same axes reordered (an
``rpy`` of quarter turns, as written: ``1.5708`` too), so that each entry is one principal
moment and the products are zero; and only when the formula, evaluated with the values read,
gives the number that would be written.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

import numpy as np

from inertia_kit.description import model
from inertia_kit.description.writing import DIGITS
from inertia_kit.physics.formatting import xml_number

if TYPE_CHECKING:
    from lxml import etree

    from inertia_kit.description.editing import Files
    from inertia_kit.description.placement import Target
    from inertia_kit.description.urdf.placement.attributes import Decision

_WHOLE = re.compile(r"^\$\{([^{}]*)\}$")
_NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")
_AXES = {"ixx": 0, "iyy": 1, "izz": 2}
# a quarter turn written as 1.5708 leaves entries of 1e-5 off the axes: still the same axes
_TURN_TOLERANCE = 1e-4


def term(text: str | None) -> str | None:
    """A written number or whole ``${expression}`` as a term of a formula, else ``None``."""
    if text is None:
        return None
    text = text.strip()
    if _NUMBER.match(text):
        return text
    found = _WHOLE.match(text)
    if found is None or not found.group(1).strip():
        return None
    inner = found.group(1).strip()
    return inner if re.fullmatch(r"[A-Za-z_]\w*", inner) else f"({inner})"


def _principal(geometry, element: etree._Element) -> list[tuple[str, float]] | None:
    """The principal moments per unit mass in the shape's own axes: (formula, value) each,
    the formula with ``{m}`` for the mass term; ``None`` for another shape or a size not
    written term by term."""
    if isinstance(geometry, model.Cylinder):
        r, h = term(element.get("radius")), term(element.get("length"))
        if r is None or h is None or not isinstance(geometry.radius, float):
            return None
        if not isinstance(geometry.length, float):
            return None
        radius, length = geometry.radius, geometry.length
        side = (f"{{m}} * (3 * {r}**2 + {h}**2) / 12", (3 * radius**2 + length**2) / 12)
        return [side, side, (f"{{m}} * {r}**2 / 2", geometry.radius**2 / 2)]
    if isinstance(geometry, model.Sphere):
        r = term(element.get("radius"))
        if r is None or not isinstance(geometry.radius, float):
            return None
        moment = (f"2 * {{m}} * {r}**2 / 5", 2 * geometry.radius**2 / 5)
        return [moment, moment, moment]
    if isinstance(geometry, model.Box):
        pieces = (element.get("size") or "").split()
        terms = [term(p) for p in pieces]
        size = geometry.size
        if len(terms) != 3 or None in terms or not all(isinstance(s, float) for s in size):
            return None
        x, y, z = terms
        sx, sy, sz = size
        return [
            (f"{{m}} * ({y}**2 + {z}**2) / 12", (sy**2 + sz**2) / 12),
            (f"{{m}} * ({x}**2 + {z}**2) / 12", (sx**2 + sz**2) / 12),
            (f"{{m}} * ({x}**2 + {y}**2) / 12", (sx**2 + sy**2) / 12),
        ]
    return None


def formula(
    name: str, target: Target, decision: Decision, mass_text: str | None, files: Files
) -> tuple[str, etree._Element] | None:
    """
    ``${...}`` giving the tensor entry ``name`` in the decision's axes from the shape's written
    dimensions and ``mass_text`` (the mass as written where the formula goes), and the shape's
    geometry element (its terms read in that element's scope); ``None`` when it cannot.
    """
    from inertia_kit.physics.frames import rpy_matrix

    if name not in _AXES:
        return None  # products: zero on reordered axes, written as 0
    shapes = target.shapes
    m = term(mass_text)
    if len(shapes) != 1 or m is None:
        return None
    shape = shapes[0]
    turned = shape.origin.rpy if isinstance(shape.origin.rpy, tuple) else None
    if turned is None or not all(isinstance(a, float) for a in turned):
        return None
    element = files.element(shape.geometry.source)
    if element is None:
        return None
    principal = _principal(shape.geometry, element)
    if principal is None:
        return None
    # the shape's axes in the <inertial>'s: which shape axis lies along each inertial axis
    relative = rpy_matrix(decision.rpy).T @ rpy_matrix(turned)
    along = np.abs(relative)
    if not np.all((along > 1 - _TURN_TOLERANCE) | (along < _TURN_TOLERANCE)):
        return None
    axis = int(np.argmax(along[_AXES[name]]))
    text, per_mass = principal[axis]
    written = text.format(m=m)
    if not re.search(r"[A-Za-z_]\w*", re.sub(r"\d[eE][-+]?\d", "", written)):
        return None  # numbers only: the number itself says as much
    value = target.properties.mass * per_mass
    if xml_number(value, DIGITS) != decision.texts[name]:
        return None  # the mass or the shape is not what the formula would read
    return "${" + written + "}", element
