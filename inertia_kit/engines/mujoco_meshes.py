"""
The mass properties MuJoCo gives a mesh geom, by its mesh inertia mode (``<mesh inertia>``:
``convex``, ``exact``, ``legacy``, ``shell``).

MuJoCo 4.0's default is ``legacy`` (``mjMESH_INERTIA_LEGACY``, the default of a new mesh in
``mujoco.MjSpec``), and a URDF cannot ask for another: the ``<mujoco><compiler .../></mujoco>``
extension element is read (``boundmass`` there takes effect) but the compiler has no mesh
inertia attribute (``exactmeshinertia`` is gone and is ignored), and a ``<default>`` there is
not read. Checked against mujoco 4.0.0 (``tests/engines/test_mujoco_meshes.py``).

``legacy`` (``user_mesh.cc``) takes every triangle's tetrahedron with a reference point at its
*absolute* volume, so a non-convex mesh, whose tetrahedra from an inside point partly cancel
in the exact sum, counts some volume twice or more: the L of two 0.1 m bars has 5.32e-3 m³
instead of 5.0e-3 (+6 %); issue 20 measured +3 % (Spot's lower legs) to +27 % (Fanuc `link_2`).
In two passes: the centre is the absolute-volume-weighted centroid of the tetrahedra from the
area-weighted centroid of the faces; volume and second moment are then summed again from that
centre (their own centroid is not used: the tensor is taken about the first centre). A convex
mesh gives its exact values (every tetrahedron from an inside point is positive).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.geometry import Solid
from inertia_kit.errors import MeshError
from inertia_kit.physics.frames import transform
from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.mesh_formats import read_triangles

#: MuJoCo 4.0's default ``<mesh inertia>``, and the only one a URDF gets
DEFAULT_MESH_INERTIA = "legacy"


def _tetrahedra(triangles: NDArray, centre: NDArray) -> tuple[NDArray, NDArray]:
    """Absolute volumes (n,) of the tetrahedra from ``centre``; their vertices relative to it."""
    r = triangles - centre
    det = np.einsum("ij,ij->i", r[:, 0], np.cross(r[:, 1], r[:, 2]))
    return np.abs(det) / 6.0, r


def legacy_unit(triangles: NDArray) -> MassProperties | None:
    """
    What MuJoCo's ``legacy`` mesh inertia gives the mesh ``triangles`` (n, 3, 3) m (scaled
    and placed in the mesh's frame) at 1 kg/m³: ``mass`` is its volume; ``None`` for no volume.
    """
    t = np.asarray(triangles, dtype=np.float64)
    area = np.linalg.norm(np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]), axis=1) / 2.0
    if not len(t) or not area.sum() > 0:
        return None
    faces = (area[:, None] * t.mean(axis=1)).sum(axis=0) / area.sum()
    volumes, r = _tetrahedra(t, faces)
    if not volumes.sum() > 0:
        return None
    centre = faces + (volumes[:, None] * r.sum(axis=1)).sum(axis=0) / (4.0 * volumes.sum())
    volumes, r = _tetrahedra(t, centre)
    s = r.sum(axis=1)
    # a tetrahedron (0, a, b, c) of volume V: ∫ x xᵀ = V/20 (a aᵀ + b bᵀ + c cᵀ + s sᵀ)
    second = np.einsum("n,nki,nkj->ij", volumes / 20.0, r, r) + np.einsum(
        "n,ni,nj->ij", volumes / 20.0, s, s
    )
    inertia = np.trace(second) * np.eye(3) - second
    return MassProperties(float(volumes.sum()), centre, inertia)


def mesh_unit(solid: Solid) -> MassProperties | None:
    """
    A mesh solid of a link as MuJoCo's default mesh inertia gives it, at 1 kg/m³ in the link
    frame: its triangles read again, scaled and placed as the URDF says; ``None`` when they
    cannot be read (the caller keeps the exact integrals then, and says so by the mode).
    """
    mesh = solid.mesh
    origin = solid.shape.origin
    if mesh is None or not isinstance(origin.xyz, tuple) or not isinstance(origin.rpy, tuple):
        return None
    try:
        triangles, unit = read_triangles(mesh.path)
    except (MeshError, OSError, ValueError):
        return None
    with np.errstate(all="ignore"):
        scaled = triangles * (unit * np.asarray(mesh.scale, dtype=np.float64))
        value = legacy_unit(scaled)
        if value is None or not np.isfinite(value.mass):
            return None
        return value.transformed(transform(origin.xyz, origin.rpy))
