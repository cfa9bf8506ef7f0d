"""How far a centre of mass lies from a geometry's centroid: a fraction of the way to its edge."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from inertia_kit.analysis.declared import declared_com
from inertia_kit.analysis.geometry import Geometry

if TYPE_CHECKING:
    from inertia_kit.analysis.links import LinkAnalysis

_AXES = np.concatenate((np.eye(3), -np.eye(3)))


def judged_com(link: LinkAnalysis, min_mass_share: float) -> np.ndarray | None:
    """
    The declared centre of mass the COM rules (IN021, IN067) judge, or ``None``: judged on its
    own (the tensor or the mass may be missing or not a number: IN003, IN004), but not for a
    mass <= 0, which has none (IN002), nor for a negligible part of a welded body, whose centre
    of mass moves the lumped one by nothing.
    """
    inertial = link.link.inertial
    com = declared_com(link.link)
    if inertial is None or com is None:
        return None
    if isinstance(inertial.mass, float) and not inertial.mass > 0:
        return None
    if link.mass_share < min_mass_share:
        return None
    return com


def offset_fraction(geometry: Geometry, com: ArrayLike) -> float:
    """
    How far ``com`` lies from the geometry's centroid, as a fraction of the way to the edge of
    the geometry's hull in that direction (and along each link axis); above 1 it is outside.
    The geometry must have a ``unit`` and a ``hull``.
    """
    assert geometry.unit is not None and geometry.hull is not None
    centroid = geometry.unit.com
    offset = np.asarray(com, dtype=np.float64) - centroid
    length = float(np.linalg.norm(offset))
    if length == 0.0:
        return 0.0
    directions = np.vstack((offset / length, _AXES))
    along = directions @ offset
    reach = geometry.hull.half_widths(centroid, directions)
    with np.errstate(divide="ignore", invalid="ignore"):
        fractions = np.where(along > 0, along / reach, 0.0)
    return float(np.nanmax(fractions))


def least_fraction(bases: Sequence[Geometry], com: ArrayLike) -> float:
    """
    :func:`offset_fraction` against the nearest of ``bases`` (a centre of mass near the
    centroid of either the collision or the visual geometry is fine); ``inf`` without one.
    """
    usable = [g for g in bases if g.unit is not None and g.hull is not None]
    return min((offset_fraction(g, com) for g in usable), default=float("inf"))
