"""
The volume integrals of a solid (volume, first and second moment about a reference point) and
their algebra: moving the reference point, flipping the winding, scaling the solid, and turning
them into mass properties at uniform density. :mod:`.polyhedra` computes them for a triangle
surface; :mod:`.unions` adds and subtracts them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from inertia_kit.physics.mass import MassProperties, inertia_from_second_moment
from inertia_kit.physics.primitives import body_mass


@dataclass(frozen=True, eq=False)
class VolumeMoments:
    """
    Signed volume integrals of the solid bounded by a triangle surface, about ``origin``.

    A surface wound inside-out has a negative ``volume``; an open surface has moments that
    depend on ``origin`` and mean nothing.

    Attributes
    ----------
    volume : float
      ``∫ dV``, m³
    first : (3,) float
      ``∫ (x - origin) dV``, m⁴
    second : (3, 3) float
      ``∫ (x - origin)(x - origin)ᵀ dV``, m⁵
    origin : (3,) float
      The reference point, m. Integrating about a point near the surface keeps the central
      second moment free of cancellation for parts far from the coordinate origin.
    """

    volume: float
    first: NDArray[np.float64]
    second: NDArray[np.float64]
    origin: NDArray[np.float64]

    def __add__(self, other: VolumeMoments) -> VolumeMoments:
        if not np.array_equal(self.origin, other.origin):
            other = other.about(self.origin)
        return VolumeMoments(
            self.volume + other.volume,
            self.first + other.first,
            self.second + other.second,
            self.origin,
        )

    def about(self, origin: ArrayLike) -> VolumeMoments:
        """The same integrals about another reference point."""
        d = self.origin - np.asarray(origin, dtype=np.float64)
        first = self.first + self.volume * d
        second = (
            self.second
            + np.outer(self.first, d)
            + np.outer(d, self.first)
            + self.volume * np.outer(d, d)
        )
        return VolumeMoments(self.volume, first, second, np.asarray(origin, dtype=np.float64))

    def negated(self) -> VolumeMoments:
        """The integrals of the same surface wound the other way."""
        return VolumeMoments(-self.volume, -self.first, -self.second, self.origin)

    def scaled(self, scale: ArrayLike) -> VolumeMoments:
        """
        The integrals after scaling every vertex by ``diag(scale)`` about the coordinate origin.

        A negative scale mirrors the solid; its volume stays positive, as URDF means it.
        """
        s = np.asarray(scale, dtype=np.float64)
        if s.shape != (3,) or not np.all(np.isfinite(s)) or np.any(s == 0):
            raise ValueError(f"scale must be three finite non-zero factors, got {scale!r}")
        jacobian = abs(float(np.prod(s)))
        return VolumeMoments(
            jacobian * self.volume,
            jacobian * s * self.first,
            jacobian * np.outer(s, s) * self.second,
            s * self.origin,
        )

    @property
    def centroid(self) -> NDArray[np.float64]:
        """(3,) centroid of the solid, m."""
        return self.origin + self.first / self.volume

    def mass_properties(
        self, *, density: float | None = None, mass: float | None = None
    ) -> MassProperties:
        """
        Mass properties of the solid at uniform density (exactly one of ``density``, ``mass``).

        Raises ``ValueError`` unless the volume is positive: an inverted or empty surface has no
        honest mass properties, and the caller decides what to report.
        """
        if not self.volume > 0:
            raise ValueError(f"the surface bounds no positive volume ({self.volume} m³)")
        m = body_mass(self.volume, density, mass)
        offset = self.first / self.volume
        central = self.second - self.volume * np.outer(offset, offset)
        return MassProperties(
            m, self.origin + offset, inertia_from_second_moment(central * (m / self.volume))
        )
