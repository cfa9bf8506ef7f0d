"""
A link's declared values, as the simulators will read them: its ``<inertial>`` as mass
properties in the link frame, and its mass alone.

Incomplete or non-numeric values give ``None`` here: other rules report them (IN002–IN004).
"""

from __future__ import annotations

import math

from inertia_kit.description import model
from inertia_kit.physics.mass import MassProperties


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
