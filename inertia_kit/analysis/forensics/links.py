"""
The forensics of a link: its declared tensor diagnosed against its collision geometry, else its
visual one, with the link's own reference points and frames as the named candidates; and what
the IN06x rules say about a diagnosis.
"""

from __future__ import annotations

import math
import weakref
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from inertia_kit.analysis.bounds import BOUND_RTOL
from inertia_kit.analysis.describe import TABLE, describe_geometry
from inertia_kit.analysis.forensics.measure import (
    BETTER,
    LOOSE,
    LOOSE_BETTER,
    MIN_MISMATCH,
    TOLERANCE,
    LogMetric,
    deviation,
)
from inertia_kit.description import model
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.frames import rpy_matrix

if TYPE_CHECKING:
    from inertia_kit.analysis.forensics.diagnosis import Diagnosis
    from inertia_kit.analysis.geometry import Geometry
    from inertia_kit.analysis.links import LinkAnalysis
    from inertia_kit.physics.mass import MassProperties


def _origin_rotation(origin: model.Origin) -> NDArray[np.float64] | None:
    rpy = origin.rpy
    if not isinstance(rpy, tuple) or not all(isinstance(v, float) for v in rpy):
        return None
    return rpy_matrix(rpy)


def _snapped(rotation: NDArray[np.float64]) -> NDArray[np.float64]:
    """An axis permutation when ``rotation`` is one up to a rounded pi (``rpy="0 1.5708 0"``)."""
    rounded = np.round(rotation)
    if np.abs(rotation - rounded).max() <= 1e-4 and np.allclose(rounded @ rounded.T, np.eye(3)):
        return rounded
    return rotation


def _named_frames(link: LinkAnalysis) -> tuple[list, list]:
    """
    Reference points (link origin, child joints, mesh origins) and shape frames of a link;
    cached per link (each basis, strict and loose, asks for them).
    """
    if link not in _FRAMES:
        _FRAMES[link] = _find_named_frames(link)
    return _FRAMES[link]


def _named(shape: model.Shape) -> str:
    """``the collision box``: the shape's kind as the report table names it (box, mesh, …)."""
    return f"the {shape.kind} {describe_geometry(shape.geometry, TABLE).split(' ')[0]}"


def _find_named_frames(link: LinkAnalysis) -> tuple[list, list]:
    # the hypotheses' modules wait for a tensor that disagrees with its geometry (issue 23:
    # start-up); each point and frame named as a finding's detail says it, with how its
    # one-line message does (Label)
    from inertia_kit.analysis.forensics.candidate import Label
    from inertia_kit.analysis.forensics.other_axes import rpy_text

    points: list[tuple[str, ArrayLike]] = [("the link origin", (0.0, 0.0, 0.0))]
    for joint in link.children:
        xyz = joint.origin.xyz
        if isinstance(xyz, tuple) and all(isinstance(v, float) for v in xyz):
            name = f"joint `{joint.name}`"
            label = Label(f"the origin of {name}", f"{name}'s origin", "a joint's origin")
            points.append((label, xyz))
    rotations: list[tuple[str, ArrayLike]] = []
    for shape in (*link.link.collisions, *link.link.visuals):
        xyz = shape.origin.xyz
        mesh = isinstance(shape.geometry, model.Mesh) and isinstance(xyz, tuple)
        if mesh and all(isinstance(v, float) for v in xyz) and any(xyz):  # type: ignore[union-attr]
            filename = shape.geometry.filename  # type: ignore[union-attr]
            label = Label(
                f"the origin of {_named(shape)} `{filename}`",
                f"{_named(shape)}'s origin",
                "a mesh's origin",
            )
            points.append((label, xyz))
        angles = shape.origin.rpy
        turned = isinstance(angles, tuple) and any(angles)  # rpy 0 0 0: no frame to name
        rotation = _origin_rotation(shape.origin) if turned else None
        if rotation is not None and not np.allclose(rotation, np.eye(3)):
            rpy = rpy_text(shape.origin.rpy)  # type: ignore[arg-type]
            what = _named(shape)
            label = Label(f'{what}\'s own axes (<origin rpy="{rpy}">)', f"{what}'s axes")
            rotations.append((label, _snapped(rotation)))
    return points, rotations


_CACHE: weakref.WeakKeyDictionary[LinkAnalysis, dict[tuple, Diagnosis | None]] = (
    weakref.WeakKeyDictionary()
)
#: the key of :func:`diagnose_link`'s result in a link's :data:`_CACHE` (the others are a basis's
#: kind and ``loose``)
_EITHER_BASIS = ("either basis",)
_FRAMES: weakref.WeakKeyDictionary[LinkAnalysis, tuple[list, list]] = weakref.WeakKeyDictionary()


def diagnose_basis(link: LinkAnalysis, basis: Geometry, loose: bool = False) -> Diagnosis | None:
    """
    The diagnosis of a link's declared tensor against one of its :attr:`LinkAnalysis.bases`
    (``basis`` set), whether or not it agrees with the other; cached per link and basis.

    ``loose``: what the tensor most likely is when it is not explained within
    :data:`TOLERANCE`: a match within :data:`LOOSE` (a real part is not the uniform solid of
    its collision shapes), only by named points, rotations, signs, units and transpositions (no
    point solved for). IN020 names it in its message; nothing is corrected from it.
    """
    return _cached(link, basis, "loose" if loose else "exact")


def _cached(link: LinkAnalysis, basis: Geometry, mode: str) -> Diagnosis | None:
    cache = _CACHE.setdefault(link, {})
    key = (basis.kind, mode)
    if key not in cache:
        cache[key] = _diagnose_basis(link, basis, mode)
    return cache[key]


def _readings_from_file(link: LinkAnalysis, basis: Geometry) -> dict[str, Any]:
    """What the file names for the hypotheses to try against ``basis``: the points and frames
    of the link, the axes its six values are written in, the geometry's volume."""
    inertial = link.link.inertial
    points, rotations = _named_frames(link)
    return {
        "points": points,
        "rotations": rotations,
        "axes": None if inertial is None else _origin_rotation(inertial.origin),
        "volume": basis.volume,
    }


def _diagnose_basis(link: LinkAnalysis, basis: Geometry, mode: str) -> Diagnosis | None:
    """:func:`diagnose` (``mode`` ``exact`` or ``loose``) or :func:`diagnose_part`
    (``likely``) of the link's declared values against ``basis``."""
    from inertia_kit.analysis.forensics.diagnosis import diagnose, diagnose_part

    declared = link.declared
    if declared is None or not declared.mass > 0:
        return None
    expected = basis.at_mass(declared.mass)
    if expected is None:
        return None
    common: dict[str, Any] = {**_readings_from_file(link, basis), "geometry": basis.describe()}
    if mode == "likely":
        diagnosis = diagnose_part(declared, expected, **common)
    else:
        loose = mode == "loose"
        diagnosis = diagnose(
            declared,
            expected,
            hull=None if loose else basis.hull,
            tolerance=LOOSE if loose else TOLERANCE,
            better=LOOSE_BETTER if loose else BETTER,
            **common,
        )
    return None if diagnosis is None else replace(diagnosis, basis=basis.kind)


def link_gains(link: LinkAnalysis) -> dict[str, float]:
    """
    :func:`~.diagnosis.part_gains` of the link's declared values against each of its bases,
    the larger of the two per rule: what a reading of a real part gains where nothing slipped
    (``benchmarks/cad_band.py``).
    """
    from inertia_kit.analysis.forensics.diagnosis import part_gains

    declared = link.declared
    if declared is None or not declared.mass > 0:
        return {}
    found: dict[str, float] = {}
    for basis in link.bases:
        expected = basis.at_mass(declared.mass)
        if expected is None:
            continue
        gains = part_gains(declared, expected, **_readings_from_file(link, basis))
        for code, gain in gains.items():
            found[code] = max(found.get(code, gain), gain)
    return found


def diagnose_link(link: LinkAnalysis) -> Diagnosis | None:
    """
    The diagnosis of a link's declared tensor, or ``None``: no declared value, no usable
    geometry, a tensor that agrees with the collision or the visual geometry (within
    :data:`MIN_MISMATCH`), or nothing that explains it. The collision geometry's diagnosis is
    preferred. ``inertia-fill --fix invalid`` writes its ``corrected`` values. Cached per link:
    each IN06x rule asks.
    """
    cache = _CACHE.setdefault(link, {})
    if _EITHER_BASIS not in cache:
        cache[_EITHER_BASIS] = _diagnose_link(link)
    return cache[_EITHER_BASIS]


def _diagnose_link(link: LinkAnalysis) -> Diagnosis | None:
    declared = link.declared
    if declared is None or not declared.mass > 0:
        return None
    found = []
    bases = _distinct(link.bases)
    for basis in bases:
        expected = basis.at_mass(declared.mass)
        if expected is None:
            return None
        try:
            if deviation(declared.inertia, expected.inertia) < MIN_MISMATCH:
                return None  # agrees with one basis: nothing to explain
        except np.linalg.LinAlgError:
            return None
        diagnosis = diagnose_basis(link, basis)
        if diagnosis is not None:
            found.append(diagnosis)
    if found:
        return found[0]
    # no exact fit: the likely slip of a real part, against the collision geometry else the
    # visual one, when no basis contradicts it: two bases that name different slips leave it
    # unknown, and a basis that names none must at least come closer with the slip undone (a
    # crude collision box and a detailed visual mesh rarely both land within the band)
    likely = [(basis, _cached(link, basis, "likely")) for basis in bases]
    named = {(d.code, type(d.slip)) for _, d in likely if d is not None}
    if len(named) != 1:
        return None
    found = next(d for _, d in likely if d is not None)
    for basis, diagnosis in likely:
        if diagnosis is None and not _closer(declared, found, basis):
            return None
    return found


def _distinct(bases: tuple[Geometry, ...]) -> list[Geometry]:
    """The bases but one of two that hold the same solids (visual and collision naming one
    mesh): its diagnosis would be the other's, which comes first and is the one kept."""
    kept: list[Geometry] = []
    for basis in bases:
        if not any(basis.same_solids(other) for other in kept):
            kept.append(basis)
    return kept


def _closer(declared: MassProperties, diagnosis: Diagnosis, basis: Geometry) -> bool:
    """Whether undoing the diagnosed slip brings the tensor closer to ``basis``'s too (log
    distance, the corrected tensor against the geometry at the corrected mass)."""
    after, before = basis.at_mass(diagnosis.corrected.mass), basis.at_mass(declared.mass)
    if after is None or before is None:
        return False
    try:
        corrected = LogMetric(after.inertia)(diagnosis.corrected.inertia)
        return corrected < LogMetric(before.inertia)(declared.inertia)
    except np.linalg.LinAlgError:
        return False


@dataclass(frozen=True)
class Explanation:
    """What a forensic rule's finding says about a link whose diagnosis is its hypothesis."""

    link: str  # the link's name
    message: str  # link `name`: the claim and its key numbers, one short line
    source: model.Source | None  # the <inertia> element, else the <inertial>
    expected: dict[str, Any]  # :meth:`Diagnosis.expected`
    help: str
    # beyond the geometry's hard bound: the finding replaces IN023's error, so it is one too
    impossible: bool
    # a real part's likely slip (diagnosis.diagnose_part), not an exact fit: its fix is unsafe
    likely: bool = False
    # what went wrong, the numbers that show it, and why it is an error when it is one: what
    # the one-line message leaves out
    detail: str | None = None


def explain(link: LinkAnalysis, code: str) -> Explanation | None:
    """The link's diagnosis when the hypothesis of the forensic rule ``code`` (``IN060`` …
    ``IN064``: :attr:`Diagnosis.code`) explains it (see :func:`diagnose_link`)."""
    diagnosis = diagnose_link(link)
    inertial = link.link.inertial
    if diagnosis is None or diagnosis.code != code or inertial is None:
        return None
    from inertia_kit.analysis.forensics.candidate import one_line

    excess = link.excess
    # an error, like IN023's, only when the bound holds with the numbers' rounding allowed for,
    # on collision geometry (analysis.firmness)
    impossible = bool(
        excess is not None
        and excess.ratio > 1.0 + BOUND_RTOL
        and link.firmness is not None
        and link.firmness.firm
    )
    beyond = "; as written no mass inside the geometry can have it (IN023)" if impossible else ""
    wording = diagnosis.wording
    help = wording.help
    if diagnosis.likely is not None:
        plain, fitted = diagnosis.likely
        help = (
            f"{help} (likely, not proven: a real part's values agree with a uniform solid of its "
            f"shapes only within a factor of about 2; undone, the slip brings the tensor from "
            f"{fmt(math.exp(plain), 3)} times off the {diagnosis.basis} geometry's to "
            f"{fmt(math.exp(fitted), 3)}, as close as real parts come: check against the CAD "
            "report before applying the fix, which is therefore unsafe)"
        )
    head = f"link `{link.name}`: " + ("likely " if diagnosis.likely is not None else "")
    return Explanation(
        link.name,
        one_line(head, wording.claim or wording.summary, wording.brief),
        inertial.inertia_source or inertial.source,
        diagnosis.expected(),
        help,
        impossible,
        likely=diagnosis.likely is not None,
        detail=f"{wording.summary}: {wording.detail}{beyond}",
    )
