"""
The mass properties MuJoCo gives a mesh geom of a link, by its mesh inertia mode (``<mesh
inertia>``: ``convex``, ``exact``, ``legacy``, ``shell``), computed by
:mod:`inertia_kit.physics.mujoco_mesh_inertia` from the mesh file's triangles.

MuJoCo 4.0's default is ``legacy`` (``mjMESH_INERTIA_LEGACY``, the default of a new mesh in
``mujoco.MjSpec``), and a URDF cannot ask for another: the ``<mujoco><compiler .../></mujoco>``
extension element is read (``boundmass`` there takes effect) but the compiler has no mesh
inertia attribute (``exactmeshinertia`` is gone and is ignored), and a ``<default>`` there is
not read. An MJCF ``<mesh>`` names its own. Checked against mujoco 4.0.0
(``tests/engines/test_mujoco_meshes.py``).

``legacy`` takes every face's pyramid at its *absolute* volume, so a non-convex mesh, whose
pyramids from an inside point partly cancel in the exact sum, counts some volume twice or
more: the L of two 0.1 m bars has 5.32e-3 m³ instead of 5.0e-3 (+6 %); issue 20 measured +3 %
(Spot's lower legs) to +27 % (Fanuc `link_2`). A convex mesh gives its exact values.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.geometry import Solid
from inertia_kit.errors import MeshError
from inertia_kit.physics.frames import transform
from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.mesh_formats import read_triangles
from inertia_kit.physics.mujoco_mesh_inertia import mesh_mass_properties

#: MuJoCo 4.0's default ``<mesh inertia>``, and the only one a URDF gets
DEFAULT_MESH_INERTIA = "legacy"


def indexed(triangles: NDArray) -> tuple[NDArray, NDArray]:
    """
    ``(vertices, faces)`` of a triangle soup (n, 3, 3), vertices shared by their exact float32
    bits as MuJoCo's STL decoder shares them (so that ``exact``'s winding check sees the
    mesh's edges).
    """
    flat = np.asarray(triangles, dtype=np.float64).reshape(-1, 3)
    keys = np.ascontiguousarray(flat.astype(np.float32)).view(np.uint32).reshape(-1, 3)
    _, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    return flat[first], inverse.reshape(-1, 3)


def mode_unit(triangles: NDArray, mode: str, scale=(1.0, 1.0, 1.0)) -> MassProperties | None:
    """
    What MuJoCo's mesh inertia ``mode`` gives the file's ``triangles`` (n, 3, 3) at ``scale``
    at 1 kg/m³ (kg/m² for ``shell``), in the mesh's frame: ``mass`` is its volume (area);
    ``None`` for a mesh MuJoCo refuses (no volume, inconsistent winding for ``exact``).
    """
    vertices, faces = indexed(triangles)
    try:
        with np.errstate(all="ignore"):
            value = mesh_mass_properties(vertices, faces, mode, density=1.0, scale=scale)
    except ValueError:
        return None
    return value if np.isfinite(value.mass) and value.mass > 0 else None


def mesh_unit(solid: Solid, mode: str = DEFAULT_MESH_INERTIA) -> MassProperties | None:
    """
    A mesh solid of a link as MuJoCo's mesh inertia ``mode`` gives it, at 1 kg/m³ in the link
    frame: its triangles read again, scaled and placed as the description says; ``None`` when
    they cannot be read or MuJoCo refuses the mesh (the caller says so).
    """
    mesh = solid.mesh
    origin = solid.shape.origin
    if mesh is None or not isinstance(origin.xyz, tuple) or not isinstance(origin.rpy, tuple):
        return None
    try:
        triangles, unit = read_triangles(mesh.path)
    except (MeshError, OSError, ValueError):
        return None
    value = mode_unit(triangles, mode, unit * np.asarray(mesh.scale, dtype=np.float64))
    return None if value is None else value.transformed(transform(origin.xyz, origin.rpy))
