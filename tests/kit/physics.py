"""
Physics test helpers: random rotations, icosphere triangles, mass properties from second moments,
and comparisons (to a tolerance, and to the bit).
"""

from __future__ import annotations

import struct

import numpy as np
import pytest


def from_second_moment(mass: float, com, second_moment):
    """Mass properties from the central second moment ``∫ r rᵀ dm`` (kg·m²): tr(S)·1 − S."""
    from inertia_kit.physics.mass import MassProperties, inertia_from_second_moment

    return MassProperties(mass, com, inertia_from_second_moment(second_moment))


def random_rotation(rng: np.random.Generator) -> np.ndarray:
    """A rotation matrix (3, 3) drawn from ``rng``."""
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


def sphere_triangles(subdivisions=4, radius=0.3) -> np.ndarray:
    """An icosphere's triangles (trimesh), wound counter-clockwise seen from outside."""
    import trimesh

    return trimesh.creation.icosphere(subdivisions=subdivisions, radius=radius).triangles


def assert_mass_close(mine, reference, rtol=1e-12) -> None:
    """Mass, COM (against the body's size) and inertia (against its largest entry) agree."""
    size = max(np.abs(reference.com).max(), 1e-3)
    assert mine.mass == pytest.approx(reference.mass, rel=rtol)
    np.testing.assert_allclose(mine.com, reference.com, rtol=0, atol=rtol * size)
    scale = np.abs(reference.inertia).max()
    np.testing.assert_allclose(mine.inertia, reference.inertia, rtol=0, atol=rtol * scale)


def assert_same(x, y, name: str) -> None:
    """``x`` and ``y`` alike to the bit: type, and for arrays dtype, shape and writeability."""
    assert type(x) is type(y), name
    if isinstance(x, np.ndarray):
        assert (x.dtype, x.shape, x.flags.writeable) == (y.dtype, y.shape, y.flags.writeable), name
        assert x.tobytes() == y.tobytes(), name
    elif isinstance(x, tuple):
        assert len(x) == len(y), name
        for u, v in zip(x, y, strict=True):
            assert_same(u, v, name)
    elif isinstance(x, float):
        assert struct.pack("<d", x) == struct.pack("<d", y), (name, x, y)
    else:
        assert x == y, name
