"""
Which of two links is at fault when a rule finds that they disagree (twins that do not mirror,
a mass ratio, a copied block): the one whose declared values depart more from its own geometry.

A link's departure has two parts, judged apart because a slip moves one and not the other:

- the tensor's: the log distance (:class:`~inertia_kit.analysis.forensics.measure.LogMetric`)
  of the declared tensor from the geometry's at the declared mass and uniform density, about
  the centre of mass, in the link frame. It sees a slipped tensor (other axes, a unit, flipped
  products) and a slipped mass (the geometry's tensor scales with it, the declared one does
  not); real CAD links land within :data:`~inertia_kit.analysis.forensics.measure.BAND` of 0;
- the centre of mass's: its distance from the geometry's centroid over the geometry's size
  (its bounding box's largest extent). A motor at one end moves a real one a third of the
  way to that end.

One link is at fault when it departs more than the other by :data:`TENSOR_MARGIN` in tensor or
:data:`COM_MARGIN` in centre of mass, and is not the clearly closer one in the other part. Two
links that depart alike, or one without geometry to judge by, give no culprit: the rule then
keeps one finding for the pair, as it would without this module.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from inertia_kit.analysis.forensics.measure import AMBIGUITY, BAND, MARGIN, LogMetric
from inertia_kit.physics.formatting import fmt

if TYPE_CHECKING:
    from inertia_kit.analysis.links import LinkAnalysis

#: a link departs clearly more in tensor than another when its log distance is this much larger
#: (a factor of 1.22 about some axis: the scatter within which two readings fit a real part
#: alike, measure.AMBIGUITY)
TENSOR_MARGIN = AMBIGUITY
#: ... or in centre of mass when its offset from the centroid is larger by this fraction of the
#: link's size (twins' own tolerance, analysis.twins.COM_TOLERANCE)
COM_MARGIN = 0.05


@dataclass(frozen=True)
class Departure:
    """How far a link's declared values are from its geometry's (module doc)."""

    tensor: float  # log distance, 0 for the geometry's own tensor
    com: float  # centre of mass from the centroid, over the geometry's size

    def text(self) -> str:
        """How far, in words: ``tensor a factor of 1.52 from its geometry's, ...``."""
        factor = math.exp(self.tensor) if self.tensor < 700 else math.inf
        return (
            f"tensor a factor of {fmt(factor, 3)} from its geometry's, centre of mass "
            f"{fmt(100 * self.com, 2)} % of its size from the centroid"
        )


def departure(link: LinkAnalysis) -> Departure | None:
    """The link's :class:`Departure`, or ``None`` without declared values or geometry."""
    declared = link.declared
    if declared is None or not declared.mass > 0:
        return None
    try:
        expected = link.geometry.at_mass(declared.mass)
        corners = link.geometry.corners
    except (ValueError, FloatingPointError, np.linalg.LinAlgError):
        return None
    if expected is None or corners is None or not np.isfinite(corners).all():
        return None
    size = float((corners.max(axis=0) - corners.min(axis=0)).max())
    if not size > 0:
        return None
    with np.errstate(all="ignore"):
        try:
            tensor = LogMetric(expected.inertia)(declared.inertia)
        except (ValueError, np.linalg.LinAlgError):
            return None
        com = float(np.linalg.norm(declared.com - expected.com)) / size
    if math.isnan(tensor) or not math.isfinite(com):
        return None
    return Departure(tensor, com)


def worse(a: Departure, b: Departure) -> bool:
    """Whether ``a`` departs clearly more than ``b`` (module doc)."""
    tensor, com = a.tensor - b.tensor, a.com - b.com
    if tensor > TENSOR_MARGIN and com >= -COM_MARGIN:
        return True
    return com > COM_MARGIN and tensor >= -TENSOR_MARGIN


def at_fault(a: LinkAnalysis, b: LinkAnalysis) -> LinkAnalysis | None:
    """``a`` or ``b``, whichever departs clearly more from its geometry; ``None`` when unclear."""
    first, second = departure(a), departure(b)
    if first is None or second is None:
        return None
    if worse(first, second):
        return a
    if worse(second, first):
        return b
    return None


#: the plausible densities of a part, kg/m³ (IN022's defaults: foam to tungsten, with room)
DENSITY_RANGE = (50.0, 25000.0)


def density_excess(link: LinkAnalysis) -> float | None:
    """
    How far the link's declared mass over its geometry's volume is outside
    :data:`DENSITY_RANGE`, as a log: positive above it, negative below, 0 inside it (what a
    slipped mass, grams for kilograms, shows). The geometry (collision, visual) that gives the
    most plausible density decides, as in IN022; ``None`` without a positive mass or a volume.
    """
    declared = link.declared
    if declared is None or not declared.mass > 0:
        return None
    low, high = DENSITY_RANGE
    found = []
    for geometry in link.bases:
        density = declared.mass / geometry.volume
        if not (math.isfinite(density) and density > 0):
            continue
        found.append(max(0.0, math.log(density / high)) - max(0.0, math.log(low / density)))
    return min(found, key=abs) if found else None


def densest(links: tuple[LinkAnalysis, ...]) -> tuple[LinkAnalysis, float] | None:
    """The link of ``links`` whose density is furthest above the plausible range, and how far."""
    judged = [(link, density_excess(link)) for link in links]
    found = [(link, excess) for link, excess in judged if excess is not None and excess > 0]
    return max(found, key=lambda item: item[1]) if found else None


#: values this far from their geometry (log distance, a factor of 5.6: BAND + MARGIN, beyond
#: the 1.38 of the worst of 2260 real links the linter is silent on) are no real part's
IMPLAUSIBLE = BAND + MARGIN


def implausible(link: LinkAnalysis) -> bool:
    """
    Whether the link's values are no real part's: a tensor :data:`IMPLAUSIBLE` from its
    geometry's, or a density outside :data:`DENSITY_RANGE`. Links without geometry are not.
    """
    found = departure(link)
    if found is not None and found.tensor > IMPLAUSIBLE:
        return True
    return bool(density_excess(link))
