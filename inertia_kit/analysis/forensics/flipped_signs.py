"""
IN061: the products of inertia are written with the opposite sign.

URDF and SDFormat write ``ixy = -∫xy dm``; a CAD report or a formula that uses ``+∫xy dm`` (or
values copied from a mirror-image part) gives the products the other sign. Undoing the slip
negates the three written products, in the axes they are written in.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.forensics.candidate import Candidate, Case, Wording, entries
from inertia_kit.physics.formatting import NEGLIGIBLE_PRODUCT, fmt
from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.tensor_names import INDEX, PRODUCTS


@dataclass(frozen=True, eq=False)
class FlippedSigns(Candidate):
    """The written products negated."""

    CODE: ClassVar[str] = "IN061"

    def word(self, case: Case) -> Wording:
        written = case.written
        right = case.axes.T @ case.expected.inertia @ case.axes
        scale = np.abs(np.diag(written)).max()
        # the products either tensor has
        names = [
            n
            for n in PRODUCTS
            if max(abs(written[INDEX[n]]), abs(right[INDEX[n]])) > NEGLIGIBLE_PRODUCT * scale
        ]
        summary = (
            "the products of inertia have the opposite sign: written as +∫xy dm (or copied "
            "from a mirror-image part), where URDF's convention is ixy = -∫xy dm"
        )
        detail = (
            f"written {entries(written, names)}; the {case.geometry} gives "
            f"{entries(right, names)} (negated, they match {self.within})"
        )
        # the message: the largest written product against the geometry's
        name = max(names or PRODUCTS, key=lambda n: abs(written[INDEX[n]]))
        value, geometry = written[INDEX[name]], right[INDEX[name]]
        claim = f"product signs flipped: {name} {fmt(value, 3)}, geometry {fmt(geometry, 3)}"
        return Wording(summary, detail, "negate ixy, ixz and iyz", claim=claim)


def _flip_products(written: NDArray[np.float64]) -> NDArray[np.float64]:
    return 2.0 * np.diag(np.diag(written)) - written


def search(case: Case) -> list[FlippedSigns]:
    """The declared tensor with its written products negated (none without products)."""
    written = case.written
    products = np.abs(written[np.triu_indices(3, 1)])
    if not products.max() > 1e-9 * np.abs(np.diag(written)).max():
        return []  # no products: flipping them changes nothing
    inertia = case.axes @ _flip_products(written) @ case.axes.T
    corrected = MassProperties(case.declared.mass, case.declared.com, inertia)
    return [FlippedSigns(1, corrected, float(case.metric(inertia)))]
