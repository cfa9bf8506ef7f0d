"""
What the review page draws of each link: its ``<visual>`` shapes (its ``<collision>`` ones when
it has no visual) as triangle meshes in their own frames, each distinct mesh carried once, and
decimated for display when the page's triangles exceed a budget.

Primitives are tessellated by :func:`~inertia_kit.physics.tessellate.primitive_mesh`; mesh files
are read as the analysis reads them (:func:`~inertia_kit.physics.mesh_formats.read_triangles`,
the file's own unit applied), and the URDF ``scale`` goes into the shape's transform, so one file
is carried once whatever scales use it. A mesh that cannot be read is left out of the drawing
(its finding, IN030/IN034, is in the panel). Decimation (trimesh's quadric decimation, through
the ``fast-simplification`` package) changes only what is drawn, never a mass property.
"""

from __future__ import annotations

import base64
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.describe import describe_geometry
from inertia_kit.description import model
from inertia_kit.errors import MeshError
from inertia_kit.physics.frames import transform
from inertia_kit.physics.tessellate import primitive_mesh

#: default triangle budget of a page: what the file carries, each distinct mesh counted once
DEFAULT_TRIANGLE_BUDGET = 300_000
#: a mesh this small is never decimated (a box is 12 triangles)
KEPT_WHOLE = 12
#: segments around a round primitive
_SEGMENTS = 32


@dataclass
class DisplayMesh:
    """One distinct mesh: ``positions`` (n, 3) m, ``indices`` (m, 3), and what it was before."""

    name: str
    positions: NDArray[np.float64]
    indices: NDArray[np.int64]
    source_triangles: int

    @property
    def triangles(self) -> int:
        return len(self.indices)

    def to_json(self) -> dict[str, Any]:
        """The scene's mesh record: little-endian float32 positions, uint32 indices, base64."""
        positions = np.ascontiguousarray(self.positions, dtype="<f4")
        indices = np.ascontiguousarray(self.indices, dtype="<u4")
        return {
            "positions": base64.b64encode(positions.tobytes()).decode("ascii"),
            "indices": base64.b64encode(indices.tobytes()).decode("ascii"),
            "triangles": self.triangles,
            "source_triangles": self.source_triangles,
            "name": self.name,
        }


TriangleReader = Callable[[str], tuple[NDArray[np.float64], float]]


def _default_reader(path: str) -> tuple[NDArray[np.float64], float]:
    from inertia_kit.physics.mesh_formats import read_triangles

    return read_triangles(path)


class MeshTable:
    """The distinct meshes of a page, each built once: a shape names its mesh by index."""

    def __init__(self, read: TriangleReader = _default_reader):
        self.meshes: list[DisplayMesh] = []
        self._index: dict[tuple, int | None] = {}
        self._read = read

    def shape_visual(self, shape: model.Shape) -> dict[str, Any] | None:
        """
        The scene's visual record of ``shape`` (its mesh index, link → shape transform with the
        mesh scale, kind), or ``None`` when it cannot be drawn: a size, origin or scale that is
        not a number, an unknown geometry, a mesh not found or unreadable.
        """
        origin = shape.origin
        if not isinstance(origin.xyz, tuple) or not isinstance(origin.rpy, tuple):
            return None
        pose = transform(origin.xyz, origin.rpy)
        geometry = shape.geometry
        if isinstance(geometry, model.Mesh):
            scale = geometry.scale
            if geometry.path is None or not isinstance(scale, tuple) or 0.0 in scale:
                return None
            index = self._mesh(("mesh", geometry.path), lambda: self._file(geometry))
            pose = pose @ np.diag([*scale, 1.0])
            kind = "mesh"
        else:
            dims = _dimensions(geometry)
            if dims is None:
                return None
            kind = type(geometry).__name__.lower()
            index = self._mesh((kind, dims), lambda: _primitive(geometry, kind, dims))
        if index is None:
            return None
        return {"mesh": index, "transform": _flat(pose), "color": None, "kind": kind}

    def _mesh(self, key: tuple, build: Callable[[], DisplayMesh | None]) -> int | None:
        if key not in self._index:
            built = build()
            self._index[key] = None if built is None else len(self.meshes)
            if built is not None:
                self.meshes.append(built)
        return self._index[key]

    def _file(self, mesh: model.Mesh) -> DisplayMesh | None:
        try:
            triangles, unit_scale = self._read(mesh.path)  # type: ignore[arg-type]
        except MeshError:
            return None  # drawn without it: IN030/IN034 says why in the panel
        positions, indices = _indexed(triangles * unit_scale)
        name = mesh.filename.rsplit("/", 1)[-1] or mesh.filename
        return DisplayMesh(name, positions, indices, len(indices))

    def within_budget(self, budget: int = DEFAULT_TRIANGLE_BUDGET) -> bool:
        """
        Decimate the meshes, each in proportion, so the page's triangles (each distinct mesh
        once) fit ``budget``; meshes of at most :data:`KEPT_WHOLE` triangles are kept as they
        are. Whether any mesh was decimated.

        The decimation lands near each target, not on it, and meshes cut to the floor of
        :data:`KEPT_WHOLE` keep more than their share: a few more passes, each aiming a little
        lower, take the total under the budget (a page of only small meshes may stay over).
        """
        decimated = False
        for attempt in range(_PASSES):
            total = sum(m.triangles for m in self.meshes)
            small = sum(m.triangles for m in self.meshes if m.triangles <= KEPT_WHOLE)
            if total <= budget or total == small:
                break
            share = max(budget - small, 0) / (total - small) * (1.0 - 0.02 * attempt)
            for mesh in self.meshes:
                target = max(KEPT_WHOLE, int(mesh.triangles * share))
                if mesh.triangles > KEPT_WHOLE and target < mesh.triangles:
                    mesh.positions, mesh.indices = decimate(mesh.positions, mesh.indices, target)
                    decimated = True
        return decimated


#: passes of :meth:`MeshTable.within_budget` at most
_PASSES = 4


def decimate(
    positions: NDArray[np.float64], indices: NDArray[np.int64], target: int
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """
    A mesh with about ``target`` triangles (quadric decimation), for display only.

    Raises ``ImportError`` with what to install when ``fast-simplification`` is missing.
    """
    import trimesh

    try:
        import fast_simplification  # noqa: F401  # trimesh's decimation backend
    except ImportError as error:
        raise ImportError(
            "decimating meshes for display needs the fast-simplification package "
            "(pip install fast-simplification), a dependency of inertia-kit"
        ) from error
    mesh = trimesh.Trimesh(positions, indices, process=False)
    simplified = mesh.simplify_quadric_decimation(face_count=target)
    return np.asarray(simplified.vertices), np.asarray(simplified.faces, dtype=np.int64)


def _indexed(
    triangles: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """
    A triangle soup (n, 3, 3) as shared vertices (v, 3) and faces (n, 3): exact duplicates
    merged (the file's own vertices, shared by their triangles).
    """
    flat = triangles.reshape(-1, 3)
    # rows ranked one column at a time, each step a 1-D unique of int64 keys: several times
    # faster than np.unique(axis=0), which sorts rows as 24-byte records (5 s for 1M triangles)
    ids = np.zeros(len(flat), dtype=np.int64)
    for column in flat.T:
        _, rank = np.unique(column, return_inverse=True)
        _, ids = np.unique(ids * (int(rank.max()) + 1) + rank, return_inverse=True)
    # ids are dense ranks 0..v-1: any row of each rank stands for its vertex
    rows = np.empty(int(ids.max()) + 1 if len(ids) else 0, dtype=np.int64)
    rows[ids] = np.arange(len(ids))
    return flat[rows], ids.reshape(-1, 3)


def _dimensions(geometry: model.Geometry) -> tuple[float, ...] | None:
    """The primitive's sizes, when they are all positive numbers; else ``None``."""
    if isinstance(geometry, model.Box):
        values = geometry.size if isinstance(geometry.size, tuple) else None
    elif isinstance(geometry, model.Cylinder | model.Capsule):
        values = (geometry.radius, geometry.length)
    elif isinstance(geometry, model.Sphere):
        values = (geometry.radius,)
    else:
        return None
    if values is None or not all(isinstance(v, float) and v > 0 for v in values):
        return None
    return tuple(values)  # type: ignore[arg-type]


def _primitive(geometry: model.Geometry, kind: str, dims: tuple[float, ...]) -> DisplayMesh:
    points, faces = primitive_mesh(kind, dims, _SEGMENTS)
    return DisplayMesh(describe_geometry(geometry), points, faces, len(faces))


def _flat(matrix: NDArray[np.float64]) -> list[float]:
    """A 4×4 transform as 16 floats, row-major."""
    return [float(v) for v in np.asarray(matrix).ravel()]
