"""
The diagnosis of one declared value against one geometry-derived value: every hypothesis is
searched, and the simplest candidate that explains the numbers is chosen and worded.
"""

from __future__ import annotations

import dataclasses
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
from inertia_kit.analysis.forensics.flipped_signs import FlippedSigns
from inertia_kit.analysis.forensics.measure import (
    AMBIGUITY,
    BAND,
    BETTER,
    DISTINCT,
    MARGIN,
    MIN_MISMATCH,
    RULE_MARGINS,
    SLACK,
    TOLERANCE,
    LogMetric,
    Metric,
)
from inertia_kit.analysis.forensics.other_axes import OtherAxes
from inertia_kit.analysis.forensics.transposed import Transposed
from inertia_kit.analysis.principal_axes import axes_mismatch
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.mass import MassProperties

if TYPE_CHECKING:
    from inertia_kit.analysis.bounds import Hull


@dataclass(frozen=True, eq=False)
class Diagnosis:
    """
    A known slip that explains a declared tensor: the chosen candidate (its type says which
    hypothesis: :class:`~inertia_kit.analysis.forensics.other_point.AboutPoint`, …) and its
    wording. A finding's message is ``f"link `{name}`: {wording.claim}"`` (or its brief), its
    detail ``f"{wording.summary}: {wording.detail}"`` (:func:`.links.explain`).
    """

    slip: Candidate
    wording: Wording
    plain_residual: float  # deviation of the declared tensor from the geometry's
    basis: str | None = None  # "collision" or "visual": the geometry it was diagnosed against
    #: the fit of a real part (:func:`diagnose_part`): the log distances from the geometry's
    #: tensor of the declared one and of the corrected one; ``None``: an exact fit
    likely: tuple[float, float] | None = None

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
            "fit": "exact" if self.likely is None else "likely",
            **(
                {}
                if self.likely is None
                else {"log_distance": self.likely[1], "plain_log_distance": self.likely[0]}
            ),
        }


def _choose(candidates: list[Candidate], tolerance: float) -> Candidate | None:
    """The simplest candidate among those that fit nearly as well as the best one."""
    fits = [c for c in candidates if c.residual <= tolerance]
    if not fits:
        return None
    best = min(c.residual for c in fits)
    near = [c for c in fits if c.residual <= best + SLACK]
    return min(near, key=lambda c: c.preference)


def _finite(declared: MassProperties) -> bool:
    """A positive finite mass, a finite tensor and COM: values a slip can be undone on."""
    return bool(
        declared.mass > 0
        and math.isfinite(declared.mass)
        and np.isfinite(declared.inertia).all()
        and np.isfinite(declared.com).all()
    )


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
    if not _finite(declared):
        return None
    try:
        metric = Metric.of(expected.inertia)
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


#: hypotheses whose candidate is fitted to the geometry rather than read from the file: a
#: real part always fits them about as well as its scatter allows, so they prove nothing there
_FITTED_RANKS = frozenset({7})  # the declared moments laid along the geometry's principal axes


#: the least log-distance gain a reading that turns mismatched principal axes back needs
#: (a factor of 1.5): the axes, not the moments, carry its evidence. Centauro's ``arm2_2`` with
#: its products negated: 1.17 from its collision mesh, 0.64 with them restored (0.53 gained,
#: under MARGIN), its least-inertia axis 47° off where a real part's strays 23° at most
AXES_GAIN = MARGIN / 2
#: the readings that turn a tensor's axes without changing its moments
_TURNING = (FlippedSigns, OtherAxes, Transposed)


def _gain_needed(
    best: Candidate, corrected: np.ndarray, geometry: np.ndarray, turned: bool
) -> float:
    """
    How much closer to the geometry (log distance) ``best``'s corrected tensor must come than
    the declared one: :data:`~.measure.MARGIN` (or the hypothesis's
    :data:`~.measure.RULE_MARGINS`), or :data:`AXES_GAIN` for a reading that turns the
    principal axes, when the declared axes are beyond a real part's from the geometry's and the
    corrected ones are not (issue 20, item 2).
    """
    if turned and isinstance(best, _TURNING) and axes_mismatch(corrected, geometry) is None:
        return AXES_GAIN
    return RULE_MARGINS.get(best.CODE, MARGIN)


def _part_candidates(
    case: Case,
    points: Sequence[tuple[str, ArrayLike]],
    rotations: Sequence[tuple[str, ArrayLike]],
    volume: float | None,
) -> list[Candidate]:
    """The readings :func:`diagnose_part` tries on a real part (its doc)."""
    # every candidate whose moments could land in the band: |ratio - 1| <= e^BAND - 1
    loose = math.expm1(BAND)
    # the slips people make, not every reading the numbers allow: a tensor in the units CAD
    # tools report (kg·mm², g·cm², g·mm²: a factor of a million or more, far beyond any
    # scatter) or a mass in grams; one pair of values exchanged. The other units, and
    # conversions the wrong way round, are only named when they fit exactly: on a real part a
    # made-up value lands within its scatter of 1e3 or 1e4 by chance too often
    return [
        *(
            c
            for c in unit_slip.search(case, volume, loose, unit_slip.PART_DENSITIES)
            if c.factor >= 1e6 or (c.factor == 1.0 and c.mass_factor > 1.0)
        ),
        *flipped_signs.search(case),
        *other_point.search(case, points, None),
        *(c for c in other_axes.search(case, rotations, loose) if c.rank not in _FITTED_RANKS),
        *(c for c in transposed.search(case, loose) if c.moved <= 2),
    ]


def _part_case(
    declared: MassProperties, expected: MassProperties, axes: ArrayLike | None, geometry: str
) -> tuple[Case, LogMetric] | None:
    """The case of a real part and its log metric; ``None`` when nothing can be judged."""
    if not _finite(declared):
        return None
    try:
        metric = Metric.of(expected.inertia)
        logs = LogMetric.of(expected.inertia)
    except np.linalg.LinAlgError:
        return None
    frame = np.eye(3) if axes is None else np.asarray(axes, dtype=np.float64)
    return Case(declared, expected, frame, metric, geometry), logs


def _per_kg(candidate: Candidate, declared: MassProperties) -> np.ndarray:
    """
    The corrected tensor at the declared mass: each reading is judged against the geometry at
    its corrected mass, and the geometry's tensor scales with the mass, so a mass in grams is
    judged by the tensor per corrected kilogram (LogMetric is scale-covariant: T against k G is
    T / k against G).
    """
    return candidate.corrected.inertia * (declared.mass / candidate.corrected.mass)


def part_gains(
    declared: MassProperties,
    expected: MassProperties,
    *,
    points: Sequence[tuple[str, ArrayLike]] = (),
    rotations: Sequence[tuple[str, ArrayLike]] = (),
    axes: ArrayLike | None = None,
    volume: float | None = None,
) -> dict[str, float]:
    """
    For each forensic rule (``IN060`` …), how much closer to the geometry (log distance) its
    best reading of :func:`diagnose_part` brings the declared tensor, among readings that land
    within :data:`~.measure.BAND`: on links that are right, what a coincidence gains
    (``benchmarks/cad_band.py`` calibrates the margins on it). Empty when nothing is read.
    """
    found_case = _part_case(declared, expected, axes, "geometry")
    if found_case is None:
        return {}
    case, logs = found_case
    plain = logs(declared.inertia)
    found: dict[str, float] = {}
    for candidate in _part_candidates(case, points, rotations, volume):
        fitted = logs(_per_kg(candidate, declared))
        if fitted <= BAND:
            code = candidate.CODE
            found[code] = max(found.get(code, -math.inf), plain - fitted)
    return found


def diagnose_part(
    declared: MassProperties,
    expected: MassProperties,
    *,
    points: Sequence[tuple[str, ArrayLike]] = (),
    rotations: Sequence[tuple[str, ArrayLike]] = (),
    axes: ArrayLike | None = None,
    volume: float | None = None,
    geometry: str = "geometry",
) -> Diagnosis | None:
    """
    The slip that most likely explains ``declared`` on a real part, or ``None``: judged in log
    space (:class:`~.measure.LogMetric`), the corrected tensor within :data:`~.measure.BAND`
    of the geometry's, at least :data:`~.measure.MARGIN` closer than the declared one, and no
    other hypothesis within :data:`~.measure.AMBIGUITY` of it (see :mod:`.measure`). Only named
    points, named frames and axis permutations, signs, units and transcriptions are tried:
    what is read from the file, not fitted to the geometry. Parameters as :func:`diagnose`.
    """
    found_case = _part_case(declared, expected, axes, geometry)
    if found_case is None:
        return None
    case, logs = found_case
    metric = case.metric
    plain_log = logs(declared.inertia)
    # principal axes turned beyond a real part's (analysis.principal_axes, IN069's test): a
    # reading that turns them back needs a smaller gain than MARGIN (below)
    turned = axes_mismatch(declared.inertia, expected.inertia) is not None
    if not plain_log >= (AXES_GAIN if turned else min(MARGIN, *RULE_MARGINS.values())):
        return None  # real-part scatter could put it there: nothing to explain
    candidates = _part_candidates(case, points, rotations, volume)

    def per_kg(c: Candidate) -> np.ndarray:
        return _per_kg(c, declared)

    scored = sorted(
        ((logs(per_kg(c)), i, c) for i, c in enumerate(candidates)),
        key=lambda item: item[:2],
    )
    if not scored:
        return None
    # the readings: candidates whose corrected tensors lie within DISTINCT of each other say
    # the same thing (a product sign flipped and a half turn about an axis, the axes of a rod
    # turned about it, iyy and izz exchanged or turned); the simplest of those near the best
    # fit speaks for it
    best_log, _, first = scored[0]
    if not best_log <= BAND:
        return None
    try:
        reading = LogMetric(per_kg(first))
    except np.linalg.LinAlgError:
        return None  # no body has the best reading (floored, it is not positive definite)
    near = [c for log, _, c in scored if log < best_log + AMBIGUITY]
    best = min((c for c in near if reading(per_kg(c)) <= DISTINCT), key=lambda c: c.preference)
    fitted = logs(per_kg(best))
    needed = _gain_needed(best, per_kg(best), expected.inertia, turned)
    if not (fitted <= BAND and plain_log - fitted >= needed):
        return None
    # another slip's reading nearly as good: which slip it was is not known. (Readings of the
    # same slip that differ, a rod's axes turned one way or another about its long axis, name
    # the slip all the same; the fix, unsafe, writes the best.)
    if any(type(c) is not type(best) and reading(per_kg(c)) > DISTINCT for c in near):
        return None
    wording = best.word(case)
    # how close a real part comes is a factor, not a percentage of the exact fit
    closeness = f"within a factor of {fmt(math.exp(fitted), 2)}"
    wording = dataclasses.replace(wording, detail=wording.detail.replace(best.within, closeness))
    diagnosis = Diagnosis(best, wording, float(metric(declared.inertia)))
    return dataclasses.replace(diagnosis, likely=(plain_log, fitted))
