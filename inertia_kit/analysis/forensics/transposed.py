"""
IN064: the six inertia values transcribed into the wrong attributes.

A value list in another order (MuJoCo's ``fullinertia`` is ``Ixx Iyy Izz Ixy Ixz Iyz``) or two
values swapped by hand. Undoing the slip reassigns the written values; a reassignment that keeps
the principal moments is a rotation in disguise and left to IN062.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from inertia_kit.analysis.forensics.candidate import Candidate, Case, Wording, entries
from inertia_kit.physics.formatting import tensor_text
from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.tensor_names import INDEX, TENSOR


@dataclass(frozen=True, eq=False)
class Transposed(Candidate):
    """
    The written values reassigned: attribute ``TENSOR[k]`` should hold the value written in
    ``TENSOR[order[k]]``; :attr:`moved` values change place.
    """

    CODE: ClassVar[str] = "IN064"

    order: tuple[int, ...]
    moved: int

    @property
    def preference(self) -> tuple[float, ...]:
        # fewer moved values first: the simplest transcription slip that explains the numbers
        return (self.rank, self.moved, self.residual)

    def word(self, case: Case) -> Wording:
        written, order, axes = case.written, self.order, case.axes
        values = [written[INDEX[name]] for name in TENSOR]
        assignment = {TENSOR[k]: TENSOR[order[k]] for k in range(6) if order[k] != k}
        changed = [k for k in range(6) if values[order[k]] != values[k]]
        pairs = {frozenset((k, order[k])) for k in changed}
        if len(changed) == 2 and len(pairs) == 1:
            a, b = (TENSOR[k] for k in changed)
            how = f"{a} and {b} are swapped"
        else:
            how = ", ".join(f"{TENSOR[order[k]]}'s value is in {TENSOR[k]}" for k in changed)
        summary = f"the six inertia values are in the wrong attributes: {how}"
        corrected = self.corrected.inertia
        right = corrected if not np.any(axes != np.eye(3)) else axes.T @ corrected @ axes
        names = [TENSOR[k] for k in changed]
        detail = (
            f"written {tensor_text(written, names, digits=4, separator=' ')}; reassigned, "
            f"{entries(right, names)} match the {case.geometry} {self.within}"
        )
        return Wording(summary, detail, f"write {entries(right)}", {"assignment": assignment})


def search(case: Case, tolerance: float) -> list[Transposed]:
    """Every reassignment of the six written values that fits within ``tolerance`` and is not a
    rotation."""
    written = case.written
    values = np.array([written[INDEX[name]] for name in TENSOR])
    orders = np.array(list(itertools.permutations(range(6))))
    candidates = values[orders]  # (720, 6)
    _, unique = np.unique(np.round(candidates, 15), axis=0, return_index=True)
    orders, candidates = orders[unique], candidates[unique]
    keep = ~np.all(candidates == values, axis=1)
    orders, candidates = orders[keep], candidates[keep]
    if not len(orders):
        return []
    tensors = np.empty((len(orders), 3, 3))
    for k, name in enumerate(TENSOR):
        i, j = INDEX[name]
        tensors[:, i, j] = tensors[:, j, i] = candidates[:, k]
    # a permutation with the declared eigenvalues is a rotation in disguise: IN062's
    own = np.linalg.eigvalsh(written)
    scale = np.abs(own).max()
    rotation_like = np.abs(np.linalg.eigvalsh(tensors) - own).max(axis=1) <= 1e-9 * scale
    in_link = case.axes @ tensors @ case.axes.T
    residuals = case.metric(in_link)
    found = []
    for order, tensor, residual, skip in zip(
        orders, in_link, residuals, rotation_like, strict=True
    ):
        if skip or residual > tolerance:
            continue
        moved = sum(1 for k in range(6) if values[order[k]] != values[k])
        corrected = MassProperties(case.declared.mass, case.declared.com, tensor)
        found.append(Transposed(5, corrected, float(residual), tuple(int(k) for k in order), moved))
    return found
