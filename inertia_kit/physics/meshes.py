"""
Mass properties of mesh files as a URDF ``<mesh filename scale>`` means them, with a record of
how they were obtained.

Every format ends in the same kernel, :mod:`inertia_kit.physics.polyhedra`: STL is read by
:func:`.stl.read_stl` without trimesh (the fast path); OBJ, DAE, PLY, GLB and glTF go
through trimesh, whose scene graph is flattened into one triangle soup. The file's own unit
(COLLADA ``<unit meter>``) and the URDF ``scale`` are applied analytically to the integrals.

How the volume integrals were obtained (``method``):

``exact``
  The surface is closed and consistently wound (directly, or once vertices that differ only by
  float noise are merged). A surface wound inside-out has a negative volume: it is reported as
  ``inverted`` and integrated flipped.
``repaired``
  Closed, but some triangles were wound against their neighbours; trimesh's winding repair
  made it consistent.
``convex-hull``
  An open surface bounds no solid; the mass properties are those of its convex hull, and
  ``volume_error`` bounds how far that is from the open surface's own volume.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from inertia_kit.errors import MeshError
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.polyhedra import SurfaceIntegrator, integrate
from inertia_kit.physics.stl import read_stl
from inertia_kit.physics.volume_moments import VolumeMoments

if TYPE_CHECKING:
    import trimesh

Method = Literal["exact", "repaired", "convex-hull"]

# file suffix -> (trimesh file type, name for messages); STL is read without trimesh
FORMATS = {
    ".stl": ("stl", "STL"),
    ".obj": ("obj", "Wavefront OBJ"),
    ".dae": ("dae", "COLLADA"),
    ".ply": ("ply", "PLY"),
    ".glb": ("glb", "binary glTF"),
    ".gltf": ("gltf", "glTF"),
}

# what to do about a MeshError of each kind, for messages that do not say it yet
ADVICE = {
    "not-found": "check the path and the package it names",
    "unreadable": "re-export it from the CAD tool as a binary STL",
    "empty": "export the part's solid body",
}

# |volume| below this fraction of the bounding box's largest extent cubed is no solid at all:
# far above the rounding of the volume sum, far below any real part (a 1 m plate 1 µm thick
# is 1e-6)
EMPTY_VOLUME_RTOL = 1e-12

# vertices closer than this fraction of the mesh's extent are merged before the trimesh checks:
# float noise, not geometry
MERGE_RTOL = 1e-8


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
      How the integrals were obtained (see the module docstring).
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

    @property
    def path(self) -> str:
        return self.solid.path

    @property
    def scale(self) -> tuple[float, float, float]:
        return self.solid.scale

    @property
    def method(self) -> Method:
        return self.solid.method

    @property
    def inverted(self) -> bool:
        return self.solid.inverted

    @property
    def closed(self) -> bool:
        return self.solid.closed

    @property
    def volume(self) -> float:
        """m³"""
        return self.solid.volume

    @property
    def volume_error(self) -> float:
        return self.solid.volume_error

    @property
    def bounds(self) -> NDArray[np.float64]:
        """(2, 3) m"""
        return self.solid.bounds

    @property
    def triangle_count(self) -> int:
        return self.solid.triangle_count

    @property
    def unit_scale(self) -> float:
        return self.solid.unit_scale

    @property
    def summary(self) -> str:
        return self.solid.summary


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
    file = Path(path)
    if not file.is_file():
        what = "is a directory, not a mesh file" if file.is_dir() else "does not exist"
        raise MeshError(
            path, "not-found", f"the mesh file {what}; check the path and the package it names"
        )
    suffix = file.suffix.lower()
    if suffix not in FORMATS:
        raise MeshError(
            path,
            "unreadable",
            f"unsupported mesh format `{file.suffix or '(no suffix)'}`, expected one of "
            f"{', '.join(FORMATS)}; convert the mesh to STL",
        )

    unit_scale = 1.0
    if suffix == ".stl":
        try:
            integrator = read_stl(file)
        except OSError as error:
            raise MeshError(
                path, "unreadable", f"cannot read the file ({error}); check its permissions"
            ) from None
        except MeshError as error:
            raise MeshError(
                error.path, error.kind, f"{error.message}; {ADVICE[error.kind]}"
            ) from None
        triangles = None if integrator.closed else _read_scene(file, suffix)[0]
    else:
        triangles, unit_scale = _read_scene(file, suffix)
        integrator = integrate(triangles)
    fields = _classify(file, integrator, triangles)
    return scaled_solid(
        file,
        fields.moments,
        integrator.bounds,
        tuple(float(s) for s in factors),
        unit_scale=unit_scale,
        method=fields.method,
        inverted=fields.inverted,
        closed=fields.closed,
        volume_error=fields.volume_error,
        triangle_count=integrator.count,
    )


@dataclass(frozen=True)
class _Fields:
    moments: VolumeMoments
    method: Method
    inverted: bool = False
    closed: bool = True
    volume_error: float = 0.0


def _classify(path: Path, integrator: SurfaceIntegrator, triangles: NDArray | None) -> _Fields:
    """Pick the method: ``triangles`` (n, 3, 3) are needed only when the surface is not closed."""
    if integrator.closed:
        return _oriented(path, integrator, "exact")
    assert triangles is not None
    import trimesh

    merged = trimesh.Trimesh(
        vertices=triangles.reshape(-1, 3),
        faces=np.arange(3 * len(triangles)).reshape(-1, 3),
        process=False,
    )
    merged.merge_vertices(digits_vertex=_merge_digits(integrator.bounds))
    faces = merged.faces
    # merging collapses slivers narrower than the noise: they hold no volume
    merged.update_faces(
        (faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & (faces[:, 2] != faces[:, 0])
    )
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


def _oriented(path: Path, integrator: SurfaceIntegrator, method: Method) -> _Fields:
    """A closed surface's integrals with positive volume; a negative one is flipped."""
    moments = integrator.moments
    _check_volume(path, moments.volume, integrator.bounds, "the mesh's closed surface")
    if moments.volume > 0:
        return _Fields(moments, method)
    # a repaired winding is oriented by whichever triangle the repair started from: flipping
    # it is part of the repair, not a fault of the file
    return _Fields(moments.negated(), method, inverted=method == "exact")


def _convex_hull(path: Path, triangles: NDArray, integrator: SurfaceIntegrator) -> _Fields:
    import manifold3d

    hull = manifold3d.Manifold.hull_points(triangles.reshape(-1, 3))
    # to_mesh64 (manifold3d ≥ 3) keeps the input's float64 vertices; to_mesh rounds to float32
    shell = getattr(hull, "to_mesh64", hull.to_mesh)()
    vertices = np.asarray(shell.vert_properties, dtype=np.float64)[:, :3]
    hull_triangles = vertices[np.asarray(shell.tri_verts, dtype=np.intp)]
    moments = integrate(hull_triangles).moments if len(hull_triangles) else None
    volume = 0.0 if moments is None else moments.volume
    _check_volume(path, volume, integrator.bounds, "the mesh is open and its convex hull")
    assert moments is not None
    if volume < 0:
        moments = moments.negated()
    open_volume = integrate(triangles, origin=moments.centroid).moments.volume
    error = abs(moments.volume - abs(open_volume)) / moments.volume
    return _Fields(moments, "convex-hull", closed=False, volume_error=error)


def _check_volume(path: Path, volume: float, bounds: NDArray, what: str) -> None:
    extent = float(np.max(bounds[1] - bounds[0]))
    if not abs(volume) > EMPTY_VOLUME_RTOL * extent**3:
        raise MeshError(
            path,
            "empty",
            f"{what} bounds no volume ({fmt(volume)} file units³ in a "
            f"bounding box {fmt(extent)} wide); export the solid body, not a flat sheet",
        )


def _merge_digits(bounds: NDArray) -> int:
    """Decimal digits that round away noise of about ``MERGE_RTOL`` times the mesh's extent."""
    extent = float(np.max(bounds[1] - bounds[0]))
    if not extent > 0:
        return 8
    return max(0, -math.floor(math.log10(MERGE_RTOL * extent)))


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
    scaled_bounds = np.sort(bounds * factors, axis=0)
    scaled_bounds.flags.writeable = False
    return MeshSolid(
        path=str(Path(path)),
        scale=scale,
        moments=moments.scaled(factors),
        bounds=scaled_bounds,
        unit_scale=unit_scale,
        **fields,
    )


def _read_scene(path: Path, suffix: str) -> tuple[NDArray[np.float64], float]:
    """
    Every triangle of a file trimesh reads, placed by its scene graph.

    Returns
    -------
    triangles : (n, 3, 3) float
      In the file's unit, wound as the file winds them (a mirroring node transform is undone).
    unit_scale : float
      Metres per file unit.
    """
    file_type, name = FORMATS[suffix]
    try:
        import trimesh
    except ImportError as error:  # pragma: no cover - trimesh is a dependency
        raise MeshError(path, "unreadable", f"reading {name} needs trimesh: {error}") from None
    try:
        scene = trimesh.load_scene(str(path), file_type=file_type, process=False)
        parts, units = _scene_parts(scene, trimesh.Trimesh)
    except MeshError:
        raise
    except Exception as error:
        # trimesh and its parsers raise anything from ValueError to XML and struct errors
        text = str(error).strip().splitlines()[0][:200] if str(error).strip() else ""
        kind = type(error).__name__
        detail = text if text.startswith(kind) else f"{kind}: {text}".rstrip(": ")
        raise MeshError(
            path,
            "unreadable",
            f"cannot read the file as {name} ({detail}); re-export it, or convert it to STL",
        ) from None
    if not parts:
        raise MeshError(
            path, "empty", f"the {name} file holds no triangles; export the part's solid body"
        )
    factors = {_unit_factor(path, unit) for unit in units}
    if len(factors) > 1:
        raise MeshError(
            path,
            "unreadable",
            f"the file's meshes are in different units ({', '.join(sorted(set(units)))}); "
            "re-export it in one unit",
        )
    triangles = np.concatenate(parts)
    if not np.isfinite(triangles).all():
        raise MeshError(path, "unreadable", f"the {name} file holds non-finite vertex coordinates")
    return triangles, factors.pop()


def _scene_parts(
    scene: trimesh.Scene, mesh_type: type
) -> tuple[list[NDArray[np.float64]], list[str]]:
    """The triangles (n, 3, 3) of each mesh instance in the scene graph, and its unit."""
    parts, units = [], []
    for node in scene.graph.nodes_geometry:
        matrix, geometry_name = scene.graph[node]
        geometry = scene.geometry[geometry_name]
        if not isinstance(geometry, mesh_type) or len(geometry.faces) == 0:
            continue
        vertices = _transformed(np.asarray(geometry.vertices, dtype=np.float64), matrix)
        faces = np.asarray(geometry.faces)
        if np.linalg.det(matrix[:3, :3]) < 0:
            # a mirroring node turns the winding inside-out: undo it, as a renderer does
            faces = faces[:, ::-1]
        parts.append(vertices[faces])
        units.append(geometry.units or "meters")
    return parts, units


def _transformed(vertices: NDArray[np.float64], matrix: NDArray) -> NDArray[np.float64]:
    """(n, 3) vertices under a (4, 4) transform, element by element."""
    matrix = np.asarray(matrix, dtype=np.float64)
    if np.array_equal(matrix, np.eye(4)):
        return vertices
    # elementwise, not a matrix product: BLAS may round the same vertex differently at
    # different rows, and the closure check compares vertices by their exact bits
    out = vertices[:, 0:1] * matrix[:3, 0]
    out += vertices[:, 1:2] * matrix[:3, 1]
    out += vertices[:, 2:3] * matrix[:3, 2]
    out += matrix[:3, 3]
    return out


def _unit_factor(path: Path, unit: str) -> float:
    """Metres per ``unit``, as trimesh spells units (``meters``, ``0.001 * meters``)."""
    from trimesh.units import unit_conversion

    try:
        factor = float(unit_conversion(unit, "meters"))
    except Exception:
        raise MeshError(
            path, "unreadable", f"unknown unit `{unit}` in the file; re-export it in metres"
        ) from None
    if not (math.isfinite(factor) and factor > 0):
        raise MeshError(
            path, "unreadable", f"unit `{unit}` is {factor} m; re-export the file in metres"
        )
    return factor
