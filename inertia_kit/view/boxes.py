"""
The equivalent uniform box of a body's mass properties: the solid box of the same mass whose
inertia about its centre equals the body's, as Gazebo's and RViz's inertia displays draw it.

For principal moments I1 ≤ I2 ≤ I3 (about the COM) and mass m, a uniform box with sides a_i
along principal axis i has I_i = m (a_j² + a_k²) / 12, so a_i² = 6 (I_j + I_k − I_i) / m. A
term below zero (the triangle inequality broken) or a mass that is not positive gives no box.

:func:`principal_directions` names the link axis each principal axis lies along, for the panel.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.tensors import axis_name
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.mass import TRIANGLE_RTOL, MassProperties


@dataclass(frozen=True, eq=False)
class EquivalentBox:
    """
    A body's principal frame and its equivalent box.

    Attributes
    ----------
    moments : (3,) float
      Principal moments about the COM, ascending, kg·m².
    axes : (3, 3) float
      Right-handed rotation whose columns are the principal axes, in moment order.
    sizes : (3,) float or None
      Full sides of the box along ``axes``' columns, m; ``None`` when there is no box.
    problem : str or None
      Why there is no box.
    """

    moments: NDArray[np.float64]
    axes: NDArray[np.float64]
    sizes: NDArray[np.float64] | None
    problem: str | None


def equivalent_box(body: MassProperties) -> EquivalentBox:
    """The principal frame of ``body`` and its equivalent uniform box (see the module)."""
    values = np.concatenate([[body.mass], body.com, body.inertia.ravel()])
    if not np.isfinite(values).all():
        return EquivalentBox(
            np.full(3, np.nan), np.eye(3), None, "a value is not finite: no equivalent box"
        )
    moments, axes = body.principal_moments, body.principal_axes
    if not body.mass > 0:
        return EquivalentBox(
            moments, axes, None, f"mass {fmt(body.mass)} kg is not positive: no equivalent box"
        )
    # a_i² = 6 (I_j + I_k − I_i) / m = 6 (trace − 2 I_i) / m
    squares = 6.0 * (moments.sum() - 2.0 * moments) / body.mass
    # a flat plate has I1 + I2 = I3 exactly: rounding may leave its thickness a hair below zero
    slack = TRIANGLE_RTOL * 6.0 * moments.sum() / body.mass
    if not (squares >= -slack).all():
        low, mid, high = moments
        return EquivalentBox(
            moments,
            axes,
            None,
            f"principal moments ({fmt(low)}, {fmt(mid)}, {fmt(high)}) kg·m² break the triangle "
            f"inequality ({fmt(low)} + {fmt(mid)} < {fmt(high)}): no uniform box, or any body, "
            "has them",
        )
    return EquivalentBox(moments, axes, np.sqrt(np.maximum(squares, 0.0)), None)


#: principal moments closer than this fraction of the largest are one repeated moment: any axis
#: of their plane is principal (a cylinder's two moments across it, rounded differently)
REPEATED_RTOL = 1e-6


def principal_directions(box: EquivalentBox) -> list[str | None]:
    """
    What each principal axis of ``box`` lies along, in moment order: ``"x"``, ``"y"`` or
    ``"z"`` for a link axis (either sense), else the unit direction as ``"(0.866, 0.5, 0)"``
    (its largest component positive); ``None`` for moments that are not finite.

    A repeated moment has no one axis: any axis of its plane is principal. When the plane is
    that of two link axes (the third moment along the third), those two name it, so that a
    cylinder along x reads ``x``, ``y``, ``z`` whatever directions its rounding gave the
    eigenvectors; three equal moments read ``x``, ``y``, ``z``.
    """
    moments, axes = box.moments, box.axes
    if not np.isfinite(moments).all():
        return [None, None, None]
    names: list[str | None] = [axis_name(axes[:, i]) for i in range(3)]
    scale = float(np.abs(moments).max())
    low, mid, high = moments
    repeated = [mid - low <= REPEATED_RTOL * scale, high - mid <= REPEATED_RTOL * scale]
    if all(repeated):
        return ["x", "y", "z"]
    if any(repeated):
        single = 2 if repeated[0] else 0
        pair = [i for i in range(3) if i != single]
        if names[single] is not None:
            rest = [name for name in "xyz" if name != names[single]]
            for i, name in zip(pair, rest, strict=True):
                names[i] = name
    return [name if name is not None else _direction(axes[:, i]) for i, name in enumerate(names)]


def _direction(axis: NDArray[np.float64]) -> str:
    """
    A unit direction, its largest component positive (the first of equal ones, whatever the
    rounding): ``(0.866, 0.5, 0)``, ``(0.707, -0.707, 0)``.
    """
    size = np.abs(axis)
    first = int(np.argmax(size >= size.max() - 1e-9))
    if axis[first] < 0:
        axis = -axis
    return "(" + ", ".join(fmt(v, 3) for v in axis) + ")"
