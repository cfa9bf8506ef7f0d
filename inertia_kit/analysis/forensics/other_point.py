"""
IN060: the declared tensor is about another point, not the centre of mass.

About a point ``p`` the tensor is ``I_com + m (|d|² E - d dᵀ)`` with ``d = com - p``: undoing the
slip subtracts that parallel-axis term. The point is a named one (the link origin, a child
joint's origin, a mesh's origin), or one solved for when no mass inside the geometry could have
the declared tensor about its centre of mass.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from inertia_kit.analysis.forensics.candidate import (
    Candidate,
    Case,
    Wording,
    brief_label,
    entries,
    short_label,
)
from inertia_kit.analysis.forensics.measure import TOLERANCE
from inertia_kit.physics.formatting import fmt, vector_text
from inertia_kit.physics.mass import MassProperties, shift_tensor
from inertia_kit.physics.tensor_names import DIAGONAL

if TYPE_CHECKING:
    from inertia_kit.analysis.bounds import Hull


@dataclass(frozen=True, eq=False)
class AboutPoint(Candidate):
    """The tensor about :attr:`point` (link frame, m), named :attr:`label` ("" if solved for)."""

    CODE: ClassVar[str] = "IN060"

    point: NDArray[np.float64]
    label: str

    def word(self, case: Case) -> Wording:
        declared, corrected = case.declared, self.corrected.inertia
        offset = declared.com - self.point
        term = shift_tensor(declared.mass, offset)
        # the moment the shift changed most
        i = int(np.argmax(np.diag(term)))
        distance = math.sqrt(max(float(offset @ offset - offset[i] ** 2), 0.0))
        where = self.label or "the point"
        summary = (
            f"the declared inertia is the tensor about {where} {vector_text(self.point)}, not "
            f"about the COM {vector_text(declared.com)}"
        )
        detail = (
            f"{DIAGONAL[i]} {fmt(declared.inertia[i, i], 5)} = {fmt(corrected[i, i], 5)} + "
            f"{fmt(declared.mass, 5)} kg × ({fmt(distance, 4)} m)²; about the COM it is "
            f"{fmt(corrected[i, i], 5)}, and the {case.geometry} gives "
            f"{fmt(case.expected.inertia[i, i], 5)}"
        )
        help = (
            "write the tensor about the centre of mass: subtract the parallel-axis term "
            f"m (|d|² E - d dᵀ) with d = {vector_text(offset)} m ({entries(corrected)})"
        )
        data = {"point": [float(v) for v in self.point], "point_name": str(self.label) or None}
        # the message: the point in a few words and how far it is from the COM; with a long
        # link name, the joint's name or the mesh's kind is left to the detail
        away = f", {fmt(float(np.linalg.norm(offset)), 3)} m from the COM"
        named = short_label(self.label) if self.label else "another point"
        brief = brief_label(self.label)
        claim = f"inertia written about {named}{away}"
        brief = f"inertia written about {brief}{away}" if brief else ""
        return Wording(summary, detail, help, data, claim, brief)


def _at_com(declared: MassProperties, point: NDArray[np.float64]) -> NDArray[np.float64]:
    """The declared tensor, read as about ``point``, moved to the COM (3, 3) kg·m²."""
    return declared.inertia - shift_tensor(declared.mass, declared.com - point)


def _about(case: Case, point: NDArray[np.float64], rank: int, label: str) -> AboutPoint:
    declared = case.declared
    inertia = _at_com(declared, point)
    corrected = MassProperties(declared.mass, declared.com, inertia)
    return AboutPoint(rank, corrected, float(case.metric(inertia)), point, label)


def _about_named(case: Case, named: list[tuple[str, NDArray[np.float64]]]) -> list[AboutPoint]:
    """:func:`_about` each named point (rank 2), their deviations in one metric call."""
    if not named:
        return []
    declared = case.declared
    tensors = np.array([_at_com(declared, point) for _, point in named])
    residuals = case.metric(tensors)
    return [
        AboutPoint(2, MassProperties(declared.mass, declared.com, inertia), float(r), point, label)
        for (label, point), inertia, r in zip(named, tensors, residuals, strict=True)
    ]


def _symmetric_about(tensor: NDArray[np.float64], axis: NDArray[np.float64]) -> bool:
    """Whether ``axis`` is a principal axis about which the body is round (equal moments across)."""
    scale = float(np.trace(tensor))
    if np.linalg.norm(tensor @ axis - (axis @ tensor @ axis) * axis) > TOLERANCE * scale:
        return False
    across = np.linalg.eigvalsh(tensor - np.outer(axis, axis) * (axis @ tensor @ axis))
    # the block across the axis has eigenvalues 0 (along it) and the two moments across it
    return bool(abs(across[2] - across[1]) <= TOLERANCE * scale)


def search(
    case: Case, points: Sequence[tuple[str, ArrayLike]], hull: Hull | None
) -> list[AboutPoint]:
    """The tensor about each named point, and about a point solved for (with a ``hull``)."""
    declared, expected = case.declared, case.expected
    size = math.sqrt(max(float(np.linalg.eigvalsh(expected.inertia).max()), 0.0) / declared.mass)
    named = []
    for label, xyz in points:
        point = np.asarray(xyz, dtype=np.float64)
        if np.linalg.norm(declared.com - point) > 1e-6 * size:
            named.append((label, point))
    found = _about_named(case, named)
    if hull is None:
        return found
    # declared - I = m (|d|² E - d dᵀ) means the second moment of the difference is m d dᵀ
    difference = (declared.inertia - expected.inertia) / declared.mass
    values, vectors = np.linalg.eigh(0.5 * np.trace(difference) * np.eye(3) - difference)
    if not values[-1] > 0:
        return found
    offset = math.sqrt(values[-1]) * vectors[:, -1]
    # A point solved for is only believed when no mass inside the geometry could give the
    # declared tensor about its COM: the declared second moment along d exceeds the most any
    # distribution in the hull has (Bhatia–Davis). Inside that bound, an excess such as (δ, δ, 0)
    # on a cylinder is as well explained by mass at its ends as by a shifted reference point.
    direction = offset / np.linalg.norm(offset)
    if _symmetric_about(expected.inertia, direction):
        # about a point on a symmetry axis the excess is (δ, δ, 0): any too large value written
        # with the body's symmetry fits it exactly, so the fit proves nothing
        return found
    second = float(direction @ declared.second_moment @ direction) / declared.mass
    if not second > (1.0 + TOLERANCE) * float(hull.spread(declared.com, direction[None, :])[0]):
        return found
    # the sign of d is free: the point nearer the link origin
    point = min((declared.com - offset, declared.com + offset), key=lambda p: float(p @ p))
    found.append(_about(case, point, 6, ""))
    return found
