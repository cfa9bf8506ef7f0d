"""
IN068: the mass was changed after the tensor was computed (or the tensor computed for another
mass): the declared tensor is the geometry's, a real part's shape and all, for a mass ``k``
times the declared one.

The geometry's tensor scales with the mass, so a tensor kept while the mass is changed (a part
re-weighed, a mass typed as 3.6 for 1.2) is ``k`` times the geometry's at the declared mass
about every axis alike. In the generalised eigenvalues ``r`` of the declared tensor against the
geometry's (``Dv = r Gv``; a tensor ``k`` times ``G`` has ``r = k, k, k``) that is a common
factor ``ln k = mean(ln r)`` far from 0 and a small departure from it,
``shape = max |ln r - ln k|``: the part's shape agrees with its geometry, its size does not.

A real part's tensor is never its uniform solid's exactly: hollow shells and dense motors move
its moments both ways (``benchmarks/cad_band.py``, ``scale`` and ``shape`` over the silent links
of the installed robot packages). The hypothesis is only named when the common factor is
beyond what any silent real link shows (:data:`SCALE`), the departure within what most show
(:data:`SHAPE`), every axis off the same way, and the factor no unit's (:data:`MOST`: a
factor of 30 or more is a unit, IN063, or a made-up value). Nothing is corrected:
which of the two numbers is right, the mass or the tensor, the values cannot say.

A real part's scatter hides a factor under 2.5 from its own geometry, but not from its twin: a
link whose six ``<inertia>`` values are another link's (a left/right twin, a repeated finger),
whose geometry is the same shape per kilogram, and whose mass is a factor beyond :data:`SCALE`
from that link's, holds a tensor computed for the other mass (:func:`mass_beside_copy`); the
link whose values depart more from its geometry (analysis.fault) is the one whose mass changed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from inertia_kit.analysis.copies import six_values
from inertia_kit.analysis.fault import departure, worse
from inertia_kit.analysis.forensics.measure import BAND, LogMetric, symmetric
from inertia_kit.physics.mass import MassProperties

if TYPE_CHECKING:
    from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis

#: the common factor must be beyond this log (a factor of 2.5, the forensics' BAND): over the
#: 2218 silent links of the installed robot packages (``benchmarks/cad_band.py``, best basis)
#: |mean ln r| has the quantiles 50 % 0.16, 95 % 0.52, 99 % 0.80, max 1.29
SCALE = 0.92
#: ... and the tensor's shape within this of the geometry's (the silent links' departure: 50 %
#: 0.18, 90 % 0.46, 99 % 0.71): a part off by one factor on every axis. Six silent links pass
#: both on their better basis (TIAGo Pro's four wheels and torso base, 1/3.6 and 1/2.6 of their
#: visual meshes; Centauro's torso_2, 1/2.6), fewer on both bases
SHAPE = 0.45
#: a factor this large either way is a unit (IN063) or a made-up value, not a retyped mass: a
#: mass typed ten times too large, scattered by a real part's factor of up to 2.5, stays below
MOST = math.log(30.0)


@dataclass(frozen=True)
class MassChange:
    """The declared tensor is the geometry's for :attr:`factor` times the declared mass."""

    factor: float  # k: the declared tensor is about k times the geometry's at the declared mass
    shape: float  # the largest departure of an axis's log ratio from ln k
    tensor_mass: float  # the mass the tensor fits, kg: k times the declared mass

    @property
    def scaled(self) -> float:
        """What the tensor must be multiplied by to fit the declared mass: 1 / k."""
        return 1.0 / self.factor


def mass_change(declared: MassProperties, expected: MassProperties) -> MassChange | None:
    """
    The mass change that explains ``declared`` against ``expected`` (the geometry's values at
    the declared mass), or ``None`` (module doc).
    """
    if not (declared.mass > 0 and np.isfinite(declared.inertia).all()):
        return None
    try:
        inverse = np.linalg.inv(np.linalg.cholesky(symmetric(expected.inertia)))
    except np.linalg.LinAlgError:
        return None  # no positive definite geometry to compare with
    ratios = np.linalg.eigvalsh(inverse @ symmetric(declared.inertia) @ inverse.T)
    if not (ratios > 0).all():
        return None  # no body has the declared tensor: IN010
    logs = np.log(ratios)
    scale = float(logs.mean())
    shape = float(np.abs(logs - scale).max())
    same_way = bool((np.sign(logs) == np.sign(scale)).all())
    if not (SCALE <= abs(scale) < MOST and shape <= SHAPE and same_way):
        return None
    factor = math.exp(scale)
    return MassChange(factor, shape, factor * declared.mass)


#: ... and at the other link's mass the tensor must fit the link's geometry this much better
#: (log distance; a factor of 1.65) than at its own: a mass ×3 on a part within the band gains
#: up to ln 3 = 1.1, a twin whose values fit better at the retyped mass gains nothing
RETYPED_GAIN = 0.5
#: two geometries are one shape per kilogram when their principal moments per kilogram are
#: within this factor of each other (IN013's default ``copy_factor``: a box of sides 1 : 1 : 1.7
#: already has moments 1 : 2)
SAME_SHAPE = 2.0


@dataclass(frozen=True)
class RetypedMass:
    """The link's six values are :attr:`other`'s, its mass :attr:`factor` times that link's."""

    other: LinkAnalysis
    factor: float


def _best_fits(robot: RobotAnalysis) -> dict[tuple[float, ...], list[tuple[float, LinkAnalysis]]]:
    """
    For each six values held by two links or more, the two links they fit best (tensor log
    distance from each one's geometry, :func:`~inertia_kit.analysis.fault.departure`): one
    pass over the links, so 5000 links sharing a placeholder cost 5000 departures, not 25 M.
    """
    groups: dict[tuple[float, ...], list[LinkAnalysis]] = {}
    for link in robot.links:
        values = six_values(link)
        if values is not None:
            groups.setdefault(values, []).append(link)
    found = {}
    for values, members in groups.items():
        if len(members) < 2:
            continue
        fits = [(d.tensor, m) for m in members if (d := departure(m)) is not None]
        found[values] = sorted(fits, key=lambda item: item[0])[:2]
    return found


def _unit_moments(link: LinkAnalysis) -> np.ndarray | None:
    try:
        unit = link.geometry.at_mass(1.0)
    except (ValueError, FloatingPointError, np.linalg.LinAlgError):
        return None
    if unit is None:
        return None
    moments = np.linalg.eigvalsh(symmetric(unit.inertia))
    return moments if moments[0] > 0 and np.isfinite(moments).all() else None


def mass_beside_copy(link: LinkAnalysis) -> RetypedMass | None:
    """The other link whose tensor this link's mass was changed beside, or ``None`` (module doc)."""
    robot = link.robot
    values = six_values(link)
    if robot is None or values is None:
        return None
    mine = _unit_moments(link)
    own = departure(link)
    best = robot.fact("best fits by six values", _best_fits).get(values, [])
    # the link the values fit best but this one: the part they were computed for (a part of
    # another shape there: a copied tensor, IN013's)
    others = [(fit, other) for fit, other in best if other is not link]
    if mine is None or own is None or not others:
        return None
    _, other = others[0]
    theirs, fit = _unit_moments(other), departure(other)
    if theirs is None or fit is None:
        return None
    if float(np.max(np.maximum(mine / theirs, theirs / mine))) > SAME_SHAPE:
        return None
    assert link.declared is not None and other.declared is not None
    factor = link.declared.mass / other.declared.mass
    if not (SCALE <= abs(math.log(factor)) < MOST) or not worse(own, fit):
        return None
    # the other's mass must explain the values: at it the link fits its geometry clearly
    # better than at its own (a part that fits better with the retyped mass, a real part's
    # scatter the other way, is no evidence: which twin changed is then unknown)
    expected = link.geometry.at_mass(other.declared.mass)
    if expected is None:
        return None
    try:
        at_theirs = LogMetric(expected.inertia)(link.declared.inertia)
    except (ValueError, np.linalg.LinAlgError):
        return None
    if not (at_theirs <= BAND and own.tensor - at_theirs >= RETYPED_GAIN):
        return None
    return RetypedMass(other, factor)
