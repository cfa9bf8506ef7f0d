"""
inertia-kit: physically right mass properties for URDF and xacro robot descriptions.

The public API is imported on first use, so that ``import inertia_kit`` (and every command-line
run) pays only for what it touches.
"""

from __future__ import annotations

import _signal  # builtin, loaded: `signal` builds enums first, 10 ms a Ctrl-C can land in
import os
import sys


def _interrupted(signum: int, frame: object) -> None:
    os.write(2, b"interrupted\n")
    os._exit(130)


# Ctrl-C while a console script still imports its command (~0.6 s on a cold machine): its guard
# (cli/guard.py) does not exist yet, and Python would print a traceback. In a console script
# (not a program that imports the package) answer as the guard does, until it restores Python's
# handler; first thing, before any import that reads a file
if os.path.basename(sys.argv[0]) in ("inertia-lint", "inertia-fill", "inertia-kit") and (
    _signal.getsignal(_signal.SIGINT) is _signal.default_int_handler
):
    _signal.signal(_signal.SIGINT, _interrupted)

import importlib  # noqa: E402
from typing import TYPE_CHECKING, Any  # noqa: E402

from inertia_kit.version import __version__  # noqa: E402

_EXPORTS = {
    "MassProperties": "inertia_kit.physics.mass",
    "Validity": "inertia_kit.physics.mass",
    "box": "inertia_kit.physics.primitives",
    "cylinder": "inertia_kit.physics.primitives",
    "sphere": "inertia_kit.physics.primitives",
    "capsule": "inertia_kit.physics.primitives",
    "ellipsoid": "inertia_kit.physics.primitives",
    "mesh": "inertia_kit.physics.meshes",
    "mesh_solid": "inertia_kit.physics.meshes",
    "MeshSolid": "inertia_kit.physics.meshes",
    "MeshMassProperties": "inertia_kit.physics.meshes",
    "Part": "inertia_kit.physics.unions",
    "union": "inertia_kit.physics.unions",
    "UnionResult": "inertia_kit.physics.unions",
    "load": "inertia_kit.description.loader",
    "XacroLimits": "inertia_kit.description.xacro_limits",
    "InputError": "inertia_kit.errors",
    "MeshError": "inertia_kit.errors",
}

__all__ = [  # noqa: RUF022  (grouped as _EXPORTS, not sorted)
    "MassProperties",
    "Validity",
    "box",
    "cylinder",
    "sphere",
    "capsule",
    "ellipsoid",
    "mesh",
    "mesh_solid",
    "MeshSolid",
    "MeshMassProperties",
    "Part",
    "union",
    "UnionResult",
    "load",
    "XacroLimits",
    "InputError",
    "MeshError",
    "__version__",
]

if TYPE_CHECKING:
    from inertia_kit.description.loader import load
    from inertia_kit.description.xacro_limits import XacroLimits
    from inertia_kit.errors import InputError, MeshError
    from inertia_kit.physics.mass import MassProperties, Validity
    from inertia_kit.physics.meshes import MeshMassProperties, MeshSolid, mesh, mesh_solid
    from inertia_kit.physics.primitives import box, capsule, cylinder, ellipsoid, sphere
    from inertia_kit.physics.unions import Part, UnionResult, union


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'inertia_kit' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(__all__)
