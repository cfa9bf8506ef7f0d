"""
How far a tensor is from the geometry's, and how far is far enough to explain.

A hypothesis explains the numbers when its corrected tensor is within :data:`TOLERANCE` of the
geometry's about every axis, at least :data:`BETTER` times closer than the declared one, and
the declared one is off by :data:`MIN_MISMATCH` at least (nothing is diagnosed on a tensor that
already agrees). Among the fits within :data:`SLACK` of the best, the simplest wins.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

#: a corrected tensor explains the numbers within this deviation (2 %): CAD values are rounded to
#: 3–4 significant digits, far below it
TOLERANCE = 0.02
#: ... and only when it is this many times closer to the geometry than the declared tensor
BETTER = 10.0
#: IN020's "most likely" note: within 10 % and 3 times closer than the declared tensor
LOOSE = 0.1
LOOSE_BETTER = 3.0
#: nothing is diagnosed when the declared tensor is within 10 % of the geometry's already
MIN_MISMATCH = 0.1
#: deviations are relative to each axis's moment plus this fraction of the largest one, so that
#: the rounding of large entries does not count as a mismatch about a thin body's long axis
FLOOR = 0.05
#: a candidate within this much of the best fit wins over it when it is a simpler explanation
SLACK = 0.005


def symmetric(tensor: ArrayLike) -> NDArray[np.float64]:
    """The symmetric part of a (..., 3, 3) tensor."""
    t = np.asarray(tensor, dtype=np.float64)
    return 0.5 * (t + t.swapaxes(-1, -2))


class Metric:
    """:func:`deviation` from one reference tensor, vectorised over candidate tensors."""

    def __init__(self, reference: ArrayLike):
        self.reference = symmetric(reference)
        floor = FLOOR * float(np.linalg.eigvalsh(self.reference).max())
        self.inverse = np.linalg.inv(np.linalg.cholesky(self.reference + floor * np.eye(3)))

    def __call__(self, tensors: ArrayLike) -> NDArray[np.float64]:
        difference = symmetric(tensors) - self.reference
        scaled = self.inverse @ difference @ self.inverse.T
        # eigvalsh: symmetric input; the extreme eigenvalues are the extreme ratios over axes
        return np.abs(np.linalg.eigvalsh(scaled)).max(axis=-1)


def deviation(tensor: ArrayLike, reference: ArrayLike) -> float:
    """
    How far ``tensor`` is from ``reference`` (both (3, 3) kg·m², same axes): the largest
    ``|nᵀ (T - R) n| / (nᵀ R n + FLOOR λmax(R))`` over unit axes ``n``.

    0 when equal, 1 for a tensor twice the reference, ~1e6 for one in kg·mm². ``reference`` must
    be positive definite; ``tensor`` may be anything symmetric (a transposed one often is not
    positive definite).
    """
    return float(Metric(reference)(tensor))
