"""
Triangle meshes at manifold3d's door: a closed mesh taken in as shared vertices and faces
(merged by manifold3d where float noise leaves it open), meshes made into manifold3d solids,
and those solids' volume integrals.

manifold3d is imported inside the functions that use it, so importing this module stays cheap.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from inertia_kit.physics.polyhedra import integrate
from inertia_kit.physics.volume_moments import VolumeMoments

if TYPE_CHECKING:
    import manifold3d


def closed_mesh(
    vertices: ArrayLike, faces: ArrayLike | None
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """
    A closed, consistently wound mesh as float64 vertices (m, 3) and int64 faces (n, 3).

    Parameters
    ----------
    vertices : (m, 3) float, or (n, 3, 3) float when ``faces`` is None
      Vertex coordinates; without ``faces``, a triangle soup whose triangles share vertices by
      exact coordinates.
    faces : (n, 3) int, optional
      Vertex indices of each triangle, counter-clockwise seen from outside.

    Raises
    ------
    ValueError
      On bad shapes, non-finite coordinates, or a surface that is not closed even after
      manifold3d merges its open edges.
    """
    points, triangles = _indexed(vertices, faces)
    if not _closed(triangles, len(points)):
        points, triangles = _merged(points, triangles)
    return points, triangles


def as_manifold(points: NDArray[np.float64], faces: NDArray[np.int64]) -> manifold3d.Manifold:
    """A closed mesh, vertices (m, 3) m and faces (n, 3), as a manifold3d solid."""
    import manifold3d

    mesh = manifold3d.Mesh64(
        np.ascontiguousarray(points, dtype=np.float64),
        np.ascontiguousarray(faces, dtype=np.uint64),
    )
    solid = manifold3d.Manifold(mesh)
    if solid.status() != manifold3d.Error.NoError:
        raise ValueError(
            f"manifold3d rejects a part's mesh ({solid.status().name}): a solid union needs "
            "a closed, consistently wound 2-manifold surface"
        )
    return solid


def manifold_moments(
    solid: manifold3d.Manifold, origin: NDArray[np.float64] | None = None
) -> VolumeMoments:
    """
    The volume integrals of a manifold3d solid about ``origin`` (3,) m (default: near its
    surface, as :func:`~inertia_kit.physics.polyhedra.integrate` picks); zero for no solid.
    Its triangles are summed in :func:`canonical_triangles`' order.
    """
    # to_mesh64 (manifold3d ≥ 3) keeps the input's float64 vertices; to_mesh rounds to float32
    mesh = getattr(solid, "to_mesh64", solid.to_mesh)()
    points = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3]
    faces = np.asarray(mesh.tri_verts, dtype=np.intp)
    if len(faces) == 0:
        return VolumeMoments(
            0.0, np.zeros(3), np.zeros((3, 3)), np.zeros(3) if origin is None else origin
        )
    return integrate(canonical_triangles(points, faces), origin).moments


def canonical_triangles(vertices: NDArray, faces: NDArray) -> NDArray:
    """
    The (n, 3, 3) triangles of a mesh in one order, whatever order its vertices and faces came
    in: manifold3d works in parallel (a convex hull of the same points comes back as the same
    triangles in an order that changes from run to run), and summing them in another order
    changes the last bits of the volume and moments (and so of what lint reports and fill
    writes). Vertices sorted by
    (x, y, z), each face turned to start at its lowest vertex (its winding kept), faces sorted.
    """
    if not len(faces):
        return vertices[faces]
    order = np.lexsort(vertices.T[::-1])
    rank = np.empty(len(order), dtype=np.intp)
    rank[order] = np.arange(len(order))
    faces = rank[faces]
    turn = (np.argmin(faces, axis=1)[:, None] + np.arange(3)) % 3
    faces = np.take_along_axis(faces, turn, axis=1)
    faces = faces[np.lexsort(faces.T[::-1])]
    return vertices[order][faces]


def _indexed(
    vertices: ArrayLike, faces: ArrayLike | None
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """
    Coerce a mesh to float64 vertices (m, 3) and int64 faces (n, 3), checking both.

    Vertices with equal coordinates become one, as manifold3d needs shared vertices to see
    a closed surface (meshes read from STL repeat each corner once per triangle).
    """
    points = np.asarray(vertices, dtype=np.float64)
    if faces is None:
        if points.ndim != 3 or points.shape[1:] != (3, 3):
            raise ValueError(f"triangles must be (n, 3, 3), got shape {points.shape}")
        corners = points.reshape(-1, 3)
    else:
        if points.ndim != 2 or points.shape[1] != 3:
            raise ValueError(f"vertices must be (m, 3), got shape {points.shape}")
        raw = np.asarray(faces)
        if raw.ndim != 2 or raw.shape[1] != 3 or (raw.size and raw.dtype.kind not in "iu"):
            raise ValueError(f"faces must be (n, 3) integers, got {raw.dtype} {raw.shape}")
        index = raw.astype(np.int64)
        if index.size and (index.min() < 0 or index.max() >= len(points)):
            raise ValueError(f"faces index vertices 0..{len(points) - 1} out of range")
        corners = points[index].reshape(-1, 3)
    if len(corners) == 0:
        raise ValueError("mesh has no triangles")
    if not np.isfinite(corners).all():
        raise ValueError("mesh vertices must be finite")
    unique, inverse = np.unique(corners, axis=0, return_inverse=True)
    return unique, inverse.reshape(-1, 3).astype(np.int64)


def _closed(faces: NDArray[np.int64], count: int) -> bool:
    """
    Whether each directed edge of ``faces`` (n, 3), over ``count`` vertices, occurs once and
    its reverse once: a closed, consistently wound surface with two faces at every edge.
    """
    edges = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    forward = np.sort(edges[:, 0] * count + edges[:, 1])
    backward = np.sort(edges[:, 1] * count + edges[:, 0])
    return bool(np.all(forward[1:] != forward[:-1]) and np.array_equal(forward, backward))


def _merged(
    points: NDArray[np.float64], faces: NDArray[np.int64]
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Let manifold3d merge near-coincident vertices of an open mesh, or raise ``ValueError``."""
    import manifold3d

    mesh = manifold3d.Mesh64(
        np.ascontiguousarray(points), np.ascontiguousarray(faces, dtype=np.uint64)
    )
    mesh.merge()
    solid = manifold3d.Manifold(mesh)
    if solid.status() != manifold3d.Error.NoError or solid.is_empty():
        raise ValueError(
            "mesh is not a closed, consistently wound surface (manifold3d: "
            f"{solid.status().name}); a solid union needs a watertight mesh"
        )
    out = solid.to_mesh64()
    return (
        np.asarray(out.vert_properties, dtype=np.float64)[:, :3].copy(),
        np.asarray(out.tri_verts, dtype=np.int64),
    )
