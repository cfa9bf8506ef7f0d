"""
The one place that decides "this mesh looks authored in mm, cm or inches": observations of a
mesh's size (:class:`Evidence`) and :func:`suspected_unit`, the unit slip that explains them.

IN031 (and through it ``inertia-fill``'s refusal) judges a link's mesh on its size, its joint
offsets, its peers and its density; ``inertia-kit mass mesh`` on the mesh's size alone (and its
density when ``--mass`` is given). Both take the verdict from here.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

# unit slips: the factor the mesh's size is wrong by, and how that happens. A factor below 1
# shrinks the mesh (a file in mm read as m); above 1 grows it (a scale for mm applied to a file
# already in m)
SLIPS = {
    0.001: "as if millimetres were read as metres",
    0.01: "as if centimetres were read as metres",
    0.0254: "as if inches were read as metres",
    1000.0: "as if a millimetre scale were put on a mesh already in metres",
    100.0: "as if a centimetre scale were put on a mesh already in metres",
    1 / 0.0254: "as if an inch scale were put on a mesh already in metres",
}
#: the unit a mesh was authored in, for the slips that shrink it
UNITS = {0.001: "mm", 0.01: "cm", 0.0254: "inch"}

# the size a robot part can have, m, and the density, kg/m³ (IN031's options' defaults)
SIZE_BAND = (0.001, 5.0)
DENSITY_BAND = (1.0, 1e7)
# millimetre exports are the common slip: between slips that explain the evidence equally well,
# the others pay this many decades (measured: finds 2 points more mm and metre-scale slips for
# 4 points fewer cm ones)
PRIOR = {0.01: 0.3, 100.0: 0.3, 0.0254: 0.3, 1 / 0.0254: 0.3}
# an alternative slip is named when it fits within this many decades per observation of the
# best one (cm and inches, 0.4 decades apart, often do)
ALTERNATIVE = 0.5
# an evidence item counts as against the current scale beyond this many decades out of band
# (a factor of 2): borderline values are the normal spread of real robots
VIOLATION = 0.3
# the best slip must explain the evidence: at most this many decades out of band in total
EXPLAINED = 0.3


@dataclass(frozen=True)
class Evidence:
    """
    One observation about a mesh's size: ``value(log_r)`` is its log10 if the mesh were
    ``10**log_r`` times its size, ``band`` the log10 range real robots fall in.
    """

    kind: str  # size | joints | peer | density
    value: Callable[[float], float]
    band: tuple[float, float]
    text: Callable[[float], str]  # what the observation is, at a slip (0: as written)

    def excess(self, log_r: float = 0.0) -> float:
        x = self.value(log_r)
        return max(self.band[0] - x, 0.0, x - self.band[1])

    def off_centre(self, log_r: float) -> float:
        return abs(self.value(log_r) - 0.5 * (self.band[0] + self.band[1]))


def size_evidence(extent: float, band: tuple[float, float] = SIZE_BAND) -> Evidence:
    """A part spanning ``extent`` m, against the sizes robot parts have (``band``, m)."""
    size = math.log10(extent)
    low, high = math.log10(band[0]), math.log10(band[1])
    return Evidence(
        "size",
        lambda r: size + r,
        (low, high),
        lambda r: "no robot part is that " + ("large" if size + r > high else "small"),
    )


def density_evidence(
    mass: float,
    own: float,
    rest: float = 0.0,
    band: tuple[float, float] = DENSITY_BAND,
    text: Callable[[float, float], str] | None = None,
) -> Evidence:
    """
    ``mass`` kg in the mesh's volume ``own`` m³ plus ``rest`` m³ of other shapes, against the
    densities materials have (``band``, kg/m³); ``text(mass, density)`` says it.
    """

    def density(r: float) -> float:
        return mass / (rest + own * 10 ** (3 * r))

    say = text or (lambda m, d: f"{m:.4g} kg in it is {d:.4g} kg/m³")
    return Evidence(
        "density",
        lambda r: math.log10(density(r)),
        (math.log10(band[0]), math.log10(band[1])),
        lambda r: say(mass, density(r)),
    )


@dataclass(frozen=True)
class Suspicion:
    """The unit slip that explains the evidence (``None``: none needed), and others that fit."""

    slip: float | None
    others: tuple[float, ...] = ()

    @property
    def unit(self) -> str | None:
        """``mm``, ``cm`` or ``inch`` when the mesh looks authored in it."""
        return None if self.slip is None else UNITS.get(self.slip)


def suspected_unit(evidence: Sequence[Evidence], min_evidence: int = 2) -> Suspicion:
    """
    The slip (the factor to scale the mesh by) that best explains ``evidence``, when at least
    ``min_evidence`` observations are out of band by more than :data:`VIOLATION` and the slip
    brings them all within :data:`EXPLAINED` decades.
    """
    against = [e for e in evidence if e.excess() > VIOLATION]
    if not against or len(against) < min_evidence:
        return Suspicion(None)
    now = sum(e.excess() for e in evidence)

    def score(slip: float) -> tuple[float, float]:
        r = math.log10(slip)
        return (
            sum(e.excess(r) for e in evidence),
            sum(e.off_centre(r) for e in evidence) + PRIOR.get(slip, 0.0),
        )

    ranked = sorted(SLIPS, key=score)
    best = ranked[0]
    explained = score(best)[0]
    if explained > EXPLAINED or not explained < 0.25 * now:
        return Suspicion(None)
    others = tuple(
        s
        for s in ranked[1:]
        if score(s)[0] <= EXPLAINED and score(s)[1] <= score(best)[1] + ALTERNATIVE * len(evidence)
    )
    return Suspicion(best, others)
