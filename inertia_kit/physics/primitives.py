"""
Closed-form mass properties of URDF primitives, centred on their own frame as URDF places them.

Each function takes the shape's dimensions in metres and exactly one of ``density`` (kg/m³) or
``mass`` (kg), and returns :class:`~.mass.MassProperties` with the COM at the origin
and the tensor in the shape's axes. Cylinders and capsules run along z, as in URDF.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.numbers import MIN_NORMAL, usable


def _dimension(value: float, name: str) -> float:
    value = float(value)
    if not (usable(value) and value > 0):
        raise ValueError(
            f"{name} must be a positive length in m, at most 1e50 and not subnormal, got {value}"
        )
    return value


def _extents(values: ArrayLike, name: str) -> tuple[float, float, float]:
    array = np.asarray(values, dtype=np.float64)
    if array.shape != (3,):
        raise ValueError(f"{name} must be (3,), got shape {array.shape}")
    x, y, z = (_dimension(v, f"{name}[{i}]") for i, v in enumerate(array))
    return x, y, z


def body_mass(volume: float, density: float | None, mass: float | None) -> float:
    """
    The mass of a solid of ``volume`` m³ from exactly one of ``density`` or ``mass``, each
    from 1e-50 to 1e50 (:mod:`.numbers`).
    """
    if (density is None) == (mass is None):
        raise ValueError("give exactly one of density (kg/m³) or mass (kg)")
    for name, unit, given in (("density", "kg/m³", density), ("mass", "kg", mass)):
        if given is not None and not (usable(float(given), scale=True) and given > 0):
            raise ValueError(
                f"{name} must be positive, from 1e-50 to 1e50 {unit}, got {given} {unit}"
            )
    if not (math.isfinite(volume) and volume >= MIN_NORMAL):
        # each dimension is usable: only their product left double precision
        how = "overflows to infinity" if volume > 1 else "underflows to zero"
        raise ValueError(
            f"the volume {how}: the dimensions are beyond what double precision can multiply"
        )
    value = float(mass) if mass is not None else float(density) * volume  # type: ignore[arg-type]
    if not value >= MIN_NORMAL:  # at most 1e50 × 1e150: only an underflow is possible
        raise ValueError(f"the mass, density {density} kg/m³ × {volume:g} m³, underflows to zero")
    return value


def cylinder_volume(radius: float, length: float) -> float:
    return math.pi * _dimension(radius, "radius") ** 2 * _dimension(length, "length")


def sphere_volume(radius: float) -> float:
    return 4.0 / 3.0 * math.pi * _dimension(radius, "radius") ** 3


def box(
    size: ArrayLike, *, density: float | None = None, mass: float | None = None
) -> MassProperties:
    """
    Solid box centred on its frame.

    Parameters
    ----------
    size : (3,) float
      Full edge lengths along x, y, z, m (URDF ``<box size>``).
    """
    x, y, z = _extents(size, "size")
    m = body_mass(x * y * z, density, mass)
    return MassProperties(
        m, np.zeros(3), np.diag([y * y + z * z, x * x + z * z, x * x + y * y]) * m / 12
    )


def cylinder(
    radius: float, length: float, *, density: float | None = None, mass: float | None = None
) -> MassProperties:
    """
    Solid cylinder along z, centred on its frame: ``ixx = iyy = m(3r² + l²)/12``, ``izz = m r²/2``.
    """
    r, h = _dimension(radius, "radius"), _dimension(length, "length")
    m = body_mass(math.pi * r * r * h, density, mass)
    side = m * (3 * r * r + h * h) / 12
    return MassProperties(m, np.zeros(3), np.diag([side, side, m * r * r / 2]))


def sphere(
    radius: float, *, density: float | None = None, mass: float | None = None
) -> MassProperties:
    """Solid sphere: ``I = 2/5 m r²`` about every axis."""
    r = _dimension(radius, "radius")
    m = body_mass(sphere_volume(r), density, mass)
    return MassProperties(m, np.zeros(3), np.eye(3) * (0.4 * m * r * r))


def capsule(
    radius: float, length: float, *, density: float | None = None, mass: float | None = None
) -> MassProperties:
    """
    Solid capsule along z: a cylinder of ``length`` (between the hemisphere centres, as URDF and
    SDFormat define it) capped by two hemispheres of ``radius``.
    """
    r, h = _dimension(radius, "radius"), _dimension(length, "length")
    v_cylinder, v_cap = math.pi * r * r * h, 2.0 / 3.0 * math.pi * r**3
    m = body_mass(v_cylinder + 2 * v_cap, density, mass)
    m_cylinder = m * v_cylinder / (v_cylinder + 2 * v_cap)
    m_cap = m * v_cap / (v_cylinder + 2 * v_cap)
    axial = m_cylinder * r * r / 2 + 2 * (0.4 * m_cap * r * r)
    # each cap: 83/320 m r² about its own COM (3r/8 from the flat face), moved h/2 + 3r/8 out
    side = m_cylinder * (3 * r * r + h * h) / 12 + 2 * m_cap * (
        0.4 * r * r + h * h / 4 + 3 * h * r / 8
    )
    return MassProperties(m, np.zeros(3), np.diag([side, side, axial]))


def ellipsoid(
    radii: ArrayLike, *, density: float | None = None, mass: float | None = None
) -> MassProperties:
    """Solid ellipsoid with semi-axes ``radii`` (a, b, c) along x, y, z: ``ixx = m(b² + c²)/5``."""
    a, b, c = _extents(radii, "radii")
    m = body_mass(4.0 / 3.0 * math.pi * a * b * c, density, mass)
    return MassProperties(
        m, np.zeros(3), np.diag([b * b + c * c, a * a + c * c, a * a + b * b]) * m / 5
    )
