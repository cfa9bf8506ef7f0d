"""Numbers as people and files read them: one deterministic format everywhere."""

from __future__ import annotations

import math


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
