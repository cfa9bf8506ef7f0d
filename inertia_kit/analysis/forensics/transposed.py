"""
IN064: the six inertia values transcribed into the wrong attributes.

A value list in another order (MuJoCo's ``fullinertia`` is ``Ixx Iyy Izz Ixy Ixz Iyz``) or two
values swapped by hand. Undoing the slip reassigns the written values; a reassignment that keeps
the principal moments is a rotation in disguise and left to IN062.
"""

from __future__ import annotations

import functools
import itertools
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.forensics.candidate import Candidate, Case, Wording, entries
from inertia_kit.analysis.forensics.measure import BOUND_MARGIN
from inertia_kit.physics.formatting import fmt, tensor_text
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
            # the message: the pair and what is written in each
            written_pair = ", ".join(f"{TENSOR[k]} {fmt(values[k], 3)}" for k in changed)
            claim = f"{how} (written {written_pair})"
        else:
            how = ", ".join(f"{TENSOR[order[k]]}'s value is in {TENSOR[k]}" for k in changed)
            claim = "inertia values in the wrong attributes: " + ", ".join(
                TENSOR[k] for k in changed
            )
        summary = f"the six inertia values are in the wrong attributes: {how}"
        corrected = self.corrected.inertia
        right = corrected if not np.any(axes != np.eye(3)) else axes.T @ corrected @ axes
        names = [TENSOR[k] for k in changed]
        detail = (
            f"written {tensor_text(written, names, digits=4, separator=' ')}; reassigned, "
            f"{entries(right, names)} match the {case.geometry} {self.within}"
        )
        help = f"write {entries(right)}"
        return Wording(summary, detail, help, {"assignment": assignment}, claim)


#: every order of the six values, in itertools' order (the first of equal reassignments wins)
ORDERS = np.array(list(itertools.permutations(range(6))))
#: base-6 place values: a row of six ranks in 0..5 as one integer, in lexicographic order
_PLACES = 6 ** np.arange(5, -1, -1)


def distinct_orders(values: NDArray[np.float64]) -> NDArray[np.intp]:
    """
    The indices into :data:`ORDERS` of the distinct reassignments of ``values``.

    Reassignments that give the same values (rounded to 15 decimals: a tie written twice is one
    value) count once, by the first order giving them; the result is sorted by the reassigned
    values, lexicographically. This is ``np.unique(np.round(values[ORDERS], 15), axis=0,
    return_index=True)[1]``, computed on integers: each value replaced by its rank among the
    distinct rounded values. Ranks keep the order and the ties of the values (``-0.0`` ties
    with ``0.0`` in both), so the result depends on the ranks alone, and is computed once for
    each pattern of ranks (at most 4683 for six values: most tensors have a few).

    Parameters
    ----------
    values : (6,) float
      The six written values, in URDF's attribute order.

    Returns
    -------
    indices : (k,) int, read-only
      Rows of :data:`ORDERS`, 1 ≤ k ≤ 720.
    """
    _, ranks = np.unique(np.round(values, 15), return_inverse=True)
    return _distinct_orders_of_ranks(tuple(int(r) for r in ranks.reshape(-1)))


@functools.cache
def _distinct_orders_of_ranks(ranks: tuple[int, ...]) -> NDArray[np.intp]:
    """:func:`distinct_orders` of values with these ranks (0 the least), one per value."""
    # each row of ranks read as one base-6 number: integers in the rows' lexicographic order
    codes = np.array(ranks)[ORDERS] @ _PLACES
    # return_index on a 1-D array sorts stably: the first order of each code
    first = np.unique(codes, return_index=True)[1]
    first.flags.writeable = False  # shared by every call with these ranks
    return first


def _tensors(rows: NDArray[np.float64]) -> NDArray[np.float64]:
    """(n, 3, 3) symmetric tensors from (n, 6) values in URDF's attribute order."""
    tensors = np.empty((len(rows), 3, 3))
    for k, name in enumerate(TENSOR):
        i, j = INDEX[name]
        tensors[:, i, j] = tensors[:, j, i] = rows[:, k]
    return tensors


def search(case: Case, tolerance: float) -> list[Transposed]:
    """Every reassignment of the six written values that fits within ``tolerance`` and is not a
    rotation."""
    written = case.written
    values = np.array([written[INDEX[name]] for name in TENSOR])
    if np.abs(values).max() > case.metric.reach(tolerance):
        return []  # every candidate holds each value, in axes turned by at most a rotation
    orders = ORDERS[distinct_orders(values)]
    candidates = values[orders]  # (k, 6)
    keep = ~np.all(candidates == values, axis=1)
    orders, candidates = orders[keep], candidates[keep]
    if not len(orders):
        return []
    in_link = case.axes @ _tensors(candidates) @ case.axes.T
    # only the fits can be chosen: the rest need no eigenvalues nor a MassProperties. Most
    # reassignments put a wrong value on the diagonal, which the cheap bound catches ("not
    # above", as the choice reads it: a NaN is kept, and never chosen)
    bounds = case.metric.lower_bound(in_link)
    maybe = np.flatnonzero(~(bounds > tolerance * (1.0 + BOUND_MARGIN)))
    scored = case.metric(in_link[maybe])
    within = ~(scored > tolerance)
    fits, residuals = maybe[within], scored[within]
    if not len(fits):
        return []
    # a permutation with the declared eigenvalues is a rotation in disguise: IN062's
    own = np.linalg.eigvalsh(written)
    scale = np.abs(own).max()
    moments = np.linalg.eigvalsh(_tensors(candidates[fits]))
    rotation_like = np.abs(moments - own).max(axis=1) <= 1e-9 * scale
    found = []
    for index, residual, skip in zip(fits, residuals, rotation_like, strict=True):
        if skip:
            continue
        order = orders[index]
        moved = sum(1 for k in range(6) if values[order[k]] != values[k])
        corrected = MassProperties(case.declared.mass, case.declared.com, in_link[index])
        found.append(Transposed(5, corrected, float(residual), tuple(int(k) for k in order), moved))
    return found
