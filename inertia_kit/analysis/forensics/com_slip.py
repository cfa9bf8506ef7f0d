"""
The forensics of a centre of mass: a declared COM outside its geometry, or far from its
centroid, explained by a slip undone.

Each hypothesis reads the declared ``<origin xyz>`` another way: one coordinate's sign flipped
(the part drawn on the other side of its joint), every sign flipped (the mirrored twin's
values), two coordinates exchanged (another frame's axes), millimetres written as metres, or the
point given in the frame of one of the link's shapes or child joints instead of the link's. A
reading is scored as the tensor forensics score theirs (:mod:`.measure`): not by an exact match,
which no real part gives, but by where the corrected point lands relative to the geometry,
:func:`~inertia_kit.analysis.com_offset.least_fraction` (0 at the centroid, 1 at the edge of the
geometry's hull), compared in log space, ``ln((a + FLOOR) / (b + FLOOR))``:

- the corrected point lies within :data:`BAND` of the centroid, where real links' centres of
  mass lie;
- it is at least :data:`MARGIN` closer than the declared one;
- no distinct reading lands within :data:`AMBIGUITY` of it: two readings that fit about as
  well do not tell which slip it was, and none is named (but a reading in another frame, less
  simple, that fits worse than a sign, axis or unit reading leaves it named).

Readings whose points lie within :data:`SAME_POINT` of the geometry's size of each other are the
same reading (``y`` negated and every sign negated, when ``x = z = 0``): the simplest speaks.

The band comes from ``python benchmarks/cad_band.py`` (its ``COM fraction`` row): over the 2219
real links of the installed PyPI robot packages the linter is silent on, the declared centre of
mass lies at a fraction of the way to the geometry's edge with quantiles 50 % 0.09, 90 % 0.29,
95 % 0.41, 99 % 0.54, max 0.75 (mesh links alone: 0.10, 0.29, 0.41, 0.54, 0.62).
"""

from __future__ import annotations

import math
import weakref
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.com_offset import least_fraction
from inertia_kit.analysis.geometry import Geometry
from inertia_kit.description import model
from inertia_kit.physics.frames import rpy_matrix

if TYPE_CHECKING:
    from inertia_kit.analysis.links import LinkAnalysis

#: the corrected point lies within this fraction of the way from the centroid to the edge:
#: between the 95th and the 99th percentile of real links (0.41, 0.54), and below IN021's
#: warning (0.6), so that a fix written from it is a fixed point
BAND = 0.5
#: log gains are of the fraction plus this: a point at the centroid (0) is not infinitely better
#: than one a tenth of the way out, both are where real parts put it
FLOOR = 0.2
#: the corrected point is this much closer (log of the floored fractions, a factor of 2.2, the
#: tensor forensics' margin): a point 92 % of the way out must come within 30 % of it
MARGIN = 0.8
#: a distinct reading within this of the best (a factor of 1.5) leaves the slip unknown
AMBIGUITY = 0.4
#: two corrected points closer than this fraction of the geometry's size are one reading
SAME_POINT = 0.05
#: millimetres written as metres: the one unit slip a centre of mass shows (CAD exports in mm)
MILLIMETRE = 1e-3
#: ... read so only when the point lies this many times the geometry's size from the link
#: origin: in millimetres a point 3 % of the size from it already does, while any point near
#: the origin read as millimetres lands on it (Talos' ankle links, 5 cm off their 4 cm part)
UNIT_REACH = 30.0

#: the rank of a reading in another frame: the least simple, as it has many frames to try
FRAME_RANK = 2

_AXIS = "xyz"


@dataclass(frozen=True)
class ComReading:
    """The declared centre of mass read another way: the slip undone."""

    rank: int  # fewer assumptions first: preferred among readings of one point
    words: str  # ``y negated``: what was undone, to follow "with"
    kind: str  # ``flip``, ``mirrored``, ``swap``, ``unit``, ``frame``: the hypothesis
    point: NDArray[np.float64]  # the corrected centre of mass, link frame, m
    fraction: float  # its least offset fraction (0 at a centroid, 1 at the hull's edge)


@dataclass(frozen=True)
class ComDiagnosis:
    """
    What undoing a slip says about a declared centre of mass: the ``reading`` that explains it
    (``None`` when two distinct readings fit alike: then ``rivals`` holds them).
    """

    declared_fraction: float
    reading: ComReading | None
    rivals: tuple[ComReading, ...] = ()
    centroid_distance: float = math.nan  # of the reading's point from the nearest centroid, m


def _gain(worse: float, better: float) -> float:
    return math.log((worse + FLOOR) / (better + FLOOR))


def readings(
    com: NDArray[np.float64],
    frames: Sequence[tuple[str, NDArray[np.float64]]] = (),
    size: float = 0.0,
) -> list[tuple[int, str, str, NDArray[np.float64]]]:
    """
    Every reading of ``com`` (link frame, m) by the hypotheses: ``(rank, words, kind, point)``,
    simplest first. ``frames``: named 4×4 poses (link frame) the point may have been given in;
    ``size``: the geometry's, m (millimetres are read only far beyond it: :data:`UNIT_REACH`).
    """
    found: list[tuple[int, str, str, NDArray[np.float64]]] = []
    for i in range(3):
        flipped = com.copy()
        flipped[i] = -flipped[i]
        found.append((0, f"{_AXIS[i]} negated", "flip", flipped))
    found.append((1, "every sign negated (mirrored)", "mirrored", -com))
    for i, j in ((0, 1), (0, 2), (1, 2)):
        swapped = com.copy()
        swapped[i], swapped[j] = com[j], com[i]
        found.append((1, f"{_AXIS[i]} and {_AXIS[j]} exchanged", "swap", swapped))
    if np.linalg.norm(com) >= UNIT_REACH * size:
        found.append((1, "the values read as millimetres", "unit", com * MILLIMETRE))
    for name, pose in frames:
        moved = pose[:3, :3] @ com + pose[:3, 3]
        found.append((FRAME_RANK, f"the point read in {name}", "frame", moved))
    # a reading that changes nothing (a zero coordinate negated) is the declared point
    return [r for r in found if not np.array_equal(r[3], com)]


def link_frames(link: model.Link, children: Sequence[model.Joint]) -> list:
    """Named poses of a link's shapes and child joints (not the link's own): ``(name, pose)``."""
    frames = []
    seen: set[tuple[float, ...]] = set()  # poses to 1e-9: a star of 5000 joints compared pairwise
    places = [(f"the frame of joint `{j.name}`", j.origin) for j in children]
    for shape in (*link.collisions, *link.visuals):
        places.append((f"the {shape.kind} origin's frame", shape.origin))
    for name, origin in places:
        xyz, rpy = origin.xyz, origin.rpy
        numbers = (*xyz, *rpy) if isinstance(xyz, tuple) and isinstance(rpy, tuple) else ()
        if len(numbers) != 6 or not all(isinstance(v, float) for v in numbers):
            continue
        pose = np.eye(4)
        pose[:3, :3] = rpy_matrix(rpy)  # type: ignore[arg-type]
        pose[:3, 3] = xyz
        key = tuple(np.round(pose, 9).ravel().tolist())
        if np.allclose(pose, np.eye(4)) or key in seen:
            continue
        seen.add(key)
        frames.append((name, pose))
    return frames


def _size(bases: Sequence[Geometry]) -> float:
    """The largest extent of the bases' hulls, m."""
    hulls = [g.hull for g in bases if g.hull is not None]
    low = np.min([h.bounds[0] for h in hulls], axis=0)
    high = np.max([h.bounds[1] for h in hulls], axis=0)
    return float((high - low).max())


def _usable(bases: Sequence[Geometry]) -> list[Geometry]:
    """The bases a point can be placed against: a solid and a hull."""
    return [g for g in bases if g.unit is not None and g.hull is not None]


def _readable(usable: Sequence[Geometry], com: NDArray[np.float64]) -> bool:
    """Whether readings of ``com`` mean anything: geometry to read them against, a finite point,
    and not the origin (a point left there is no slip to undo: every reading of it is the
    origin, or a frame's origin; IN021 moves it to the centroid)."""
    return bool(usable) and bool(np.isfinite(com).all()) and bool(com.any())


def _scored(
    com: NDArray[np.float64],
    usable: Sequence[Geometry],
    frames: Sequence[tuple[str, NDArray[np.float64]]],
    size: float,
) -> list[ComReading]:
    """Every reading of ``com`` with where it lands (:func:`least_fraction`), unsorted."""
    return [
        ComReading(rank, words, kind, point, least_fraction(usable, point))
        for rank, words, kind, point in readings(com, frames, size)
    ]


def diagnose_com(
    com: NDArray[np.float64],
    bases: Sequence[Geometry],
    frames: Sequence[tuple[str, NDArray[np.float64]]] = (),
) -> ComDiagnosis | None:
    """
    The slip that explains the declared centre of mass ``com`` (link frame, m) against the
    link's ``bases`` (collision, visual), or ``None``: no usable geometry, or a declared point
    already within :data:`BAND`, or no reading that lands in the band a clear margin closer.
    A diagnosis without a ``reading`` is ambiguous (see the module docstring).
    """
    usable = _usable(bases)
    com = np.asarray(com, dtype=np.float64)
    if not _readable(usable, com):
        return None
    declared = least_fraction(usable, com)
    if not declared > BAND:
        return None
    size = _size(usable)
    scored = sorted(_scored(com, usable, frames, size), key=lambda r: (r.fraction, r.rank))
    fits = [r for r in scored if r.fraction <= BAND and _gain(declared, r.fraction) >= MARGIN]
    if not fits:
        return None
    best = fits[0]
    near = [r for r in scored if _gain(r.fraction, best.fraction) < AMBIGUITY]
    same = [r for r in near if np.linalg.norm(r.point - best.point) <= SAME_POINT * size]
    chosen = min(same, key=lambda r: r.rank)
    # a rival is a distinct reading that fits about as well; a reading in another frame (which
    # some frame of a link's shapes or joints gives by chance more often) that fits worse
    # does not put a sign, axis or unit reading in doubt
    rivals = [
        r
        for r in near
        if np.linalg.norm(r.point - best.point) > SAME_POINT * size
        and (r.rank < FRAME_RANK or chosen.rank == FRAME_RANK)
    ]
    if rivals:
        return ComDiagnosis(declared, None, (chosen, *rivals))
    distance = min(
        float(np.linalg.norm(chosen.point - g.unit.com))  # type: ignore[union-attr]
        for g in usable
    )
    return ComDiagnosis(declared, chosen, (), distance)


def inside_readings(link: LinkAnalysis) -> list[ComReading]:
    """
    The sign, axis and unit readings of a link's declared centre of mass that land inside its
    geometry's hull (fraction below 1) but beyond :data:`BAND`, best first: slips that would
    put the point back inside, though not near enough to the centroid to be named (IN021
    says them; a reading within the band is IN067's).
    """
    from inertia_kit.analysis.declared import declared_com

    com = declared_com(link.link)
    usable = _usable(link.bases)
    if com is None or not _readable(usable, com):
        return []
    size = _size(usable)
    found = sorted(_scored(com, usable, (), size), key=lambda r: (r.rank, r.fraction))
    kept: list[ComReading] = []
    for reading in found:  # the simplest of readings that give one point (see SAME_POINT)
        if all(np.linalg.norm(reading.point - k.point) > SAME_POINT * size for k in kept):
            kept.append(reading)
    return sorted((r for r in kept if BAND < r.fraction < 1), key=lambda r: (r.fraction, r.rank))


_LINKS: weakref.WeakKeyDictionary[LinkAnalysis, ComDiagnosis | None] = weakref.WeakKeyDictionary()


def diagnose_link_com(link: LinkAnalysis) -> ComDiagnosis | None:
    """
    :func:`diagnose_com` of a link's declared centre of mass against its bases and the frames
    of its shapes and child joints, or ``None`` (no declared point). Cached per link: IN021's
    help, IN067 and the fix planner all ask.
    """
    if link not in _LINKS:
        from inertia_kit.analysis.declared import declared_com

        com = declared_com(link.link)
        _LINKS[link] = (
            None
            if com is None
            else diagnose_com(com, link.bases, link_frames(link.link, link.children))
        )
    return _LINKS[link]
