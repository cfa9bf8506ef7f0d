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

from inertia_kit.analysis.geometry import Solid
from inertia_kit.physics.frames import transform
from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.mujoco_mesh_inertia import file_mass_properties

#: MuJoCo 4.0's default ``<mesh inertia>``, and the only one a URDF gets
DEFAULT_MESH_INERTIA = "legacy"


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
    value = file_mass_properties(mesh.path, mode, mesh.scale)
    return None if value is None else value.transformed(transform(origin.xyz, origin.rpy))
