"""
How far a tensor is from the geometry's, and how far is far enough to explain.

A hypothesis explains the numbers when its corrected tensor is within :data:`TOLERANCE` of the
geometry's about every axis, at least :data:`BETTER` times closer than the declared one, and
the declared one is off by :data:`MIN_MISMATCH` at least (nothing is diagnosed on a tensor that
already agrees). Among the fits within :data:`SLACK` of the best, the simplest wins: the exact
fit of a part made of the link's shapes (the textbook cases).

A real part is not the uniform solid of its shapes: a CAD link's declared moments agree with its
meshes' only within a factor of about 0.6–1.7, so no hypothesis lands within 2 % of them. A
hypothesis is then judged in log space (:class:`LogMetric`, the largest
``|ln((nᵀTn + f λ) / (nᵀGn + f λ))|`` over axes ``n``: moments and principal axes at once): its
corrected tensor must land within :data:`BAND` of the geometry's, where real links land, and
beat the declared tensor by :data:`MARGIN` at least, more than real parts scatter; and no
other hypothesis may come within :data:`AMBIGUITY` of it. That is a *likely* slip, reported
by its rule with an unsafe fix.

The numbers come from ``python benchmarks/cad_band.py``: over the 2260 links of the installed
PyPI robot packages (1997 with meshes) on which the linter is silent, the log distance of the
declared tensor from the geometry's has the quantiles 50 % 0.30, 90 % 0.61, 95 % 0.73,
99 % 1.14, max 1.38.
"""

from __future__ import annotations

import functools
import math
from typing import TypeVar

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
#: a real part's corrected tensor lands within this log distance of the geometry's (a factor
#: of 2.5: between the 95th and the 99th percentile of real links, 0.73 and 1.14)
BAND = 0.92
#: ... and is this much closer than the declared one (a factor of 2.2): on none of the 1608
#: real links within a factor of two of their geometry the linter is silent on does any
#: reading gain this much (1.1, a factor of 3, named 5 to 20 % fewer of the slips planted
#: on them)
MARGIN = 0.8
#: the gain each hypothesis needs where the axes do not speak, when the calibration allows less
#: than MARGIN: 0.1 above the most its reading gains on any of the 2220 links of the installed
#: robot packages the linter is silent on (``benchmarks/cad_band.py``, "gains": products
#: negated at most 0.50, Talos ``arm_left_2_link``; other axes 0.55, SO-100 ``shoulder``;
#: about the origin 0.77 and one pair exchanged 0.79 keep MARGIN)
RULE_MARGINS = {"IN061": 0.6, "IN062": 0.65}
#: a likely slip is only named when every other reading's fit is this much worse (a factor of
#: 1.22): two readings that fit a real part about as well do not tell which slip it was (0.1
#: named 5 % more turned tensors on real links, and misnamed some as transcriptions)
AMBIGUITY = 0.2
#: two corrected tensors this close (a factor of 1.22 along any axis, inside the scatter of a
#: real part) are the same reading of the declared values
DISTINCT = 0.2
#: below this, the entries of ``inverse @ difference @ inverse.T`` are finite (with room to spare)
_SAFE = 1e300
#: a candidate is skipped when its lower bound exceeds the tolerance by this fraction: far more
#: than the ~1e-13 by which the computed deviation may fall short of the bound
BOUND_MARGIN = 1e-6


def symmetric(tensor: ArrayLike) -> NDArray[np.float64]:
    """The symmetric part of a (..., 3, 3) tensor."""
    t = np.asarray(tensor, dtype=np.float64)
    return 0.5 * (t + t.swapaxes(-1, -2))


_Kind = TypeVar("_Kind", bound="_Made")


class _Made:
    @classmethod
    def of(cls: type[_Kind], reference: ArrayLike) -> _Kind:
        """The metric from ``reference``, made once for equal tensors: a link's diagnoses (exact,
        loose, likely) each judge against its geometry's tensor. Raises as the constructor does."""
        array = np.ascontiguousarray(reference, dtype=np.float64)
        return _made(cls, array.tobytes(), array.shape)


@functools.lru_cache(maxsize=64)
def _made(kind: type[_Kind], data: bytes, shape: tuple[int, ...]) -> _Kind:
    return kind(np.frombuffer(data, dtype=np.float64).reshape(shape))


class Metric(_Made):
    """:func:`deviation` from one reference tensor, vectorised over candidate tensors."""

    def __init__(self, reference: ArrayLike):
        self.reference = symmetric(reference)
        self.largest_moment = float(np.linalg.eigvalsh(self.reference).max())
        floor = FLOOR * self.largest_moment
        # the denominator's tensor: nᵀ R n + FLOOR λmax(R) = nᵀ (R + FLOOR λmax(R) E) n
        self.denominator = self.reference + floor * np.eye(3)
        self.inverse = np.linalg.inv(np.linalg.cholesky(self.denominator))

    def reach(self, tolerance: float) -> float:
        """
        The largest entry, in magnitude and in any axes, of a tensor within ``tolerance``: a
        search whose candidates keep the declared values' magnitudes or moments (a rotation,
        signs, values moved among the six attributes) is skipped when one is larger.

        Within it, ``-tol (R + f λ E) <= T - R <= tol (R + f λ E)`` (``λ`` the reference's
        largest moment, ``f`` :data:`FLOOR`), so every moment of ``T`` is at most
        ``(1 + tol (1 + f)) λ`` in magnitude, and no entry exceeds the largest moment; widened
        by :data:`BOUND_MARGIN`, far more than the computed deviation's rounding.
        """
        return (1.0 + tolerance * (1.0 + FLOOR)) * self.largest_moment * (1.0 + BOUND_MARGIN)

    def __call__(self, tensors: ArrayLike) -> NDArray[np.float64]:
        difference = symmetric(tensors) - self.reference
        scaled = self.inverse @ difference @ self.inverse.T
        # eigvalsh: symmetric input; the extreme eigenvalues are the extreme ratios over axes
        return np.abs(np.linalg.eigvalsh(scaled)).max(axis=-1)

    def lower_bound(self, tensors: ArrayLike) -> NDArray[np.float64]:
        """
        A cheap lower bound of each deviation: its ratio about the three link axes alone,
        ``max_i |T_ii - R_ii| / (R_ii + FLOOR λmax(R))`` (the deviation is the largest ratio over
        every axis). Searches use it to skip the eigenvalues of candidates that cannot fit.

        It bounds the deviation as computed, not only the exact one: the inverse factor is
        accurate to ~1e-15 relative (the denominator's condition number is at most
        (1 + FLOOR) / FLOOR = 21), so the computed deviation is at least the bound less ~1e-13
        of it. Where the deviation's own arithmetic could overflow (a value ~1e150 or beyond,
        where eigvalsh may fail), the bound is 0: nothing is skipped, nothing changes.

        Parameters
        ----------
        tensors : (n, 3, 3) float
          Candidate tensors, in the reference's axes, kg·m².

        Returns
        -------
        bound : (n,) float
          At most each :meth:`__call__` value, less ~1e-13 of it.
        """
        tensors = np.asarray(tensors, dtype=np.float64)
        # every entry of inverse @ difference @ inverse.T is at most 9 |inverse|² |difference|
        # (NaN entries fail the test too)
        largest = np.abs(tensors).max(initial=0.0) + np.abs(self.reference).max()
        if not largest * 9.0 * np.abs(self.inverse).max() ** 2 < _SAFE:
            return np.zeros(len(tensors))
        # the diagonal of symmetric(tensors) is the tensors' own: 0.5 (t + t) is t
        difference = np.diagonal(tensors, axis1=-2, axis2=-1) - np.diagonal(self.reference)
        return (np.abs(difference) / np.diagonal(self.denominator)).max(axis=-1)


class LogMetric(_Made):
    """
    The log distance of tensors from one reference: the largest
    ``|ln((nᵀTn + f λ) / (nᵀRn + f λ))|`` over unit axes ``n``, ``λ`` the reference's largest
    moment and ``f`` :data:`FLOOR` (the rounding of large entries does not count about a thin
    body's long axis). It is the largest absolute log of the generalised eigenvalues of the
    floored tensors: invariant under a common rotation, ``ln((k + f) / (1 + f))`` for a tensor
    ``k`` times the reference (along its largest moment's axis). ``inf`` for a tensor whose
    floored form is not positive definite (no body has it).
    """

    def __init__(self, reference: ArrayLike):
        self.reference = symmetric(reference)
        self.floor = FLOOR * float(np.linalg.eigvalsh(self.reference).max()) * np.eye(3)
        self.inverse = np.linalg.inv(np.linalg.cholesky(self.reference + self.floor))

    def __call__(self, tensor: ArrayLike) -> float:
        floored = symmetric(tensor) + self.floor
        if not np.isfinite(floored).all():
            return math.inf
        ratios = np.linalg.eigvalsh(self.inverse @ floored @ self.inverse.T)
        if not (ratios > 0).all():
            return math.inf
        return float(np.abs(np.log(ratios)).max())


def deviation(tensor: ArrayLike, reference: ArrayLike) -> float:
    """
    How far ``tensor`` is from ``reference`` (both (3, 3) kg·m², same axes): the largest
    ``|nᵀ (T - R) n| / (nᵀ R n + FLOOR λmax(R))`` over unit axes ``n``.

    0 when equal, 1 for a tensor twice the reference, ~1e6 for one in kg·mm². ``reference`` must
    be positive definite; ``tensor`` may be anything symmetric (a transposed one often is not
    positive definite).
    """
    return float(Metric.of(reference)(tensor))
