"""A URDF ``<inertial>`` element as text, with deterministic numbers, ready to paste or insert."""

from __future__ import annotations

from inertia_kit.mass import MassProperties
from inertia_kit.text import xml_number

# significant digits written: CAD tools report about six; more only adds churn
DIGITS = 6


def inertial_values(properties: MassProperties, digits: int = DIGITS) -> dict[str, str]:
    """
    The attribute values of an ``<inertial>`` block for ``properties`` in link-frame axes
    (``rpy = 0``): ``xyz``, ``rpy``, ``mass`` and the six tensor entries, as text.
    """
    clean = properties.cleaned()
    tensor = clean.inertia

    def number(value: float) -> str:
        return xml_number(value, digits)

    values = {
        "xyz": " ".join(number(x) for x in clean.com),
        "rpy": "0 0 0",
        "mass": xml_number(properties.mass, digits),
    }
    for name, (i, j) in {
        "ixx": (0, 0),
        "ixy": (0, 1),
        "ixz": (0, 2),
        "iyy": (1, 1),
        "iyz": (1, 2),
        "izz": (2, 2),
    }.items():
        values[name] = number(tensor[i, j])
    return values


def inertial_block(
    properties: MassProperties,
    *,
    indent: str = "  ",
    level: int = 0,
    newline: str = "\n",
    digits: int = DIGITS,
) -> str:
    """
    The ``<inertial>`` element for ``properties`` (in link-frame axes), without a trailing newline.

    Parameters
    ----------
    indent : str
      One level of indentation, as the surrounding file uses it.
    level : int
      How many levels the ``<inertial>`` line itself is indented.
    """
    v = inertial_values(properties, digits)
    outer, inner = indent * level, indent * (level + 1)
    return newline.join(
        [
            f"{outer}<inertial>",
            f'{inner}<origin xyz="{v["xyz"]}" rpy="{v["rpy"]}"/>',
            f'{inner}<mass value="{v["mass"]}"/>',
            f'{inner}<inertia ixx="{v["ixx"]}" ixy="{v["ixy"]}" ixz="{v["ixz"]}" '
            f'iyy="{v["iyy"]}" iyz="{v["iyz"]}" izz="{v["izz"]}"/>',
            f"{outer}</inertial>",
        ]
    )
