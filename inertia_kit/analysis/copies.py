"""
Copied ``<inertial>`` blocks: links whose whole block (mass, ``<origin>``, the six values) is
another link's, and which of them the block belongs to.

Identical blocks are right on identical parts (left/right twins, repeated fingers, four wheels):
each link's geometry then fits the block alike. A block copied onto a different part (the
neighbouring link's, pasted by hand or by a macro called with the wrong arguments) fits the
part it was made for and departs from the other: its tensor is another shape's, its centre of
mass sits where the other part's would. Among links that share a block, the one that fits it
best (:func:`~inertia_kit.analysis.fault.departure`, the smallest) is its owner when it fits as
a real part does (its tensor within :data:`~inertia_kit.analysis.forensics.measure.BAND`, its
centre of mass within :data:`OWNER_COM` of its size from the centroid); each
other one whose values depart clearly more from its own geometry
(:func:`~inertia_kit.analysis.fault.worse_part`) holds a copy. Real CAD values sometimes fit their
own part more loosely than that (Panda's ``link5`` a factor of 4.9 from its collision mesh); a
block that fits its best link only so is still that link's where on another link it is no real
part's values and departs far more (:func:`_foreign`). A block that fits no link plausibly is a
placeholder, not a copy: each link's own rules (IN013, IN020, IN023) judge it, and no link is
named the copy of another (two dummy frames sharing 1e-6 kg could each be either).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from inertia_kit.analysis.fault import (
    IMPLAUSIBLE,
    PLAUSIBLE_COM,
    Departure,
    departure,
    least_departure,
    score,
    worse_part,
)
from inertia_kit.analysis.forensics.measure import BAND, MARGIN

if TYPE_CHECKING:
    from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis


#: ... and its centre of mass within this fraction of the link's size from the centroid
OWNER_COM = PLAUSIBLE_COM
#: a centre of mass farther than half the link's size from its centroid is outside its geometry
OUTSIDE = 1 / 2


@dataclass(frozen=True)
class Copy:
    """``link`` holds ``original``'s whole ``<inertial>``, which fits ``original`` only."""

    link: LinkAnalysis
    original: LinkAnalysis
    mine: Departure  # the block against the link's own geometry
    theirs: Departure  # ... against the original's


def six_values(link: LinkAnalysis) -> tuple[float, ...] | None:
    """
    The six ``<inertia>`` values as written, what links that share them share, when the link's
    declared values are complete and finite with a mass > 0 (others are other rules'), and not
    all zero (a zero tensor is IN012's, not a copy of anything); else ``None``.
    """
    inertial, declared = link.link.inertial, link.declared
    if inertial is None or declared is None:
        return None
    if not (declared.mass > 0 and math.isfinite(declared.mass)):
        return None
    if not np.isfinite(declared.inertia).all():
        return None
    values = tuple(inertial.tensor_values().values())  # numbers: ``declared`` read them
    return values if any(values) else None  # type: ignore[return-value]


def block(link: LinkAnalysis) -> tuple | None:
    """The whole ``<inertial>`` as numbers (mass, xyz, rpy, six values), or ``None``."""
    values = six_values(link)
    if values is None:
        return None
    inertial = link.link.inertial
    assert inertial is not None
    return (inertial.mass, inertial.origin.xyz, inertial.origin.rpy, values)


def _foreign(copy: Departure, best: Departure) -> bool:
    """
    Whether a block that fits its best link only roughly (a real part's CAD values off by more
    than the band, a centre of mass far from the centroid: Panda's ``link5``, Mini Cheetah's
    shanks) is still plainly that link's and not the other's: on the other it is no real part's
    values (:data:`~inertia_kit.analysis.fault.IMPLAUSIBLE`), and it departs there by a factor
    of 2.2 more (:data:`~inertia_kit.analysis.forensics.measure.MARGIN`) or by a third of the
    link's size more in centre of mass, while the best link's tensor is plausible.
    """
    if best.tensor > IMPLAUSIBLE:
        return False  # it fits no link as any real part: a placeholder
    if not (copy.tensor > IMPLAUSIBLE or copy.com > OUTSIDE):
        return False
    return copy.tensor - best.tensor > MARGIN or copy.com - best.com > OWNER_COM


def _unfit_anywhere(link: LinkAnalysis, best: Departure) -> bool:
    """Whether the block departs clearly more on every geometry of ``link`` (collision, visual)."""
    least = least_departure(link)
    return least is not None and worse_part(least, best)


def copies(robot: RobotAnalysis) -> list[Copy]:
    """The links holding another link's copied block, in file order (module doc)."""
    return robot.fact("whole copies", _copies)


def _copies(robot: RobotAnalysis) -> list[Copy]:
    groups: dict[tuple, list[LinkAnalysis]] = {}
    for link in robot.links:
        key = block(link)
        if key is not None and link.name not in {m.name for m in groups.get(key, [])}:
            groups.setdefault(key, []).append(link)
    found: list[Copy] = []
    for members in groups.values():
        judged = [(m, d) for m in members if (d := departure(m)) is not None]
        if len(judged) < 2:
            continue
        original, best = min(judged, key=lambda item: score(item[1]))
        owned = best.tensor <= BAND and best.com <= OWNER_COM
        found += [
            Copy(m, original, d, best)
            for m, d in judged
            if m is not original
            and worse_part(d, best)
            and (owned or _foreign(d, best))
            and _unfit_anywhere(m, best)
        ]
    order = {link.name: i for i, link in enumerate(robot.links)}
    return sorted(found, key=lambda c: order[c.link.name])
