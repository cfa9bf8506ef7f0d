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

Of two links of the same part (mirrored twins, one shape at two masses: :func:`worse`), one is
at fault when it departs more than the other by :data:`TENSOR_MARGIN` in tensor or
:data:`COM_MARGIN` in centre of mass, and is not closer in the other part by half that part's
margin: their values scatter alike about their geometry (the same CAD part, the same simplified
collision shape), so what differs is the slip's. Evidence that points both ways names neither:
GR3's left upper arm yaw link, given its neighbour's block, departs 0.18 more in tensor than its
twin and 11 % of its size less in centre of mass (a block from another part need not move both
away from the geometry). With the whole margin allowed, the planted-slip benchmark blamed that
untouched twin (2 cases); with half, detection and naming were unchanged (96.95 %, 90.10 %).

Of two different parts (a block copied from one onto the other: :func:`worse_part`), the one at
fault must also depart there more than a real part does (a tensor beyond
:data:`~inertia_kit.analysis.forensics.measure.BAND`, a centre of mass beyond
:data:`PLAUSIBLE_COM`), unless the other's values are exactly its geometry's. Real parts' values
scatter about their geometry's by up to those bounds, each part its own way, so a link whose
values fit as a real part's do is not the culprit beside another part: UR3e's cylinder-formula
tensors fit ``base_link_inertia`` at a factor of 1.82 and ``shoulder_link`` at 2.13, which tells
nothing about which of the two a shared block was made for. Beside values computed from their
geometry (within :data:`~inertia_kit.analysis.forensics.measure.TOLERANCE`, the centre of mass
within :data:`EXACT_COM` of the centroid) the file's values are its geometry's, and the margin
alone tells (the textbook cases stay exact).

Two links that depart alike, or one without geometry to judge by, give no culprit: the rule
then keeps one finding for the pair, as it would without this module.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from inertia_kit.analysis.forensics.measure import AMBIGUITY, BAND, MARGIN, TOLERANCE, LogMetric
from inertia_kit.physics.formatting import fmt

if TYPE_CHECKING:
    from inertia_kit.analysis.geometry import Geometry
    from inertia_kit.analysis.links import LinkAnalysis
    from inertia_kit.physics.mass import MassProperties

#: a link departs clearly more in tensor than another when its log distance is this much larger
#: (a factor of 1.22 about some axis: the scatter within which two readings fit a real part
#: alike, measure.AMBIGUITY)
TENSOR_MARGIN = AMBIGUITY
#: ... or in centre of mass when its offset from the centroid is larger by this fraction of the
#: link's size (twins' own tolerance, analysis.twins.COM_TOLERANCE)
COM_MARGIN = 0.05
#: a real part's centre of mass lies within this fraction of its size from its centroid: a
#: motor at one end moves it a third of the way to that end (rules/IN021)
PLAUSIBLE_COM = 1 / 3
#: a centre of mass within this fraction of the link's size from the centroid is the geometry's
EXACT_COM = 0.01


@dataclass(frozen=True)
class Departure:
    """How far a link's declared values are from its geometry's (module doc)."""

    tensor: float  # log distance, 0 for the geometry's own tensor
    com: float  # centre of mass from the centroid, over the geometry's size

    @property
    def exact(self) -> bool:
        """Whether the values are the geometry's own (tensor within TOLERANCE, centre of mass
        within EXACT_COM): computed from it, as textbook files are."""
        return self.tensor <= TOLERANCE and self.com <= EXACT_COM

    def text(self) -> str:
        """How far, in words: ``tensor a factor of 1.52 from its geometry's, ...``."""
        factor = math.exp(self.tensor) if self.tensor < 700 else math.inf
        return (
            f"tensor a factor of {fmt(factor, 3)} from its geometry's, centre of mass "
            f"{fmt(100 * self.com, 2)} % of its size from the centroid"
        )


def score(d: Departure) -> float:
    """One number to rank departures: the centre of mass's counted in tensor units."""
    return d.tensor + d.com * (TENSOR_MARGIN / COM_MARGIN)


def departure(link: LinkAnalysis) -> Departure | None:
    """
    The link's :class:`Departure` from the geometry mass comes from (collision, else visual),
    or ``None`` without declared values or geometry: two links of one part are compared on the
    same kind of geometry.
    """
    robot = link.robot
    if robot is None:
        return _plain_departure(link)
    # several rules ask of every link sharing a block (thousands on an asset library's robots)
    # (by identity: a malformed file may name two links alike; the robot keeps its links alive)
    known = robot.fact("departures", lambda _: {})
    if id(link) not in known:
        known[id(link)] = _plain_departure(link)
    return known[id(link)]


def _plain_departure(link: LinkAnalysis) -> Departure | None:
    declared = link.declared
    if declared is None or not declared.mass > 0:
        return None
    return _departure(declared, link.geometry)


def least_departure(link: LinkAnalysis) -> Departure | None:
    """
    The link's :class:`Departure` from the geometry (collision or visual) its values fit best:
    a link is blamed for another part's values only when they fit none of its geometries as
    its own would. GR3's upper arm roll link has a 5 cm collision sphere standing in for its
    part; its own values, a factor of 3.5 from the sphere's, fit its visual mesh within 1.5.
    """
    declared = link.declared
    if declared is None or not declared.mass > 0:
        return None
    found = [d for geometry in link.bases if (d := _departure(declared, geometry)) is not None]
    return min(found, key=score) if found else None


def _departure(declared: MassProperties, geometry: Geometry) -> Departure | None:
    try:
        expected = geometry.at_mass(declared.mass)
        corners = geometry.corners
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
    """Whether ``a`` departs clearly more than ``b``, ``b`` a link of the same part (module doc)."""
    tensor, com = a.tensor - b.tensor, a.com - b.com
    if tensor > TENSOR_MARGIN and com >= -COM_MARGIN / 2:
        return True
    return com > COM_MARGIN and tensor >= -TENSOR_MARGIN / 2


def worse_part(a: Departure, b: Departure) -> bool:
    """
    Whether ``a`` departs clearly more than ``b``, a link of another part, and more than a real
    part does, unless ``b``'s values are exactly its geometry's (module doc).
    """
    if not worse(a, b):
        return False
    if b.exact:
        return True
    tensor, com = a.tensor - b.tensor, a.com - b.com
    return (tensor > TENSOR_MARGIN and a.tensor > BAND) or (
        com > COM_MARGIN and a.com > PLAUSIBLE_COM
    )


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


def lightest(links: tuple[LinkAnalysis, ...]) -> tuple[LinkAnalysis, float] | None:
    """The link of ``links`` whose density is furthest below the plausible range, and how far."""
    judged = [(link, density_excess(link)) for link in links]
    found = [(link, excess) for link, excess in judged if excess is not None and excess < 0]
    return min(found, key=lambda item: item[1]) if found else None


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
