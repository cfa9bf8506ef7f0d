"""
Principal axes of a declared tensor compared with its geometry's (issue 20, item 2).

A tensor whose products have the wrong sign, or that is written in turned axes, keeps its
principal moments and so passes every moment test; only its principal axes show the slip. But
an axis is only defined when its moment stands apart from the other two, and a real CAD part's
axes follow its geometry only when its moments are well apart: so each axis ``i`` is judged by
its *gap*, how far (in log) its moment is from the nearest other one, in both tensors,

    g_i = min(min_{j≠i} |ln λ_i − ln λ_j| over the declared moments, the same over the
              geometry's),

and the angle between the declared and the geometry's axis ``i`` (matched by moment order, sign
ignored) is a mismatch beyond :func:`angle_limit` of that gap.

The model: perturbing a tensor with principal gap ``Δλ`` by a relative error ``ε`` of its
largest moment turns its axes by ``½ arctan(2 ε λ / Δλ)`` (the exact rotation of a 2×2
symmetric matrix's eigenvectors), and ``Δλ / λ ≈ g`` for small gaps: the limit is
``½ arctan(SCATTER / g)``, degrees. :data:`SCATTER` and :data:`MIN_GAP` come from
``python benchmarks/cad_band.py`` over the links of the installed robot packages the linter is
silent on (see the constants).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

#: below this gap (moments within a factor of 2.2 of each other) an axis is not compared: over
#: the 2213 links of the installed robot packages the linter is silent on, axes with a gap of
#: 0.3-0.8 still lie up to 81-90° from the geometry's (99 %: 89° at 0.3-0.5, 50° at 0.5-0.8;
#: Talos `arm_*_2_link` 90° at 0.73 on both bases): a real part's moments scatter by a factor
#: of up to 2.5 about its geometry's, enough to exchange the order of moments that near
MIN_GAP = 0.8
#: the relative scatter of a real part's tensor the limit allows for: from a gap of 0.8 up, the
#: largest angle per bin of g is 22° (0.8-1), 24° (1-1.5), 15° (1.5-2), 10° (2-3), 2.6° (3+);
#: the scatter each link needs, ``g tan(2 angle)`` on its worst axis, its better basis, has
#: 99 % 1.07 and max 1.57 (xArm6 `link4`, 24° at g = 1.37): 2 leaves 27 % over the largest
#: (28° against its 24°)
SCATTER = 2.0


def angle_limit(gap: float) -> float:
    """
    The largest angle, degrees, between a real part's principal axis and its geometry's for an
    axis of log gap ``gap``: ``½ arctan(SCATTER / gap)``, 90 (anything goes) below
    :data:`MIN_GAP`.
    """
    if not gap >= MIN_GAP:
        return 90.0
    return math.degrees(0.5 * math.atan2(SCATTER, gap))


def gaps(moments: ArrayLike) -> NDArray[np.float64]:
    """
    ``g_i = min_{j≠i} |ln λ_i − ln λ_j|`` of three positive principal moments (any order).
    """
    logs = np.log(np.asarray(moments, dtype=np.float64))
    apart = np.abs(logs[:, None] - logs[None, :])
    np.fill_diagonal(apart, np.inf)
    return apart.min(axis=1)


@dataclass(frozen=True)
class AxisComparison:
    """
    One principal axis of a declared tensor against the geometry's with the same moment rank
    (0: the smallest moment).

    Attributes
    ----------
    rank : int
    gap : float
      The smaller of the two tensors' log gaps for this axis (:func:`gaps`).
    angle : float
      Degrees, 0–90: the angle between the two axes, sign ignored.
    declared, geometry : (3,) float
      The two unit axes, link frame.
    """

    rank: int
    gap: float
    angle: float
    declared: NDArray[np.float64]
    geometry: NDArray[np.float64]

    @property
    def limit(self) -> float:
        """:func:`angle_limit` of the gap."""
        return angle_limit(self.gap)

    @property
    def excess(self) -> float:
        """How far the angle is beyond its limit, degrees (negative: within it)."""
        return self.angle - self.limit


def compare_axes(declared: ArrayLike, geometry: ArrayLike) -> list[AxisComparison]:
    """
    The three principal axes of ``declared`` against those of ``geometry`` ((3, 3) kg·m², same
    axes), matched by moment order; empty when either tensor has a moment that is not positive
    and finite (no body has it: other rules say so).
    """
    tensors = [np.asarray(t, dtype=np.float64) for t in (declared, geometry)]
    if not all(t.shape == (3, 3) and np.isfinite(t).all() for t in tensors):
        return []
    (ld, ad), (lg, ag) = (np.linalg.eigh(0.5 * (t + t.T)) for t in tensors)
    if not (ld[0] > 0 and lg[0] > 0):
        return []
    gap = np.minimum(gaps(ld), gaps(lg))
    cosines = np.minimum(np.abs(np.einsum("ji,ji->i", ad, ag)), 1.0)
    angles = np.degrees(np.arccos(cosines))
    return [
        AxisComparison(i, float(gap[i]), float(angles[i]), ad[:, i], ag[:, i]) for i in range(3)
    ]


def axes_mismatch(declared: ArrayLike, geometry: ArrayLike) -> AxisComparison | None:
    """
    The principal axis of ``declared`` furthest beyond :func:`angle_limit` from the
    geometry's, among those well defined in both (gap at least :data:`MIN_GAP`); ``None`` when
    every such axis is within its limit.
    """
    beyond = [c for c in compare_axes(declared, geometry) if c.gap >= MIN_GAP and c.excess > 0]
    return max(beyond, key=lambda c: c.excess, default=None)
