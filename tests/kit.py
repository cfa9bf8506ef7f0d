"""The shared test kit: where the repository is, and the robot texts the tests build on."""

from __future__ import annotations

import struct
from pathlib import Path

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
    import numpy as np

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
