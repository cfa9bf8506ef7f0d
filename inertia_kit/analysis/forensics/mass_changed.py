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
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from inertia_kit.analysis.forensics.measure import symmetric
from inertia_kit.physics.mass import MassProperties

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
