"""A URDF ``<inertial>`` element as text, with deterministic numbers, ready to paste or insert."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from inertia_kit.description.writing import DIGITS, PRODUCT_FLOOR
from inertia_kit.physics.formatting import xml_number
from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.numbers import unusable

TENSOR = {"ixx": (0, 0), "ixy": (0, 1), "ixz": (0, 2), "iyy": (1, 1), "iyz": (1, 2), "izz": (2, 2)}


def inertial_values(
    properties: MassProperties, digits: int = DIGITS, rpy: ArrayLike = (0.0, 0.0, 0.0)
) -> dict[str, str]:
    """
    The attribute values of an ``<inertial>`` block for ``properties`` (link frame, about the
    COM) whose ``<origin rpy>`` is ``rpy``: ``xyz``, ``rpy``, ``mass`` and the six tensor
    entries in those axes, as text.
    """
    from inertia_kit.physics.frames import rpy_matrix

    clean = properties.cleaned()
    rotation = rpy_matrix(rpy)
    tensor = rotation.T @ clean.inertia @ rotation
    floor = PRODUCT_FLOOR * np.abs(np.diag(tensor)).max()

    def number(value: float) -> str:
        return xml_number(value, digits)

    values = {
        "xyz": " ".join(number(x) for x in clean.com),
        "rpy": " ".join(number(a) for a in rpy) if np.any(rpy) else "0 0 0",
        "mass": xml_number(properties.mass, digits),
    }
    for name, (i, j) in TENSOR.items():
        small = i != j and abs(tensor[i, j]) <= floor
        values[name] = number(0.0 if small else tensor[i, j])
    return values


def exact_values(properties: MassProperties, rpy: ArrayLike = (0.0, 0.0, 0.0)) -> dict[str, float]:
    """
    The mass and the six tensor entries :func:`inertial_values` writes for ``properties`` with
    ``<origin rpy>`` = ``rpy``, before they are rounded to text.
    """
    from inertia_kit.physics.frames import rpy_matrix

    rotation = rpy_matrix(rpy)
    tensor = rotation.T @ properties.cleaned().inertia @ rotation
    values = {"mass": float(properties.mass)}
    for name, (i, j) in TENSOR.items():
        values[name] = float(tensor[i, j])
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


def unwritable(properties: MassProperties, rpy: ArrayLike = (0.0, 0.0, 0.0)) -> str | None:
    """
    Why the ``<inertial>`` of ``properties`` must not be written: a value not finite, or one
    the linter refuses (IN004: beyond ±1e50, subnormal, a mass or moment below 1e-50, as
    written to :data:`DIGITS` digits), or no positive mass; ``None`` when it can be.
    """
    finite = (
        np.isfinite(properties.mass)
        and np.isfinite(properties.com).all()
        and np.isfinite(properties.inertia).all()
    )
    if not finite:
        return "its mass properties are not finite numbers"
    for attribute, text in inertial_values(properties, rpy=rpy).items():
        for piece in text.split():
            why = unusable(float(piece), attribute in ("mass", "ixx", "iyy", "izz"))
            if why is not None:
                what = "centre of mass" if attribute == "xyz" else attribute
                return (
                    f"its {what} would be written as {piece} ({why}), a number the linter "
                    "refuses (IN004)"
                )
    if not properties.mass > 0:
        return f"its mass is {properties.mass} kg"
    return None
