"""
How the solid a mesh's surface bounds is found, and so how its volume integrals are obtained
(``method``):

``exact``
  The surface is closed and consistently wound (directly, or once vertices that differ only by
  float noise are welded: :data:`WELD_RTOLS`). A surface wound inside-out has a negative
  volume: it is reported as ``inverted`` and integrated flipped.
``repaired``
  Closed, but some triangles were wound against their neighbours; trimesh's winding repair
  made it consistent.
``convex-hull``
  An open surface bounds no solid; the mass properties are those of its convex hull, and
  ``volume_error`` bounds how far that is from the open surface's own volume.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from inertia_kit.errors import MeshError
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.manifolds import manifold_moments
from inertia_kit.physics.polyhedra import SurfaceIntegrator, integrate
from inertia_kit.physics.volume_moments import VolumeMoments

Method = Literal["exact", "repaired", "convex-hull"]

# |volume| below this fraction of the bounding box's largest extent cubed is no solid at all:
# far above the rounding of the volume sum, far below any real part (a 1 m plate 1 µm thick
# is 1e-6)
EMPTY_VOLUME_RTOL = 1e-12

# vertices closer than these fractions of the mesh's extent are one corner written twice, and
# are welded before the trimesh checks: float noise, not geometry. The finer tolerance first;
# the coarser only when the finer leaves the surface open, and only if it then closes it.
# STL stores float32 (24 bits, a step of 6e-8 of the coordinate), and exporters round a corner
# shared by two bodies' faces differently: Fetch's laser_link.STL has two copies of a corner one
# float32 step (9.3e-10 m) apart in a 0.075 m part, 1.2e-8 of its extent. Rounding to decimal
# digits cannot weld them when the two fall on either side of a rounding boundary (it left that
# mesh open, and its convex hull 3.1 times its volume); a distance tolerance can. But distinct
# corners can be as close: TIAGo's base_ring.stl (0.54 m) has corners one float32 step (1.6e-8
# m, 3e-8 of its extent) apart, closed as they are and pinched if welded, hence the fine first.
WELD_RTOLS = (1e-8, 1e-7)


@dataclass(frozen=True)
class Classification:
    """What a surface was found to bound: the integrals and how they were obtained."""

    moments: VolumeMoments
    method: Method
    inverted: bool = False
    closed: bool = True
    volume_error: float = 0.0


def classify(
    path: Path,
    integrator: SurfaceIntegrator,
    triangles: NDArray | None,
    shared: tuple[NDArray, NDArray] | None = None,
) -> Classification:
    """
    Pick the method for a surface integrated in ``integrator``, in the file's unit:
    ``triangles`` (n, 3, 3) are needed only when the surface is not closed; ``shared``, the
    vertices and faces they are made of, if known, finds their distinct corners faster.

    Raises
    ------
    MeshError
      ``empty`` when the surface, or its convex hull, bounds no volume.
    """
    if integrator.closed:
        return _oriented(path, integrator, "exact")
    assert triangles is not None
    if shared is None:
        points, corners = unique_rows(np.asarray(triangles, dtype=np.float64).reshape(-1, 3))
    else:
        points, corners = shared_unique_rows(*shared)
    extent = _extent(integrator.bounds)
    judged = None
    for rtol in WELD_RTOLS:
        faces = weld(points, rtol * extent)[corners.reshape(-1, 3)]
        # welding collapses slivers narrower than the noise: they hold no volume
        faces = faces[
            (faces[:, 0] != faces[:, 1])
            & (faces[:, 1] != faces[:, 2])
            & (faces[:, 2] != faces[:, 0])
        ]
        if judged is None or not np.array_equal(faces, judged):  # a wider weld merged more
            watertight, consistent = closure(faces)
            judged = faces
        if watertight:
            break
    if watertight and len(faces):
        method: Method = "exact" if consistent else "repaired"
        if method == "repaired":
            faces = _rewound(path, points, faces)
        closed = integrate(points[faces])
        if closed.closed:
            return _oriented(path, closed, method)
    return _convex_hull(path, triangles, integrator, first_seen(points, corners))


def unique_rows(rows: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.intp]]:
    """
    ``np.unique(rows, axis=0, return_inverse=True)`` (the distinct rows in lexicographic order,
    and each row's index among them) for finite rows (k, 3), two to three times faster: one
    ``lexsort`` of the columns instead of a sort of the rows as records. Non-finite rows are
    left to ``np.unique``.
    """
    if not np.isfinite(rows).all():
        points, inverse = np.unique(rows, axis=0, return_inverse=True)
        return points, inverse.reshape(-1)
    order = np.lexsort((rows[:, 2], rows[:, 1], rows[:, 0]))
    ranked = rows[order]
    first = np.empty(len(rows), dtype=bool)
    first[:1] = True
    first[1:] = (ranked[1:] != ranked[:-1]).any(axis=1)
    inverse = np.empty(len(rows), dtype=np.intp)
    inverse[order] = np.cumsum(first) - 1
    return ranked[first], inverse


def shared_unique_rows(
    vertices: NDArray[np.float64], faces: NDArray[np.intp]
) -> tuple[NDArray[np.float64], NDArray[np.intp]]:
    """
    :func:`unique_rows` of the triangles' corners ``vertices[faces]``, found among the
    vertices the faces use, not among every corner: the same distinct points in the same
    order and each corner's index among them (a point whose copies differ only in the sign of
    a zero may come from another copy: equal, and weighing the same).
    """
    marked = np.zeros(len(vertices), dtype=bool)
    marked[faces.reshape(-1)] = True
    used = np.flatnonzero(marked)  # np.unique(faces), without sorting the corners
    points, inverse = unique_rows(vertices[used])
    lookup = np.empty(len(vertices), dtype=np.intp)
    lookup[used] = inverse
    return points, lookup[faces.reshape(-1)]


def closure(faces: NDArray[np.int64]) -> tuple[bool, bool]:
    """
    ``(watertight, consistently wound)`` of a surface's faces (k, 3), as trimesh judges them
    (``graph.is_watertight``): watertight when every edge is shared by exactly two faces;
    consistently wound when, of every edge shared by exactly two, they run along it in opposite
    directions (so an open surface may be consistent, and no faces is both).
    """
    directed = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    if not len(directed):
        return True, True
    # each undirected edge as one integer, (low, high) in lexicographic order: one stable sort
    # of integers, not a lexsort of two columns (indices are below 2**31: no overflow)
    low = np.minimum(directed[:, 0], directed[:, 1]).astype(np.int64)
    high = np.maximum(directed[:, 0], directed[:, 1]).astype(np.int64)
    edges = low * (int(high.max()) + 1) + high
    order = np.argsort(edges, kind="stable")
    ranked = edges[order]
    starts = np.flatnonzero(np.r_[True, ranked[1:] != ranked[:-1]])
    sizes = np.diff(np.r_[starts, len(ranked)])
    pairs = order[starts[sizes == 2][:, None] + np.arange(2)]
    watertight = 2 * len(pairs) == len(directed)
    first, second = directed[pairs[:, 0]], directed[pairs[:, 1]]
    return watertight, bool((first[:, 1] == second[:, 0]).all())


def _rewound(path: Path, points: NDArray, faces: NDArray[np.int64]) -> NDArray[np.int64]:
    """The faces wound consistently, by trimesh's repair (which walks the face graph)."""
    import trimesh

    merged = trimesh.Trimesh(vertices=points, faces=faces, process=False)
    try:
        trimesh.repair.fix_winding(merged)
    except ImportError as error:
        # trimesh walks the face graph with networkx, an optional dependency of its own
        raise ImportError(
            f"repairing the triangle winding of {path} needs networkx "
            f"(`pip install networkx`): {error}"
        ) from error
    return np.asarray(merged.faces)


def _oriented(path: Path, integrator: SurfaceIntegrator, method: Method) -> Classification:
    """A closed surface's integrals with positive volume; a negative one is flipped."""
    moments = integrator.moments
    _check_volume(path, moments.volume, integrator.bounds, "the mesh's closed surface")
    if moments.volume > 0:
        return Classification(moments, method)
    # a repaired winding is oriented by whichever triangle the repair started from: flipping
    # it is part of the repair, not a fault of the file
    return Classification(moments.negated(), method, inverted=method == "exact")


def first_seen(points: NDArray[np.float64], corners: NDArray[np.intp]) -> NDArray[np.float64]:
    """
    The distinct ``points`` in the order the ``corners`` (each one's index among them) first
    reach them: the corners without their repeats, in order. manifold3d's convex hull of these
    is that of every corner to the last bit (on all 1616 open meshes with a volume at hand), in
    about half the time; the hull of the same points sorted is not (it differs in the last
    bits on half of them, up to 1e-8 relative).
    """
    ids = corners.reshape(-1)
    first = np.full(len(points), len(ids))
    np.minimum.at(first, ids, np.arange(len(ids)))
    return points[ids[np.sort(first)]]


def _convex_hull(
    path: Path, triangles: NDArray, integrator: SurfaceIntegrator, distinct: NDArray
) -> Classification:
    """The convex hull of the ``triangles``' corners, taken of their ``distinct`` ones (the
    corners without repeats, in order: :func:`first_seen`)."""
    import manifold3d

    moments = manifold_moments(manifold3d.Manifold.hull_points(distinct))
    volume = moments.volume
    _check_volume(path, volume, integrator.bounds, "the mesh is open and its convex hull")
    if volume < 0:
        moments = moments.negated()
    open_volume = integrate(triangles, origin=moments.centroid).moments.volume
    error = abs(moments.volume - abs(open_volume)) / moments.volume
    return Classification(moments, "convex-hull", closed=False, volume_error=error)


def weld(points: NDArray, tolerance: float) -> NDArray[np.int64]:
    """
    For each of the distinct points (m, 3), the index of the point it is welded to: points
    within ``tolerance / 2`` of each other on every axis are welded (so are chains of them),
    points more than ``tolerance · √3`` apart only through such a chain.

    How: the points are binned on 8 grids of cell ``tolerance``, offset by half a cell or not
    on each axis; two points within half a cell on every axis share a cell on at least one of
    them. The points of a cell take the lowest index among them, grid after grid, until no
    index changes (a chain of n points settles within n rounds). When no two points come
    within twice the tolerance on every axis (:func:`apart`), which is what most meshes' corners
    are, no cell holds two and the labels are the points' own indices without the grids.
    """
    if not len(points) or not tolerance > 0 or apart(points, 2.0 * tolerance):
        return np.arange(len(points))
    return grid_weld(points, tolerance)


def grid_weld(points: NDArray, tolerance: float) -> NDArray[np.int64]:
    """:func:`weld` on its grids alone, for points (m, 3), m > 0, and a positive tolerance."""
    labels = np.arange(len(points))
    scaled = (points - points.min(axis=0)) / tolerance
    offsets = np.array([[(k >> axis) & 1 for axis in range(3)] for k in range(8)]) / 2
    cells = [_cell_ids(np.floor(scaled + offset).astype(np.int64)) for offset in offsets]
    while True:
        before = labels
        for cell in cells:
            lowest = np.full(cell.max() + 1, len(points))
            np.minimum.at(lowest, cell.ravel(), labels)
            labels = lowest[cell.ravel()]
        if np.array_equal(labels, before):
            return labels


#: a direction no grid of CAD coordinates lines up with (powers of the plastic number's
#: inverse): points along it are as spread out as the mesh, so few pairs are near in projection
_SPREAD = np.array([1.0, 0.7548776662466927, 0.5698402909980532])
#: more pairs near in projection than this many per point: the grids are cheaper than the pairs
_MOST_NEAR = 8


def apart(points: NDArray, distance: float) -> bool:
    """
    Whether no two of ``points`` (m, 3) lie within ``distance`` of each other on every axis:
    two that do are within ``distance · Σ|spread|`` along one direction, so only the pairs that
    near in that single sort are measured. False (not known to be apart) also when the points
    are not finite or more than a few pairs per point are that near in projection.
    """
    along = (points - points.min(axis=0)) @ _SPREAD
    if not np.isfinite(along).all():
        return False
    order = np.argsort(along, kind="stable")
    ranked = along[order]
    # and the rounding of the projection, far below any tolerance of a weld
    reach = distance * float(_SPREAD.sum()) + 16 * np.finfo(float).eps * float(ranked[-1])
    # the pairs (i, i + k) in sorted order nearer than ``reach``: sorted, so they are the
    # first ``k`` steps of each run of near neighbours
    near = np.flatnonzero(np.diff(ranked) < reach)
    step, measured = 1, 0
    while len(near):
        measured += len(near)
        if measured > _MOST_NEAR * len(points):
            return False
        gaps = np.abs(points[order[near]] - points[order[near + step]]).max(axis=1)
        if (gaps < distance).any():
            return False
        step += 1
        near = near[near + step < len(ranked)]
        near = near[ranked[near + step] - ranked[near] < reach]
    return True


def _cell_ids(cells: NDArray[np.int64]) -> NDArray[np.int64]:
    """
    One id per distinct row of ``cells`` (m, 3) non-negative integers, the same for equal rows:
    as ``np.unique(cells, axis=0, return_inverse=True)[1]`` groups them, an order of magnitude
    faster (two sorts of integers instead of one of rows). Each product stays below 2⁶³: a
    coordinate is at most 1/:data:`WELD_RTOLS`'s finest (1e8), an id at most m.
    """
    x, y, z = cells.T
    planar = np.unique(x * (int(y.max()) + 1) + y, return_inverse=True)[1].reshape(-1)
    return np.unique(planar * (int(z.max()) + 1) + z, return_inverse=True)[1].reshape(-1)


def _extent(bounds: NDArray) -> float:
    return float(np.max(bounds[1] - bounds[0]))


def _check_volume(path: Path, volume: float, bounds: NDArray, what: str) -> None:
    extent = _extent(bounds)
    if not abs(volume) > EMPTY_VOLUME_RTOL * extent**3:
        raise MeshError(
            path,
            "empty",
            f"{what} bounds no volume ({fmt(volume)} file units³ in a "
            f"bounding box {fmt(extent)} wide); export the solid body, not a flat sheet",
        )
