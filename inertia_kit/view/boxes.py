"""
The equivalent uniform box of a body's mass properties: the solid box of the same mass whose
inertia about its centre equals the body's, as Gazebo's and RViz's inertia displays draw it.

For principal moments I1 ≤ I2 ≤ I3 (about the COM) and mass m, a uniform box with sides a_i
along principal axis i has I_i = m (a_j² + a_k²) / 12, so a_i² = 6 (I_j + I_k − I_i) / m. A
term below zero (the triangle inequality broken) or a mass that is not positive gives no box.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

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
