"""
The numbers mass properties can be computed from, and why others cannot (rules/IN004, IN026).

Mass properties multiply and divide up to six input numbers: a box's moment at a density is
``ρ·x·y·z·(y² + z²)``, a lumped body's ``m·d²`` is squared again by a tolerance, a declared
tensor is compared in the metric of another (``L⁻¹ A L⁻ᵀ``). So that none of these overflows
or vanishes in double precision (1.8e308 to 2.2e-308):

- every mass, moment, length and position is at most :data:`MAX_MAGNITUDE` = 1e50 in
  magnitude: six of them multiply to at most 1e300;
- a mass, a principal moment (``ixx``, ``iyy``, ``izz``) or a density, which set the scale
  other values are divided by, is zero or at least :data:`MIN_SCALE` = 1e-50: six of them
  divide into at most 1e300 too. Positions and products of inertia only add to other values:
  a tiny one is as good as zero, and CAD exports write 1e-17 to 1e-66 for a zero;
- no number is subnormal (non-zero, below 2.2e-308): it has already lost digits.

None of these is ever meant: the largest robot is about 1e2 m and 1e6 kg, the smallest moving
part 1e-9 kg with moments of 1e-12 kg·m².

A solid's dimension is at least :data:`MIN_LENGTH` = 1e-10 m, an ångström, the size of an
atom: nothing thinner is a solid, and a volume made from it would give a link a mass no
simulator can integrate (a cylinder 1e-320 m long: 3e-319 kg). Point-like contact spheres of
real robots are 1e-7 m.
"""

from __future__ import annotations

import math
import sys

#: the largest magnitude of a number mass properties are computed from (kg, m, kg·m²): six of
#: them multiply to at most 1e300, below the largest double
MAX_MAGNITUDE = 1e50

#: the smallest non-zero magnitude of a mass, principal moment or density (values others are
#: divided by): six of them divide into at most 1e300
MIN_SCALE = 1e-50

#: the smallest positive normal double (2.2e-308); a non-zero number below it is subnormal
MIN_NORMAL = sys.float_info.min

#: the thinnest dimension of a solid, m: an ångström, the size of an atom
MIN_LENGTH = 1e-10


def unusable(value: float, scale: bool = False) -> str | None:
    """
    Why ``value`` cannot be computed with (a few words), or ``None`` when it can: not finite,
    beyond ±:data:`MAX_MAGNITUDE`, subnormal, or for a ``scale`` (a mass, principal moment or
    density) non-zero below :data:`MIN_SCALE`.
    """
    if math.isnan(value):
        return "not a number"
    if math.isinf(value):
        return "infinite"
    magnitude = abs(value)
    if magnitude > MAX_MAGNITUDE:
        return "beyond ±1e50"
    if 0 < magnitude < MIN_NORMAL:
        return "subnormal: non-zero below 2.2e-308"
    if scale and 0 < magnitude < MIN_SCALE:
        return "non-zero below 1e-50"
    return None


def usable(value: float, scale: bool = False) -> bool:
    """Whether ``value`` can be computed with (:func:`unusable` gives no reason)."""
    return unusable(value, scale) is None


def one_digit(value: float) -> bool:
    """A value with one significant digit (1, 0.001, 5e-4): how placeholders are written."""
    if not value > 0:
        return False
    mantissa = value / 10.0 ** math.floor(math.log10(value))
    return abs(mantissa - round(mantissa)) <= 1e-9 * mantissa
