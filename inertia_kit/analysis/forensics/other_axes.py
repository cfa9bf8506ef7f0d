"""
IN062: the declared tensor is written in the axes of another frame.

A tensor is only meaningful in the axes it was computed in; written without the
``<inertial><origin rpy>`` that turns those axes into the link's, it is the right tensor for the
wrong axes (same principal moments). The axes tried: a shape's own (``<origin rpy>`` of a
visual or collision), every axis permutation, and the geometry's principal axes (a diagonal
tensor from a CAD report without its rotation).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from inertia_kit.analysis.forensics.candidate import (
    Candidate,
    Case,
    Wording,
    entries,
    short_label,
)
from inertia_kit.analysis.forensics.measure import symmetric
from inertia_kit.analysis.tensors import axis_name
from inertia_kit.physics.formatting import fmt, vector_text
from inertia_kit.physics.frames import matrix_rpy
from inertia_kit.physics.mass import MassProperties

# every proper rotation that permutes the axes, the identity aside
_PERMUTATIONS = tuple(
    matrix
    for order in itertools.permutations(range(3))
    for signs in itertools.product((1.0, -1.0), repeat=3)
    if np.linalg.det(matrix := np.eye(3)[list(order)] * np.array(signs)[:, None]) > 0
    and not np.array_equal(matrix, np.eye(3))
)
#: the same, stacked (23, 3, 3): the declared tensor turned by every one in one product
_PERMUTATION_STACK = np.array(_PERMUTATIONS)


def rpy_text(rpy: Iterable[float]) -> str:
    """``0 1.5708 0``: angles as an ``rpy`` attribute says them."""
    return " ".join(fmt(v, 5) for v in rpy)


def _axis_text(axis: NDArray[np.float64]) -> str:
    """``x`` for a link axis, else the direction, pointing to the positive side."""
    name = axis_name(axis)
    if name is not None:
        return name
    if axis[int(np.argmax(np.abs(axis)))] < 0:
        axis = -axis
    return vector_text(axis, 3)


def _distinct_axis(tensor: NDArray[np.float64]) -> tuple[str, NDArray[np.float64]] | None:
    """The principal axis whose moment stands apart from the other two (a rod's, a disc's)."""
    moments, axes = np.linalg.eigh(symmetric(tensor))
    low, high = moments[1] - moments[0], moments[2] - moments[1]
    if max(low, high) <= 1e-6 * moments[2]:
        return None  # isotropic
    return ("least", axes[:, 0]) if low > high else ("greatest", axes[:, 2])


@dataclass(frozen=True, eq=False)
class OtherAxes(Candidate):
    """
    The tensor written in the axes :attr:`rotation` turns into link axes (``A T Aᵀ``; columns:
    those axes in link coordinates), of the frame named :attr:`label` ("" for unnamed axes).
    """

    CODE: ClassVar[str] = "IN062"

    rotation: NDArray[np.float64]
    label: str

    def word(self, case: Case) -> Wording:
        rotation, corrected = self.rotation, self.corrected.inertia
        rpy = matrix_rpy(rotation @ case.axes)
        distinct = _distinct_axis(case.expected.inertia)
        where = ""
        # the message: whose axes they are, else where they put the distinct axis
        brief = "inertia written in other axes than the link's"
        claim = brief
        if distinct is not None:
            kind, axis = distinct
            # the axis the declared values put there: the geometry's, turned back
            assumed = rotation.T @ axis
            where = (
                f"; it puts the axis of {kind} inertia along {_axis_text(assumed)}, the "
                f"{case.geometry} has it along {_axis_text(axis)}"
            )
            claim = (
                f"inertia written in other axes: {kind} inertia along {_axis_text(assumed)}, "
                f"not {_axis_text(axis)}"
            )
        if self.label:  # a shape's axes: a few words, always said
            claim, brief = f"inertia written in {short_label(self.label)}, not the link's", ""
        frame = f": {self.label}" if self.label else ""
        summary = f"the declared inertia is written for other axes{frame}{where}"
        detail = (
            f"declared {entries(case.declared.inertia)}; in the link axes it is "
            f"{entries(corrected)}, the geometry's {self.within}"
        )
        help = (
            f'set <inertial><origin rpy="{rpy_text(rpy)}"/> or write the tensor in the link axes '
            f"({entries(corrected)})"
        )
        data = {
            "rotation": [[float(v) for v in row] for row in rotation],
            "rpy": [float(v) for v in rpy],
            "frame": str(self.label) or None,
        }
        return Wording(summary, detail, help, data, claim, brief)


def _principal_axes(case: Case) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """
    The declared principal moments laid along the geometry's principal axes (a diagonal tensor
    from a CAD report written without its rotation), and the rotation that takes one set of axes
    to the other: the tensor in link axes, (3, 3) kg·m², and the rotation, (3, 3).
    """
    moments, declared_axes = np.linalg.eigh(symmetric(case.declared.inertia))
    _, geometry_axes = np.linalg.eigh(symmetric(case.expected.inertia))
    rotation = geometry_axes @ declared_axes.T
    if np.linalg.det(rotation) < 0:
        rotation = geometry_axes @ np.diag([1.0, 1.0, -1.0]) @ declared_axes.T
    return geometry_axes @ np.diag(moments) @ geometry_axes.T, rotation


def search(
    case: Case, rotations: Sequence[tuple[str, ArrayLike]], tolerance: float = math.inf
) -> list[OtherAxes]:
    """
    The tensor turned from each named frame's axes, each axis permutation and the geometry's
    principal axes into link axes: those whose deviation from the geometry's is not above
    ``tolerance`` (the others cannot be chosen), in that order.
    """
    declared = case.declared
    if np.abs(declared.inertia).max() > case.metric.reach(tolerance):
        return []  # every candidate is the declared tensor turned: its moments, too large
    named = [np.asarray(r, dtype=np.float64) for _, r in rotations]
    # each named frame on its own (any layout), the permutations all at once: the same
    # products either way, each tensor's own
    turned = [r @ declared.inertia @ r.T for r in named]
    permuted = _PERMUTATION_STACK @ declared.inertia @ _PERMUTATION_STACK.swapaxes(-1, -2)
    principal, principal_rotation = _principal_axes(case)
    tensors = np.concatenate([np.reshape(turned, (-1, 3, 3)), permuted, principal[None]])
    # one metric call for every candidate: the deviations of each tensor alone
    residuals = case.metric(tensors)
    frames = [
        *((r, 3, label) for r, (label, _) in zip(named, rotations, strict=True)),
        *((p, 4, "") for p in _PERMUTATIONS),
        (principal_rotation, 7, ""),
    ]
    found = []
    for (rotation, rank, label), tensor, residual in zip(frames, tensors, residuals, strict=True):
        if residual > tolerance:
            continue
        corrected = MassProperties(declared.mass, declared.com, tensor)
        found.append(OtherAxes(rank, corrected, float(residual), rotation, label))
    return found
