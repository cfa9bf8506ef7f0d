"""The shared test kit: where the repository is, and the robot texts the tests build on."""

from __future__ import annotations

import struct
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parent.parent
EXAMPLES = REPO / "examples"

SHELL = """<robot name="r">
  <link name="base"/>
  <joint name="j" type="revolute">
    <parent link="base"/><child link="{name}"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
  <link name="{name}">{body}</link>{extra}
</robot>"""


def moving(body: str, name: str = "plate", extra: str = "") -> str:
    """
    A robot whose moving link ``name`` (revolute on a massless base) holds ``body``; ``extra``
    is written after that link (more joints and links).
    """
    return SHELL.format(name=name, body=body, extra=extra)


def from_second_moment(mass: float, com, second_moment):
    """Mass properties from the central second moment ``∫ r rᵀ dm`` (kg·m²): tr(S)·1 − S."""
    from inertia_kit.physics.mass import MassProperties, inertia_from_second_moment

    return MassProperties(mass, com, inertia_from_second_moment(second_moment))


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


# --- triangle soups ------------------------------------------------------------------------


def box_triangles(size=(0.5, 0.25, 2.0), low=(0.0, 0.0, 0.0)) -> np.ndarray:
    """The 12 triangles of an axis-aligned box, wound counter-clockwise seen from outside."""
    corners = np.array(low) + np.array(size) * np.array(
        [[i >> 2 & 1, i >> 1 & 1, i & 1] for i in range(8)], dtype=np.float64
    )
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    faces = [(a, b, c) for a, b, c, d in quads] + [(a, c, d) for a, b, c, d in quads]
    return corners[np.array(faces)]


def box_inertia(size, mass) -> np.ndarray:
    """The closed form: a box's inertia tensor (3, 3) about its centre, in its axes."""
    x, y, z = np.square(size)
    return mass / 12.0 * np.diag([y + z, x + z, x + y])


def sphere_triangles(subdivisions=4, radius=0.3) -> np.ndarray:
    """An icosphere's triangles (trimesh), wound counter-clockwise seen from outside."""
    import trimesh

    return trimesh.creation.icosphere(subdivisions=subdivisions, radius=radius).triangles


def random_rotation(rng: np.random.Generator) -> np.ndarray:
    """A rotation matrix (3, 3) drawn from ``rng``."""
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


def assert_mass_close(mine, reference, rtol=1e-12) -> None:
    """Mass, COM (against the body's size) and inertia (against its largest entry) agree."""
    size = max(np.abs(reference.com).max(), 1e-3)
    assert mine.mass == pytest.approx(reference.mass, rel=rtol)
    np.testing.assert_allclose(mine.com, reference.com, rtol=0, atol=rtol * size)
    scale = np.abs(reference.inertia).max()
    np.testing.assert_allclose(mine.inertia, reference.inertia, rtol=0, atol=rtol * scale)
