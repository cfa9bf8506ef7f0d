"""
Mass and moments of solid bodies from the textbook closed forms, written out here so that no
expected value comes from the code under test. Moments are about the body's centre, in its own
axes; a cylinder's axis is z.
"""

from __future__ import annotations

import math

import numpy as np


def box_moments(mass, size) -> tuple[float, float, float]:
    """(ixx, iyy, izz) of a solid box of ``size`` (x, y, z): m(b² + c²)/12 and so on."""
    x, y, z = size
    return mass * (y * y + z * z) / 12, mass * (x * x + z * z) / 12, mass * (x * x + y * y) / 12


def cylinder_moments(mass, radius, length) -> tuple[float, float, float]:
    """(ixx, iyy, izz) of a solid cylinder along z: m(3r² + l²)/12 across, mr²/2 along."""
    across = mass * (3 * radius**2 + length**2) / 12
    return across, across, mass * radius**2 / 2


def sphere_moments(mass, radius) -> tuple[float, float, float]:
    """(ixx, iyy, izz) of a solid ball: 2mr²/5 about every axis."""
    moment = 0.4 * mass * radius**2
    return moment, moment, moment


def solid_box(size, *, density=None, mass=None) -> tuple[float, float, float, float]:
    """(mass, ixx, iyy, izz) of a solid box, its mass given or from ``density``."""
    x, y, z = size
    m = mass if mass is not None else density * x * y * z
    return (m, *box_moments(m, size))


def solid_cylinder(radius, length, *, density=None, mass=None) -> tuple[float, float, float, float]:
    """(mass, ixx, iyy, izz) of a solid cylinder along z, its mass given or from ``density``."""
    m = mass if mass is not None else density * math.pi * radius**2 * length
    return (m, *cylinder_moments(m, radius, length))


def solid_sphere(radius, *, density=None, mass=None) -> tuple[float, float, float, float]:
    """(mass, ixx, iyy, izz) of a solid ball, its mass given or from ``density``."""
    m = mass if mass is not None else density * 4 / 3 * math.pi * radius**3
    return (m, *sphere_moments(m, radius))


def box_tensor(mass, size, rotation=None) -> np.ndarray:
    """The box's 3×3 tensor about its centre; turned by ``rotation`` (R I Rᵀ) when given."""
    tensor = np.diag(box_moments(mass, size))
    return tensor if rotation is None else rotation @ tensor @ np.transpose(rotation)
