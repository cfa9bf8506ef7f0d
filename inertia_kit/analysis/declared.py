"""
A link's declared values, as the simulators will read them: its ``<inertial>`` as mass
properties in the link frame, and each part on its own (the mass, the tensor as written, the
centre of mass), so that a rule judges the part it needs even when another part is missing or
not a number: one bad attribute hides no other finding.

Incomplete or non-numeric values give ``None`` here: other rules report them (IN002–IN004).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from inertia_kit.description import model
from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.tensor_names import DIAGONAL


def _finite(value: model.Number) -> float | None:
    return value if isinstance(value, float) else None


def declared_mass(link: model.Link) -> float | None:
    """The link's declared ``<mass value>`` when it is a finite positive number, else ``None``."""
    inertial = link.inertial
    mass = None if inertial is None else inertial.mass
    return mass if isinstance(mass, float) and math.isfinite(mass) and mass > 0 else None


def declared(link: model.Link) -> MassProperties | None:
    """
    The link's ``<inertial>`` as mass properties in the link frame, or ``None`` when it is
    absent or incomplete (a value missing or not a finite number).
    """
    inertial = link.inertial
    if inertial is None:
        return None
    mass = _finite(inertial.mass)
    tensor = [_finite(v) for v in inertial.tensor_values().values()]
    xyz, rpy = inertial.origin.xyz, inertial.origin.rpy
    if mass is None or None in tensor or not isinstance(xyz, tuple) or not isinstance(rpy, tuple):
        return None
    ixx, ixy, ixz, iyy, iyz, izz = tensor
    return MassProperties.from_urdf(mass, ixx, ixy, ixz, iyy, iyz, izz, xyz=xyz, rpy=rpy)  # type: ignore[arg-type]


def written_tensor(link: model.Link) -> NDArray[np.float64] | None:
    """
    (3, 3) the six ``<inertia>`` values, kg·m², in the axes they are written in, when all six
    are finite numbers, whatever the mass and the ``<origin>`` say: the axes change no
    principal moment, so the tensor can be judged on its own (IN010-IN012).
    """
    inertial = link.inertial
    if inertial is None:
        return None
    values = [_finite(v) for v in inertial.tensor_values().values()]
    if None in values:
        return None
    ixx, ixy, ixz, iyy, iyz, izz = values
    tensor = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]], dtype=np.float64)
    return tensor if np.isfinite(tensor).all() else None


def principal_moments(tensor: NDArray[np.float64]) -> NDArray[np.float64] | None:
    """(3,) ascending principal moments of a symmetric (3, 3) tensor, or ``None`` if not finite."""
    try:
        # eigvalsh: symmetric input, best precision; values near the float range overflow
        with np.errstate(all="ignore"):
            moments = np.linalg.eigvalsh(tensor)
    except (np.linalg.LinAlgError, ValueError):
        return None
    return moments if np.isfinite(moments).all() else None


def negative_diagonal(link: model.Link) -> list[tuple[str, float]]:
    """
    The diagonal values (``izz``, ...) written as negative numbers: each proves a principal
    moment negative (the smallest eigenvalue of a symmetric matrix is at most its smallest
    diagonal entry), whatever the other values are, even missing or not numbers.
    """
    inertial = link.inertial
    if inertial is None:
        return []
    values = inertial.tensor_values()
    return [(name, v) for name in DIAGONAL if isinstance(v := values[name], float) and v < 0]


def declared_com(link: model.Link) -> NDArray[np.float64] | None:
    """(3,) the ``<inertial><origin xyz>``, m, link frame, when numeric (judged alone: IN021)."""
    inertial = link.inertial
    if inertial is None or not isinstance(inertial.origin.xyz, tuple):
        return None
    com = np.array(inertial.origin.xyz, dtype=np.float64)
    return com if np.isfinite(com).all() else None
