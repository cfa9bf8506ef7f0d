"""
What every hypothesis produces: a candidate correction of the declared values, how well it
fits the geometry, and the words that say what went wrong.

A hypothesis module defines its :class:`Candidate` subclass (its code, its parameters and its
:meth:`~Candidate.word`) next to the ``search`` that makes them from a :class:`Case`.
"""

from __future__ import annotations

import functools
from abc import ABC, abstractmethod
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.forensics.measure import Metric
from inertia_kit.physics.formatting import NEGLIGIBLE_PRODUCT, fmt, tensor_text
from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.tensor_names import DIAGONAL, INDEX, TENSOR


@dataclass(frozen=True, eq=False)
class Case:
    """One declared value tested against one geometry-derived value."""

    declared: MassProperties  # link frame: tensor in link axes, about the declared COM
    expected: MassProperties  # the geometry's for the declared mass, link frame
    axes: NDArray[np.float64]  # (3, 3) the axes the six values are written in, as columns
    metric: Metric  # deviation from the geometry's tensor
    geometry: str  # how messages name the geometry

    @functools.cached_property
    def written(self) -> NDArray[np.float64]:
        """The declared tensor as written, in :attr:`axes` (what a transcription slip touches)."""
        return self.axes.T @ self.declared.inertia @ self.axes


#: a finding's one-line message keeps its fuller wording up to this many characters, the link's
#: name included (issue 21, item 5: about 100, at most 120); beyond it, its brief wording
MESSAGE_BUDGET = 100


def one_line(head: str, claim: str, brief: str = "") -> str:
    """``head + claim``, or ``head + brief`` when that is beyond :data:`MESSAGE_BUDGET` (a long
    link or joint name) and a brief wording is given."""
    message = head + claim
    return head + brief if brief and len(message) > MESSAGE_BUDGET else message


class Label(str):
    """
    The name of a point or a frame as a finding's detail says it (``the origin of joint `j2```),
    with :attr:`short`, as its one-line message says it (``joint `j2`'s origin``), and
    :attr:`brief`, without the name a long one would not fit (``a child joint's origin``; ""
    when there is none). Plain text everywhere else (JSON, comparisons); a plain ``str`` label
    is its own short form.
    """

    short: str
    brief: str

    def __new__(cls, text: str, short: str, brief: str = "") -> Label:
        label = super().__new__(cls, text)
        label.short, label.brief = short, brief
        return label

    def __getnewargs__(self) -> tuple[str, str, str]:  # type: ignore[override]
        return str(self), self.short, self.brief


def short_label(label: str) -> str:
    """How a one-line message names ``label`` (:class:`Label`)."""
    return getattr(label, "short", label)


def brief_label(label: str) -> str:
    """How a one-line message names ``label`` when its name does not fit; "" if it cannot."""
    return getattr(label, "brief", "")


@dataclass(frozen=True)
class Wording:
    """What a finding says about a diagnosis (pieces of a message, without the link name)."""

    summary: str  # one clause: what went wrong
    detail: str  # the numbers that show it
    help: str  # what to write instead
    data: dict[str, Any] = field(default_factory=dict)  # the hypothesis's parameters, JSON-ready
    #: the one-line message's claim and its key numbers (``inertia written in the collision
    #: cylinder's axes, not the link's``); ``summary: detail`` is the finding's detail
    claim: str = ""
    #: a shorter claim for when the link's name makes :attr:`claim` too long (:func:`one_line`)
    brief: str = ""


@dataclass(frozen=True, eq=False)
class Candidate(ABC):
    """A slip undone: the corrected values and their deviation from the geometry."""

    CODE: ClassVar[str]  # the forensic rule that reports this hypothesis

    rank: int  # lower: fewer free parameters, preferred among near-equal fits
    corrected: MassProperties  # link frame, tensor in link axes about the declared COM
    residual: float  # deviation of the corrected tensor from the geometry's

    @property
    def preference(self) -> tuple[float, ...]:
        """Sort key among near-equal fits: the simplest explanation first."""
        return (self.rank, 0, self.residual)

    @property
    def within(self) -> str:
        """``within 0.37 %``: how closely the corrected tensor matches the geometry's."""
        return f"within {fmt(max(self.residual * 100, 0.01), 2)} %"

    @abstractmethod
    def word(self, case: Case) -> Wording:
        """What this slip is, in words and numbers, for the case it was found in."""


def entries(tensor: NDArray[np.float64], names: Sequence[str] | None = None) -> str:
    """
    ``ixx 0.0002, iyy 0.0076, izz 0.0076``: the named entries, else the moments and the products
    that are not negligible, in URDF's attribute order (how the values to write are listed).
    """
    if names is None:
        scale = np.abs(np.diag(tensor)).max()
        names = [
            n for n in TENSOR if n in DIAGONAL or abs(tensor[INDEX[n]]) > NEGLIGIBLE_PRODUCT * scale
        ]
    return tensor_text(tensor, names, digits=5, separator=" ")
