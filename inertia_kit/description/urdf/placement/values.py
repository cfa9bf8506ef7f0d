"""
A link's ``<inertial>`` values as text, compared as written.

A value is rewritten only when its text would read differently: the declared value and the new
one are both written to :data:`~inertia_kit.description.writing.DIGITS` digits, in
the axes of the ``<inertial>``'s ``<origin rpy>``, and compared. ``ixx="0.0191441"`` read
back, written again, is ``0.0191441``: left alone, so a second run finds nothing to do.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING

import numpy as np

from inertia_kit.description.model import Inertial
from inertia_kit.physics.formatting import xml_number

if TYPE_CHECKING:
    from inertia_kit.physics.mass import MassProperties

#: The values of an ``<inertial>``, each written in one attribute.
NAMES = ("xyz", "rpy", "mass", *Inertial.TENSOR)
ZERO = (0.0, 0.0, 0.0)


def vector(value) -> tuple[float, float, float] | None:
    """A parsed ``xyz``/``rpy`` as three floats, ``None`` when it is not numeric."""
    if isinstance(value, tuple) and len(value) == 3 and all(isinstance(v, float) for v in value):
        return value
    return None


def new_texts(properties: MassProperties, rpy=ZERO) -> dict[str, str]:
    """The text of each value of ``properties`` (link frame) written with ``<origin rpy>``."""
    from inertia_kit.description.urdf.inertial_xml import inertial_values

    return inertial_values(properties, rpy=rpy)


def declared_texts(inertial: Inertial) -> dict[str, str | None]:
    """The text each declared value would be written as (``None``: not numeric)."""
    from inertia_kit.description.writing import DIGITS

    def number(value) -> str | None:
        return xml_number(value, DIGITS) if isinstance(value, float) else None

    texts: dict[str, str | None] = {}
    for name in ("xyz", "rpy"):
        parsed = vector(getattr(inertial.origin, name))
        texts[name] = None if parsed is None else " ".join(xml_number(v, DIGITS) for v in parsed)
    if texts["rpy"] is not None and not any(vector(inertial.origin.rpy) or ZERO):
        texts["rpy"] = "0 0 0"
    texts["mass"] = number(inertial.mass)
    for name in Inertial.TENSOR:
        texts[name] = number(getattr(inertial, name))
    return texts


def differing(
    inertial: Inertial, new: dict[str, str], exact: Mapping[str, float] | None = None
) -> list[str]:
    """
    The names of the values whose text would change. A product of inertia within rounding
    noise of zero (:data:`~inertia_kit.description.writing.PRODUCT_FLOOR` of the largest
    moment to be written) is the zero that would be written, whatever digits it has. With
    ``exact``, the new values before rounding: a declared value that is one of the two
    roundings of a new value lying on the midpoint between them (within float noise) is kept,
    whichever way this run's arithmetic rounds it (the run that wrote it computed the tie
    along another path, and rounded it the other way).
    """
    from inertia_kit.description.writing import PRODUCT_FLOOR

    old = declared_texts(inertial)
    # the moments to be written, not the declared ones: the next run compares against the
    # same numbers, so a product kept as noise now is kept as noise then
    largest = max(abs(float(new[n])) for n in ("ixx", "iyy", "izz"))
    changed = []
    for name in NAMES:
        if old[name] == new[name]:
            continue
        value = getattr(inertial, name, None)
        if exact is not None and name in exact and _rounds_to(value, exact[name]):
            continue
        if (
            name in ("ixy", "ixz", "iyz")
            and new[name] == "0"
            and isinstance(value, float)
            and abs(value) <= PRODUCT_FLOOR * largest
        ):
            continue
        changed.append(name)
    return changed


def _rounds_to(declared, exact: float) -> bool:
    """Whether ``declared`` is ``exact`` rounded to DIGITS digits, either way on a tie."""
    from inertia_kit.description.writing import DIGITS

    if not isinstance(declared, float) or not math.isfinite(exact) or exact == 0:
        return False
    unit = 10.0 ** (math.floor(math.log10(abs(exact))) - DIGITS + 1)
    return abs(declared - exact) <= 0.5 * unit * (1 + 1e-6)


def same_vector(text: str, values) -> bool:
    """Whether the written vector ``text`` reads as ``values`` once written to DIGITS."""
    from inertia_kit.description.writing import DIGITS

    parsed = vector(values)
    if parsed is None:
        return False
    return text == " ".join(xml_number(v, DIGITS) for v in np.asarray(parsed, dtype=float))
