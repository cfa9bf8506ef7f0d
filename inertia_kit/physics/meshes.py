"""
Mass properties of mesh files as a URDF ``<mesh filename scale>`` means them, with a record of
how they were obtained.

Every format ends in the same kernel, :mod:`inertia_kit.physics.polyhedra`: the file is read
into a surface in its own unit (:mod:`.mesh_formats`), the surface's solid is found, exactly or
not (``method``, :mod:`.mesh_closure`), and the file's unit and the URDF ``scale`` are applied
analytically to the integrals (:func:`scaled_solid`).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from inertia_kit.errors import MeshError
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.mesh_closure import Method, classify
from inertia_kit.physics.mesh_formats import read_surface
from inertia_kit.physics.numbers import MIN_NORMAL
from inertia_kit.physics.volume_moments import VolumeMoments


@dataclass(frozen=True, eq=False)
class MeshSolid:
    """
    The solid a mesh file describes, in metres after its unit and the URDF ``scale``.

    Attributes
    ----------
    path : str
      The mesh file.
    scale : (3,) tuple of float
      The URDF ``scale`` applied (negative factors mirror).
    moments : VolumeMoments
      Volume integrals of the solid, positive ``volume`` (m³, m⁴, m⁵).
    method : {"exact", "repaired", "convex-hull"}
      How the integrals were obtained (see :mod:`.mesh_closure`).
    inverted : bool
      The closed surface was wound inside-out (negative volume); ``moments`` are those of the
      flipped surface. A mirroring ``scale`` is not an inversion.
    closed : bool
      The surface bounds a solid (for ``exact`` and ``repaired``).
    volume_error : float
      Relative error bound of ``volume``: 0 for a closed surface; for ``convex-hull``,
      ``|V_hull - |V_open|| / V_hull``, where ``V_open`` is the open surface's signed volume
      about the hull's centroid.
    bounds : (2, 3) float
      Lowest and highest vertex coordinates, m.
    triangle_count : int
      Triangles in the file.
    unit_scale : float
      Factor from the file's own unit to metres (COLLADA ``<unit meter>``), applied before
      ``scale``.
    """

    path: str
    scale: tuple[float, float, float]
    moments: VolumeMoments
    method: Method
    inverted: bool
    closed: bool
    volume_error: float
    bounds: NDArray[np.float64]
    triangle_count: int
    unit_scale: float

    @property
    def volume(self) -> float:
        """Volume of the solid, m³."""
        return self.moments.volume

    @property
    def centroid(self) -> NDArray[np.float64]:
        """(3,) centroid of the solid, m."""
        return self.moments.centroid

    @property
    def summary(self) -> str:
        """One sentence on how the values were obtained and what to do about it, if anything."""
        name = Path(self.path).name
        count = f"{self.triangle_count} triangles"
        if self.method == "convex-hull":
            return (
                f"`{name}` is an open surface ({count}): used its convex hull, whose volume "
                f"differs from the open surface's by {fmt(100 * self.volume_error, 3)}%; "
                "close the mesh (export it as a solid) for exact values"
            )
        if self.method == "repaired":
            return (
                f"`{name}` is closed ({count}) but its triangles were wound inconsistently: "
                "repaired the winding; re-export the mesh with consistent normals"
            )
        if self.inverted:
            return (
                f"`{name}` is closed ({count}) but wound inside-out (negative volume): "
                "computed from the flipped surface; flip the mesh's normals"
            )
        return f"`{name}` is closed ({count}): exact volume integrals"

    def mass_properties(
        self, *, density: float | None = None, mass: float | None = None
    ) -> MassProperties:
        """
        Mass properties at uniform density, in the mesh's frame.

        Parameters
        ----------
        density : float, optional
          kg/m³
        mass : float, optional
          kg; exactly one of ``density`` and ``mass``.
        """
        return self.moments.mass_properties(density=density, mass=mass)


def _solid_field(name: str, doc: str | None = None) -> property:
    """A read-only attribute of :class:`MeshMassProperties` that is its solid's ``name``."""
    return property(lambda self: getattr(self.solid, name), doc=doc)


@dataclass(frozen=True, eq=False)
class MeshMassProperties:
    """
    Mass properties of a mesh file and how they were obtained.

    Attributes
    ----------
    mass_properties : MassProperties
      Mass (kg), centre of mass (3,) m and inertia tensor (3, 3) kg·m² about it, in the
      mesh's frame.
    solid : MeshSolid
      The geometry and its diagnostics, also reachable directly (``.method``, ``.volume``, ...).
    """

    mass_properties: MassProperties
    solid: MeshSolid

    # the solid's geometry and diagnostics, reachable directly (see MeshSolid for each)
    path = _solid_field("path")
    scale = _solid_field("scale")
    method = _solid_field("method")
    inverted = _solid_field("inverted")
    closed = _solid_field("closed")
    volume = _solid_field("volume", "m³")
    volume_error = _solid_field("volume_error")
    bounds = _solid_field("bounds", "(2, 3) m")
    triangle_count = _solid_field("triangle_count")
    unit_scale = _solid_field("unit_scale")
    summary = _solid_field("summary")


def mesh(
    path: str | Path,
    scale: ArrayLike = (1.0, 1.0, 1.0),
    *,
    density: float | None = None,
    mass: float | None = None,
) -> MeshMassProperties:
    """
    Mass properties of a mesh file at uniform density, as URDF ``<mesh filename scale>``.

    Parameters
    ----------
    path : str or Path
      STL (binary or ASCII), OBJ, DAE, PLY, GLB or glTF file.
    scale : (3,) float
      URDF per-axis ``scale``; negative factors mirror.
    density : float, optional
      kg/m³
    mass : float, optional
      kg; exactly one of ``density`` and ``mass``.

    Raises
    ------
    MeshError
      ``not-found``, ``unreadable`` or ``empty`` (see :func:`mesh_solid`).
    ValueError
      For a bad ``scale``, or not exactly one positive ``density`` or ``mass``.
    """
    if (density is None) == (mass is None):
        raise ValueError("give exactly one of density (kg/m³) or mass (kg)")
    solid = mesh_solid(path, scale)
    return MeshMassProperties(solid.mass_properties(density=density, mass=mass), solid)


def mesh_solid(path: str | Path, scale: ArrayLike = (1.0, 1.0, 1.0)) -> MeshSolid:
    """
    The solid a mesh file describes, in metres, without a density.

    Parameters
    ----------
    path : str or Path
      STL (binary or ASCII), OBJ, DAE, PLY, GLB or glTF file.
    scale : (3,) float
      URDF per-axis ``scale``; negative factors mirror, and the volume stays positive.

    Raises
    ------
    MeshError
      ``not-found`` for a missing file; ``unreadable`` for a corrupt file or an unsupported
      format; ``empty`` for a file with no triangles or no volume.
    ValueError
      For a ``scale`` that is not three finite non-zero factors.
    """
    factors = np.asarray(scale, dtype=np.float64)
    if factors.shape != (3,) or not np.isfinite(factors).all() or np.any(factors == 0):
        raise ValueError(
            f"scale must be three finite non-zero factors, got {scale!r}; "
            "use a negative factor to mirror"
        )
    # non-finite coordinates: the readers refuse non-finite integrals, without warnings
    with np.errstate(over="ignore", invalid="ignore"):
        integrator, triangles, unit_scale, shared = read_surface(path)
        file = Path(path)
        classified = classify(file, integrator, triangles, shared)
    return scaled_solid(
        file,
        classified.moments,
        integrator.bounds,
        tuple(float(s) for s in factors),
        unit_scale=unit_scale,
        method=classified.method,
        inverted=classified.inverted,
        closed=classified.closed,
        volume_error=classified.volume_error,
        triangle_count=integrator.count,
    )


def scaled_solid(
    path: str | Path,
    moments: VolumeMoments,
    bounds: NDArray[np.float64],
    scale: tuple[float, float, float],
    *,
    unit_scale: float,
    **fields: Any,
) -> MeshSolid:
    """
    The solid at the URDF ``scale`` from the file's own-unit volume integrals and bounds: the
    file's unit and the scale are applied analytically. ``fields`` are the other
    :class:`MeshSolid` fields, which no scale changes. The mesh cache builds its hits with this
    same arithmetic, so a hit equals a read to the last bit.
    """
    factors = unit_scale * np.asarray(scale)
    with np.errstate(over="ignore", invalid="ignore"):  # checked below
        scaled_bounds = np.sort(bounds * factors, axis=0)
        scaled = moments.scaled(factors)
        # the mass properties are computed from these, with a centroid and a tensor
        finite = (
            np.isfinite(scaled.centroid).all()
            and np.isfinite(
                [scaled.volume, *scaled.first, *scaled.second.ravel(), *scaled_bounds.ravel()]
            ).all()
        )
    if not finite:
        raise MeshError(
            path,
            "overflow",
            f"its volume or moments overflow double precision: coordinates up to "
            f"{np.abs(bounds).max():.3g} file units, times {np.abs(factors).max():.3g}",
        )
    if not abs(scaled.volume) >= MIN_NORMAL:
        raise MeshError(
            path, "empty", f"its volume, {scaled.volume:.3g} m³, underflows double precision"
        )
    scaled_bounds.flags.writeable = False
    return MeshSolid(
        path=str(Path(path)),
        scale=scale,
        moments=scaled,
        bounds=scaled_bounds,
        unit_scale=unit_scale,
        **fields,
    )
