"""
inertia-kit: physically right mass properties for URDF and xacro robot descriptions.

The public API is imported on first use, so that ``import inertia_kit`` (and every command-line
run) pays only for what it touches.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from inertia_kit.version import __version__

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
