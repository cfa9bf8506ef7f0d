"""Numbers as people and files read them: one deterministic format everywhere."""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import Any

from inertia_kit.physics.tensor_names import DIAGONAL, INDEX, PRODUCTS

#: A product of inertia below this fraction of the largest moment is not shown in messages and
#: reports: it is rounding noise (an rpy of 1.5708 for π/2 leaves products ~1e-6 of the moments).
NEGLIGIBLE_PRODUCT = 1e-6


def fmt(value: float, digits: int = 5) -> str:
    """
    A number with ``digits`` significant digits for messages: ``6.929``, ``157.63``, ``1.2e-07``.

    ``-0`` prints as ``0`` so that a sign never appears on a value that rounds to nothing.
    """
    value = float(value)
    if not math.isfinite(value):
        return str(value)
    text = f"{value:.{digits}g}"
    return "0" if text in ("-0", "0") else text


def as_printed(value: float, digits: int = 5) -> float:
    """
    ``value`` as :func:`fmt` prints it, read back. A rule that prints a value and the bound it
    broke compares the two as printed, so that no message says "50 kg/m³, below the plausible
    50 kg/m³" (1 kg in a 0.1 × 0.1 × 2 m box is 49.99999999999999 kg/m³ in floats).
    """
    return float(fmt(value, digits))


def xml_number(value: float, digits: int = 9) -> str:
    """
    A number for an XML attribute: ``digits`` significant digits, positional notation for
    ordinary magnitudes, the exponent form only below 1e-4 or from 1e9 up.

    Deterministic (the same float always gives the same text) so that re-running a fill
    changes no byte.
    """
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"cannot write {value} into a URDF attribute")
    if value == 0:
        return "0"
    magnitude = abs(value)
    if 1e-4 <= magnitude < 1e9:
        decimals = max(digits - 1 - math.floor(math.log10(magnitude)), 0)
        text = f"{value:.{decimals}f}"
        if "." in text:
            text = text.rstrip("0").rstrip(".")
        return "0" if text in ("-0", "0") else text
    mantissa, exponent = f"{value:.{digits - 1}e}".split("e")
    if "." in mantissa:
        mantissa = mantissa.rstrip("0").rstrip(".")
    return f"{mantissa}e{int(exponent)}"


def vector_text(values: Iterable[float], digits: int = 4) -> str:
    """``(0.1, -2, 3.5e-05)``: a point or direction for messages."""
    return "(" + ", ".join(fmt(value, digits) for value in values) + ")"


def tensor_text(
    tensor: Any,
    names: Sequence[str] | None = None,
    digits: int = 4,
    separator: str = " = ",
) -> str:
    """
    ``ixx = 0.0163, iyy = 0.0163, izz = 0.0025``: the named entries of a 3×3 tensor, else the
    three moments and every product that is not negligible (:data:`NEGLIGIBLE_PRODUCT`).
    ``separator`` goes between a name and its value.
    """
    if names is None:
        scale = max(abs(float(tensor[i][i])) for i in range(3))
        shown = [
            n
            for n in PRODUCTS
            if abs(float(tensor[INDEX[n][0]][INDEX[n][1]])) > NEGLIGIBLE_PRODUCT * scale
        ]
        names = (*DIAGONAL, *shown)
    return ", ".join(
        f"{name}{separator}{fmt(tensor[INDEX[name][0]][INDEX[name][1]], digits)}" for name in names
    )
