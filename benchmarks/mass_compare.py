"""How far our mass properties are from a reference's (trimesh's), for the mesh benchmarks."""

from __future__ import annotations

import numpy as np


def difference(mine, reference, size: float) -> float:
    """Largest relative difference: mass, COM against the body's size, inertia against its
    largest entry. ``reference`` is ``(mass, com, inertia)``."""
    mass, com, inertia = reference
    return max(
        abs(mine.mass - mass) / abs(mass),
        float(np.abs(mine.com - com).max()) / size,
        float(np.abs(mine.inertia - inertia).max()) / float(np.abs(inertia).max()),
    )
