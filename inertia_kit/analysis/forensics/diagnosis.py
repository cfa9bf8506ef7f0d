"""
The diagnosis of one declared value against one geometry-derived value: every hypothesis is
searched, and the simplest candidate that explains the numbers is chosen and worded.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from inertia_kit.analysis.expected import tensor_fields
from inertia_kit.analysis.forensics import (
    flipped_signs,
    other_axes,
    other_point,
    transposed,
    unit_slip,
)
from inertia_kit.analysis.forensics.candidate import Candidate, Case, Wording
from inertia_kit.analysis.forensics.measure import (
    BETTER,
    MIN_MISMATCH,
    SLACK,
    TOLERANCE,
    Metric,
)
from inertia_kit.physics.mass import MassProperties

if TYPE_CHECKING:
    from inertia_kit.analysis.bounds import Hull


@dataclass(frozen=True, eq=False)
class Diagnosis:
    """
    A known slip that explains a declared tensor: the chosen candidate (its type says which
    hypothesis: :class:`~inertia_kit.analysis.forensics.other_point.AboutPoint`, …) and its
    wording. A message is ``f"link `{name}`: {wording.summary}: {wording.detail}"``.
    """

    slip: Candidate
    wording: Wording
    plain_residual: float  # deviation of the declared tensor from the geometry's
    basis: str | None = None  # "collision" or "visual": the geometry it was diagnosed against

    @property
    def code(self) -> str:
        """The forensic rule of the hypothesis: ``IN060`` … ``IN064``."""
        return self.slip.CODE

    @property
    def corrected(self) -> MassProperties:
        """
        The declared values with the slip undone, link frame (tensor in link axes about the
        declared COM; the declared mass but for a mass in grams).
        """
        return self.slip.corrected

    @property
    def residual(self) -> float:
        """Deviation of :attr:`corrected` from the geometry's tensor."""
        return self.slip.residual

    def expected(self) -> dict[str, Any]:
        """The corrected values and the hypothesis, JSON-ready, for a finding's ``expected``."""
        clean = self.corrected.cleaned()
        return {
            "mass": clean.mass,
            "xyz": [float(v) for v in clean.com],
            **tensor_fields(clean.inertia),
            "hypothesis": self.wording.summary,
            **self.wording.data,
            "basis": self.basis,
            "residual": self.residual,
            "plain_residual": self.plain_residual,
        }


def _choose(candidates: list[Candidate], tolerance: float) -> Candidate | None:
    """The simplest candidate among those that fit nearly as well as the best one."""
    fits = [c for c in candidates if c.residual <= tolerance]
    if not fits:
        return None
    best = min(c.residual for c in fits)
    near = [c for c in fits if c.residual <= best + SLACK]
    return min(near, key=lambda c: c.preference)


def diagnose(
    declared: MassProperties,
    expected: MassProperties,
    *,
    points: Sequence[tuple[str, ArrayLike]] = (),
    rotations: Sequence[tuple[str, ArrayLike]] = (),
    axes: ArrayLike | None = None,
    hull: Hull | None = None,
    volume: float | None = None,
    geometry: str = "geometry",
    tolerance: float = TOLERANCE,
    better: float = BETTER,
) -> Diagnosis | None:
    """
    The slip that explains ``declared`` against ``expected``, or ``None``.

    Parameters
    ----------
    declared : MassProperties
      The declared values, link frame (tensor in link axes, about the declared COM).
    expected : MassProperties
      The geometry's values for the declared mass, link frame, about the geometry's COM.
    points : sequence of (str, (3,) float)
      Named reference points in the link frame, m (``("the link origin", (0, 0, 0))``): IN060
      prefers them to a point solved for.
    rotations : sequence of (str, (3, 3) float)
      Named frames whose axes the tensor may have been written in (columns: their axes in link
      coordinates), e.g. a shape's ``<origin rpy>``: IN062 prefers them.
    axes : (3, 3) float, optional
      The rotation of ``<inertial><origin rpy>``: the axes the six values are written in (IN061
      and IN064 work on the written values). Default: the link axes.
    hull : Hull, optional
      A convex set containing the geometry: a point is only solved for when no distribution
      inside it has the declared tensor. Without one, only named points are tried.
    volume : float, optional
      The geometry's volume, m³: unit slips are judged by the density it gives.
    geometry : str
      How messages name the geometry (``collision cylinder (r = 0.05 m, l = 0.3 m)``).
    tolerance, better : float
      A hypothesis explains the numbers when the corrected tensor deviates from the geometry's
      by at most ``tolerance`` and ``better`` times less than the declared one.
    """
    if not (declared.mass > 0 and math.isfinite(declared.mass)):
        return None
    if not (np.isfinite(declared.inertia).all() and np.isfinite(declared.com).all()):
        return None
    try:
        metric = Metric(expected.inertia)
    except np.linalg.LinAlgError:
        return None  # the geometry's tensor is not positive definite: nothing to compare with
    plain = float(metric(declared.inertia))
    if plain < MIN_MISMATCH:
        return None
    frame = np.eye(3) if axes is None else np.asarray(axes, dtype=np.float64)
    case = Case(declared, expected, frame, metric, geometry)
    # in this order: among equally simple fits, the first found wins. The searches that make
    # many candidates drop those above the tolerance, which _choose would drop
    candidates: list[Candidate] = [
        *unit_slip.search(case, volume, tolerance),
        *flipped_signs.search(case),
        *other_point.search(case, points, hull),
        *other_axes.search(case, rotations, tolerance),
        *transposed.search(case, tolerance),
    ]
    chosen = _choose(candidates, tolerance)
    if chosen is None or chosen.residual * better > plain:
        return None
    return Diagnosis(chosen, chosen.word(case), plain)
