"""
Densities of common materials, for ``inertia-fill --material``.

One table for the fill and for ``--help``, which shows it: this module imports only ``re``, so
the help costs no import of the physics.
"""

from __future__ import annotations

import re

#: kg/m³, typical values for solid parts; 3D-printed parts are lighter at partial infill, so
#: pass ``--mass`` when the real mass is known
MATERIALS: dict[str, float] = {
    "steel": 7850.0,
    "stainless-steel": 8000.0,
    "aluminium": 2700.0,
    "abs": 1040.0,
    "pla": 1240.0,
    "petg": 1270.0,
    "nylon": 1150.0,
    "carbon-fibre": 1600.0,
    "water": 1000.0,
    "wood": 700.0,
}


#: other spellings of the names above, after :func:`canonical_material`'s folding of case,
#: spaces and underscores (US spellings, and the words people leave out)
ALIASES: dict[str, str] = {
    "aluminum": "aluminium",
    "alu": "aluminium",
    "stainless": "stainless-steel",
    "carbon-fiber": "carbon-fibre",
    "carbon": "carbon-fibre",
}


def canonical_material(name: str) -> str | None:
    """
    The table's name for ``name`` in any case, with spaces, underscores or hyphens between
    words and US or British spelling (``Aluminum``, ``stainless_steel``, ``carbon fiber``),
    or ``None`` when it names no material of the table.
    """
    folded = "-".join(re.split(r"[\s_\-]+", name.strip().lower()))
    folded = ALIASES.get(folded, folded)
    return folded if folded in MATERIALS else None


def materials_text() -> str:
    """``steel 7850, aluminium 2700, ... wood 700 kg/m³``: the table in one line."""
    return ", ".join(f"{name} {density:g}" for name, density in MATERIALS.items()) + " kg/m³"
