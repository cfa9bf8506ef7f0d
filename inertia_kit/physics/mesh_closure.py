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
    path: Path, integrator: SurfaceIntegrator, triangles: NDArray | None
) -> Classification:
    """
    Pick the method for a surface integrated in ``integrator``, in the file's unit:
    ``triangles`` (n, 3, 3) are needed only when the surface is not closed.

    Raises
    ------
    MeshError
      ``empty`` when the surface, or its convex hull, bounds no volume.
    """
    if integrator.closed:
        return _oriented(path, integrator, "exact")
    assert triangles is not None
    import trimesh

    points, corners = np.unique(
        np.asarray(triangles, dtype=np.float64).reshape(-1, 3), axis=0, return_inverse=True
    )
    extent = _extent(integrator.bounds)
    for rtol in WELD_RTOLS:
        faces = weld(points, rtol * extent)[corners.reshape(-1, 3)]
        # welding collapses slivers narrower than the noise: they hold no volume
        faces = faces[
            (faces[:, 0] != faces[:, 1])
            & (faces[:, 1] != faces[:, 2])
            & (faces[:, 2] != faces[:, 0])
        ]
        merged = trimesh.Trimesh(vertices=points, faces=faces, process=False)
        if merged.is_watertight:
            break
    if merged.is_watertight and len(merged.faces):
        method: Method = "exact" if merged.is_winding_consistent else "repaired"
        if method == "repaired":
            try:
                trimesh.repair.fix_winding(merged)
            except ImportError as error:
                # trimesh walks the face graph with networkx, an optional dependency of its own
                raise ImportError(
                    f"repairing the triangle winding of {path} needs networkx "
                    f"(`pip install networkx`): {error}"
                ) from error
        closed = integrate(merged.triangles)
        if closed.closed:
            return _oriented(path, closed, method)
    return _convex_hull(path, triangles, integrator)


def _oriented(path: Path, integrator: SurfaceIntegrator, method: Method) -> Classification:
    """A closed surface's integrals with positive volume; a negative one is flipped."""
    moments = integrator.moments
    _check_volume(path, moments.volume, integrator.bounds, "the mesh's closed surface")
    if moments.volume > 0:
        return Classification(moments, method)
    # a repaired winding is oriented by whichever triangle the repair started from: flipping
    # it is part of the repair, not a fault of the file
    return Classification(moments.negated(), method, inverted=method == "exact")


def _convex_hull(path: Path, triangles: NDArray, integrator: SurfaceIntegrator) -> Classification:
    import manifold3d

    moments = manifold_moments(manifold3d.Manifold.hull_points(triangles.reshape(-1, 3)))
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
    index changes (a chain of n points settles within n rounds).
    """
    labels = np.arange(len(points))
    if not len(points) or not tolerance > 0:
        return labels
    scaled = (points - points.min(axis=0)) / tolerance
    offsets = np.array([[(k >> axis) & 1 for axis in range(3)] for k in range(8)]) / 2
    cells = [
        np.unique(np.floor(scaled + offset).astype(np.int64), axis=0, return_inverse=True)[1]
        for offset in offsets
    ]
    while True:
        before = labels
        for cell in cells:
            lowest = np.full(cell.max() + 1, len(points))
            np.minimum.at(lowest, cell.ravel(), labels)
            labels = lowest[cell.ravel()]
        if np.array_equal(labels, before):
            return labels


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
