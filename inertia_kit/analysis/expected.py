"""
The values a link's ``<inertia>`` should hold, as the file writes them: the geometry's tensor
for a mass, re-expressed in the axes of ``<inertial><origin rpy>``, as the six URDF values
(a finding's ``expected``) and as message text.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, NamedTuple

import numpy as np
from numpy.typing import NDArray

from inertia_kit.description import model
from inertia_kit.physics.formatting import fmt, tensor_text
from inertia_kit.physics.frames import rpy_matrix
from inertia_kit.physics.tensor_names import INDEX, TENSOR

if TYPE_CHECKING:
    from inertia_kit.analysis.geometry import Geometry
    from inertia_kit.analysis.links import LinkAnalysis


def _written_axes(
    inertial: model.Inertial | None, inertia: NDArray[np.float64]
) -> tuple[NDArray[np.float64], str]:
    """
    A link-frame tensor re-expressed in the axes the ``<inertia>`` values are written in (those
    of ``<inertial><origin rpy>``), so that its six values can replace the declared ones; with
    the words that say so (empty for rpy = 0).
    """
    rpy = (0.0, 0.0, 0.0) if inertial is None else inertial.origin.rpy
    if not isinstance(rpy, tuple) or not any(rpy):
        return inertia, ""
    rotation = rpy_matrix(rpy)
    return rotation.T @ inertia @ rotation, " in the axes of its `<inertial><origin rpy>`"


def tensor_fields(inertia: NDArray[np.float64]) -> dict[str, float]:
    """The six URDF values of a (3, 3) tensor, kg·m², JSON-ready."""
    return {name: float(inertia[INDEX[name]]) for name in TENSOR}


class WrittenTensor(NamedTuple):
    """A tensor in the axes its ``<inertia>`` is written in."""

    fields: dict[str, float]  # the six URDF values, kg·m², JSON-ready (a finding's ``expected``)
    tensor: NDArray[np.float64]  # (3, 3) kg·m²
    axes: str  # " in the axes of its `<inertial><origin rpy>`", or "" for the link axes

    def text(self, names: Sequence[str] | None = None) -> str:
        """``ixx = 0.0163, iyy = 0.0163, izz = 0.0025 kg·m²`` (or the ``names`` entries only),
        and the axes they are in."""
        return f"{tensor_text(self.tensor, names)} kg·m²{self.axes}"


def geometry_tensor(link: LinkAnalysis, mass: float) -> WrittenTensor | None:
    """
    The link geometry's tensor for ``mass`` at uniform density, in the axes the link's
    ``<inertia>`` is written in; ``None`` when its geometry has no usable volume.
    """
    return _written_tensor(link, link.geometry, mass)


def base_tensors(link: LinkAnalysis, mass: float) -> list[WrittenTensor]:
    """:func:`geometry_tensor` for each of the link's geometries (``LinkAnalysis.bases``)."""
    found = (_written_tensor(link, geometry, mass) for geometry in link.bases)
    return [written for written in found if written is not None]


def _written_tensor(link: LinkAnalysis, geometry: Geometry, mass: float) -> WrittenTensor | None:
    body = geometry.at_mass(mass)
    if body is None:
        return None
    inertia, axes = _written_axes(link.link.inertial, body.inertia)
    return WrittenTensor(tensor_fields(inertia), inertia, axes)


def basis_text(link: LinkAnalysis, mass: float) -> str:
    """``its collision box (0.4 × 0.4 × 0.1 m) with the declared 2 kg gives``: what introduces
    the geometry's values in a message."""
    return f"its {link.geometry.describe()} with the declared {fmt(mass)} kg gives"
