"""
A MuJoCo mesh geom's mass properties as MuJoCo's compiler infers them (``inertiafromgeom``),
by the mesh's ``inertia`` mode, computed without MuJoCo: the same formulas, in the same order,
with the same thresholds and refusals, so that the results agree with MuJoCo 4.0.0 to rounding
(1e-9 relative, tested against it; primitives: :mod:`.mujoco_primitive_inertia`).

Sources, in google-deepmind/mujoco: ``src/user/user_mesh.cc`` (``mjCMesh::Process``,
``ComputeFaceCentroid``, ``ComputeVolume``, ``ComputeSurfaceArea``, ``ComputeInertia``,
``MakeGraph``, the file-local ``triangle``), ``src/user/user_objects.cc`` (``mjCGeom::Compile``,
``GetVolume``, ``SetInertia``; ``mjCBody::InertiaFromGeom`` copies a lone geom's values as they
are), ``src/user/user_util.cc`` (``mjuu_eig3``) and the decoders
``plugin/stl_decoder/stl_decoder.cc`` and ``plugin/obj_decoder/obj_decoder.cc``.

The source read is the snapshot of August 2026 (3.12.1 in development); where MuJoCo 4.0.0
itself, run, differs from it, 4.0.0 is followed and the difference said (a mirrored convex
hull; the eigen-solver, whose early stop is not copied: :func:`principal_axes`).

What a mesh's numbers depend on that is not obvious:

- MuJoCo stores a file's vertices as float32 and computes in double from them; the mesh
  ``scale`` multiplies them in double after the convex hull and the winding check
  (:func:`mujoco_vertices`, or ``scale=`` of :func:`mesh_mass_properties`).
- ``legacy`` (the default ``<mesh inertia>``) adds the *absolute* volume of each face's
  pyramid: with its apex at the area-weighted centroid of the faces for the centre of mass,
  then at that centre of mass for the volume and the tensor. Both over-count a non-convex mesh.
- A mesh geom's moments are not the tensor's eigenvalues but ``mass (b_j² + b_k²) / 3`` of its
  "equivalent inertia box" ``b``, made from them (equal to rounding, and refused or NaN when
  they break the triangle inequality).
"""

from __future__ import annotations

import functools
import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from inertia_kit.physics.mass import MassProperties

#: ``<mesh inertia>`` values; ``legacy`` is MuJoCo 4's default
MESH_MODES = ("legacy", "exact", "convex", "shell")
#: a geom's ``density`` when it gives neither ``density`` nor ``mass``, kg/m³
DEFAULT_DENSITY = 1000.0

# mjMINVAL and mjEPS (include/mujoco/mjtype.h, user_util.cc)
MJMINVAL = 1e-15
MJEPS = 1e-14
# mjCMesh::Process's tolerances of the triangle inequality
_INEQUALITY_RTOL = 1e-6
_INEQUALITY_ATOL = 1e-9


# --- meshes ---------------------------------------------------------------------------------


def mujoco_vertices(vertices: ArrayLike, scale: ArrayLike = (1.0, 1.0, 1.0)) -> NDArray:
    """
    A mesh file's vertices as MuJoCo computes with them: rounded to float32 (its storage), then
    multiplied by ``scale`` in double.

    Parameters
    ----------
    vertices : (n, 3) float
      Coordinates as read from the file.
    scale : (3,) float
      The ``<mesh scale>``.

    Returns
    -------
    vertices : (n, 3) float64
    """
    return _vertices(vertices).astype(np.float32).astype(np.float64) * _scale(scale)


def shared_vertices(triangles: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.intp]]:
    """
    ``(vertices, faces)`` of a triangle soup (n, 3, 3), vertices shared by their exact float32
    bits as MuJoCo's STL decoder shares them (so that ``exact``'s winding check sees the
    mesh's edges).
    """
    flat = np.asarray(triangles, dtype=np.float64).reshape(-1, 3)
    keys = np.ascontiguousarray(flat.astype(np.float32)).view(np.uint32).reshape(-1, 3)
    _, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    return flat[first], inverse.reshape(-1, 3)


def soup_mass_properties(
    triangles: ArrayLike, mode: str, scale: ArrayLike = (1.0, 1.0, 1.0)
) -> MassProperties | None:
    """
    What MuJoCo's mesh inertia ``mode`` gives ``triangles`` (n, 3, 3) at ``scale`` at 1 kg/m³
    (kg/m² for ``shell``), in the mesh's frame: ``mass`` is its volume (area); ``None`` for a
    mesh MuJoCo refuses (no volume, inconsistent winding for ``exact``).
    """
    vertices, faces = shared_vertices(triangles)
    try:
        with np.errstate(all="ignore"):
            value = mesh_mass_properties(vertices, faces, mode, density=1.0, scale=scale)
    except ValueError:
        return None
    return value if np.isfinite(value.mass) and value.mass > 0 else None


def file_mass_properties(
    path: str, mode: str, scale: ArrayLike = (1.0, 1.0, 1.0)
) -> MassProperties | None:
    """
    :func:`soup_mass_properties` of a mesh file's triangles (in metres: the file's unit
    applied), ``None`` when they cannot be read; kept per file state, mode and scale, since
    every rule that weighs a mesh as MuJoCo does asks again.
    """
    stamp = _file_stamp(path)
    if stamp is None:
        return None
    return _file_mass_properties(path, *stamp, mode, _factors(scale))


def file_fitted_primitive(
    path: str, kind: str, mode: str, scale: ArrayLike = (1.0, 1.0, 1.0), fitscale: float = 1.0
) -> tuple[tuple[float, ...], NDArray[np.float64], NDArray[np.float64]] | None:
    """
    :func:`fitted_primitive` of a mesh file's triangles (in metres: the file's unit applied),
    ``None`` when they cannot be read or MuJoCo refuses the mesh; kept as
    :func:`file_mass_properties` keeps its values.
    """
    stamp = _file_stamp(path)
    if stamp is None:
        return None
    return _file_fitted_primitive(path, *stamp, kind, mode, _factors(scale), float(fitscale))


def _file_stamp(path: str) -> tuple[int, int] | None:
    """A file's modification time and size: what a cached value of it is kept under."""
    import os

    try:
        stat = os.stat(path)
    except OSError:
        return None
    return stat.st_mtime_ns, stat.st_size


def _factors(scale: ArrayLike) -> tuple[float, ...]:
    return tuple(float(f) for f in np.broadcast_to(np.asarray(scale, dtype=np.float64), 3))


def _file_triangles(path: str) -> tuple[NDArray[np.float64], float] | None:
    """The triangles MuJoCo builds from a mesh file and its unit, ``None`` when unreadable."""
    from inertia_kit.errors import MeshError
    from inertia_kit.physics.mesh_formats import read_mujoco_triangles

    try:
        return read_mujoco_triangles(path)
    except (MeshError, OSError, ValueError):
        return None


@functools.lru_cache(maxsize=512)
def _file_mass_properties(
    path: str, _mtime: int, _size: int, mode: str, scale: tuple[float, ...]
) -> MassProperties | None:
    read = _file_triangles(path)
    if read is None:
        return None
    triangles, unit = read
    return soup_mass_properties(triangles, mode, unit * np.asarray(scale))


@functools.lru_cache(maxsize=512)
def _file_fitted_primitive(
    path: str,
    _mtime: int,
    _size: int,
    kind: str,
    mode: str,
    scale: tuple[float, ...],
    fitscale: float,
) -> tuple[tuple[float, ...], NDArray[np.float64], NDArray[np.float64]] | None:
    read = _file_triangles(path)
    if read is None:
        return None
    triangles, unit = read
    vertices, faces = shared_vertices(triangles)
    try:
        with np.errstate(all="ignore"):
            return fitted_primitive(
                kind, vertices, faces, mode, scale=unit * np.asarray(scale), fitscale=fitscale
            )
    except ValueError:
        return None


def mesh_frame(
    vertices: ArrayLike, faces: ArrayLike, mode: str = "legacy", *, scale: ArrayLike | None = None
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], float]:
    """
    ``(com, axes, box, measure)`` of a mesh as ``mjCMesh::Process`` leaves it, in the mesh's
    frame: its centre of mass, principal axes (columns, :func:`principal_axes`' order), the
    half-sides of its equivalent inertia box along them, and its volume (area for ``shell``).
    The arguments are :func:`mesh_mass_properties`'; ``ValueError`` for a mesh MuJoCo refuses.
    """
    if mode not in MESH_MODES:
        raise ValueError(f"mode must be one of {', '.join(MESH_MODES)}, got {mode!r}")
    vert = _vertices(vertices)
    if scale is not None:
        vert = vert.astype(np.float32).astype(np.float64)
    face = _faces(faces, len(vert))
    hull = hull_faces(vert) if mode == "convex" or not len(face) else None
    if not len(face):
        face = hull
    if mode == "exact":
        _check_orientation(vert, face)
    if scale is not None:
        factors = _scale(scale)
        if not np.prod(factors) > 0:
            face = face[:, [0, 2, 1]]
            hull = None if hull is None else hull[:, [0, 2, 1]]
        vert = vert * factors

    facecen = _face_centroid(vert, face)
    solid = hull if mode == "convex" else face
    if mode == "shell":
        com = _surface_centre(vert, face, facecen)
    else:
        com = _volume_centre(vert, solid, facecen, absolute=mode == "legacy")
    tensor, measure = _unit_inertia(vert - com, solid, mode)
    eigval, eigvec = principal_axes(tensor)
    if eigval[2] <= 0:
        raise ValueError("eigenvalue of mesh inertia must be positive")
    a, b, c = eigval
    tol = 1.0 - _INEQUALITY_RTOL
    if (
        a + b < c * tol - _INEQUALITY_ATOL
        or a + c < b * tol - _INEQUALITY_ATOL
        or b + c < a * tol - _INEQUALITY_ATOL
    ):
        raise ValueError("eigenvalues of mesh inertia violate A + B >= C")
    with np.errstate(invalid="ignore"):
        box = 0.5 * np.sqrt(6 * np.array([b + c - a, a + c - b, a + b - c]) / measure)
    if np.isnan(box).any():
        # within the tolerance above but negative: MuJoCo takes the root of it
        raise ValueError("the equivalent inertia box has a negative side² (MuJoCo: NaN inertia)")
    return com, eigvec, box, measure


def fitted_primitive(
    kind: str,
    vertices: ArrayLike,
    faces: ArrayLike,
    mode: str = "legacy",
    *,
    scale: ArrayLike | None = None,
    fitscale: float = 1.0,
) -> tuple[tuple[float, ...], NDArray[np.float64], NDArray[np.float64]]:
    """
    ``(size, centre, axes)`` of the primitive ``kind`` MuJoCo fits to a mesh
    (``mjCMesh::FitGeom``, ``fitaabb="false"``): its ``size`` (radii and half-lengths, times
    ``fitscale``) from the mesh's equivalent inertia box, placed at the mesh's centre of mass
    in its principal axes. ``ValueError`` for a kind MuJoCo does not fit, or a mesh it refuses.
    """
    com, axes, box, _ = mesh_frame(vertices, faces, mode, scale=scale)
    if kind == "sphere":
        size: tuple[float, ...] = (float(box.sum()) / 3,)
    elif kind == "capsule":
        radius = float(box[0] + box[1]) / 2
        size = (radius, max(0.0, float(box[2]) - radius / 2))
    elif kind == "cylinder":
        size = (float(box[0] + box[1]) / 2, float(box[2]))
    elif kind in ("ellipsoid", "box"):
        size = tuple(float(b) for b in box)
    else:
        raise ValueError(f"invalid geom type in fitting mesh: {kind}")
    return tuple(v * fitscale for v in size), com, axes


def mesh_mass_properties(
    vertices: ArrayLike,
    faces: ArrayLike,
    mode: str = "legacy",
    *,
    density: float | None = None,
    mass: float | None = None,
    scale: ArrayLike | None = None,
) -> MassProperties:
    """
    Mass properties of a mesh geom as MuJoCo computes them, in the mesh's own frame.

    Mirrors ``mjCMesh::Process`` (centroid of the faces, centre of mass, tensor, eigenvalues
    (:func:`principal_axes`), equivalent inertia box) and the mesh branch of
    ``mjCGeom::Compile`` and ``SetInertia`` (``mass = density · volume``, or the given
    ``mass``; moments ``mass (b_j² + b_k²) / 3``):

    - ``legacy``: each face's pyramid adds its absolute volume; the centre of mass is measured
      from the faces' area-weighted centroid, the volume and tensor from that centre of mass;
    - ``exact``: signed pyramids (any closed, consistently wound surface); refused when two
      faces share a directed edge (inconsistent winding);
    - ``convex``: the signed pyramids of the convex hull of *all* vertices (qhull's, as
      ``MakeGraph`` builds it; here scipy's qhull, oriented outward);
    - ``shell``: mass on the surface, by area: ``mass = density · area``.

    Parameters
    ----------
    vertices : (n, 3) float
      In metres, already scaled (MuJoCo's are a file's float32 values times ``scale``:
      :func:`mujoco_vertices`), or the file's coordinates when ``scale`` is given.
    faces : (m, 3) int
      Vertex indices of each triangle, wound counter-clockwise seen from outside; none (shape
      ``(0, 3)``) for the convex hull's, as MuJoCo does for a mesh without faces.
    mode : {"legacy", "exact", "convex", "shell"}
      The ``<mesh inertia>``.
    density, mass : float
      Exactly one: kg/m³ (kg/m² for ``shell``), or kg. Zero gives a massless geom, as in MuJoCo.
    scale : (3,) float, optional
      The ``<mesh scale>``: ``vertices`` are then rounded to float32 and scaled as MuJoCo does
      it, after the hull and the winding check; a mirroring scale reverses the faces (not the
      hull's too: MuJoCo 4.0.0 integrates the mirrored hull; the 3.x source would refuse it).

    Returns
    -------
    MassProperties
      Mass (kg), centre of mass (m) and the tensor MuJoCo integrates (kg·m²), in the mesh frame.

    Raises
    ------
    ValueError
      For a mesh MuJoCo refuses, in its words where it has them.
    """
    com, eigvec, box, measure = mesh_frame(vertices, faces, mode, scale=scale)
    m = geom_mass(measure, density, mass)
    if m == 0:
        return MassProperties(0.0, com, np.zeros((3, 3)))
    s = box * box
    moments = np.array([m * (s[1] + s[2]) / 3, m * (s[0] + s[2]) / 3, m * (s[0] + s[1]) / 3])
    return MassProperties(m, com, eigvec @ np.diag(moments) @ eigvec.T)


def hull_faces(vertices: ArrayLike) -> NDArray[np.intp]:
    """
    The convex hull of ``vertices`` as outward-wound triangles, refused as ``mjCMesh::MakeGraph``
    refuses colocated, collinear or coplanar vertices.

    qhull triangulates (``Qt``) as MuJoCo's does; the coplanar facets may be split along other
    diagonals than MuJoCo's, which changes the integrals only by rounding.

    Parameters
    ----------
    vertices : (n, 3) float

    Returns
    -------
    faces : (h, 3) int
      Indices into ``vertices``.
    """
    vert = _vertices(vertices)
    _check_hull(vert)
    from scipy.spatial import ConvexHull, QhullError  # scipy only for a hull

    try:
        hull = ConvexHull(vert, qhull_options="Qt")
    except QhullError as error:
        raise ValueError(f"qhull error: {str(error).splitlines()[0]}") from None
    faces = hull.simplices.astype(np.intp)
    a, b, c = (vert[faces[:, i]] for i in range(3))
    inward = np.einsum("ij,ij->i", np.cross(b - a, c - a), hull.equations[:, :3]) < 0
    faces[inward] = faces[inward][:, [0, 2, 1]]
    return faces


def principal_axes(tensor: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """
    The principal moments of a symmetric 3×3 tensor in decreasing order, as MuJoCo's
    ``mjuu_eig3`` orders them, and the right-handed rotation whose columns are their axes.

    These are exact to rounding. MuJoCo's are not quite: its mesh eigen-solver (a Jacobi
    iteration, ``mjuu_eig3`` in the source) stops early, leaving MuJoCo 4.0.0's mesh axes up to
    ~1e-7 rad off these and two nearly equal moments ~1e-9 (relative) off; masses, centres and
    other moments agree to ~1e-11. Its stopping rule is not the 3.x source's (an off-diagonal
    below 1e-12 absolute, or a rotation below ~1.4e-6 rad: measured, 4.0.0 turns a 1 m³ box
    by 3e-7 rad and a 5 mm one at all) nor ``mju_eig3``'s (which turns by 1e-12 rad), so it is
    not copied.

    Returns
    -------
    moments : (3,) float
      Decreasing.
    axes : (3, 3) float
      Columns: the axis of each moment.
    """
    # eigh: symmetric input, best precision; ascending, so reversed
    values, vectors = np.linalg.eigh(np.asarray(tensor, dtype=np.float64))
    values, vectors = values[::-1], vectors[:, ::-1].copy()
    if np.linalg.det(vectors) < 0:
        vectors[:, 2] = -vectors[:, 2]
    return values, vectors


def _vertices(vertices: ArrayLike) -> NDArray[np.float64]:
    vert = np.asarray(vertices, dtype=np.float64)
    if vert.ndim != 2 or vert.shape[1] != 3:
        raise ValueError(f"vertices must be (n, 3), got shape {vert.shape}")
    if len(vert) < 4:
        raise ValueError("at least 4 vertices required")
    if not np.isfinite(vert).all():
        raise ValueError("vertex coordinate is not finite")
    return vert


def _faces(faces: ArrayLike, count: int) -> NDArray[np.intp]:
    face = np.asarray(faces)
    if face.size == 0:
        return np.zeros((0, 3), dtype=np.intp)
    if face.ndim != 2 or face.shape[1] != 3 or not np.issubdtype(face.dtype, np.integer):
        raise ValueError(f"faces must be (m, 3) integers, got {face.dtype} {face.shape}")
    if face.min() < 0 or face.max() >= count:
        raise ValueError(f"a face's vertex index does not exist (vertices: {count})")
    return face.astype(np.intp)


def _scale(scale: ArrayLike) -> NDArray[np.float64]:
    factors = np.asarray(scale, dtype=np.float64)
    if factors.shape != (3,) or not np.isfinite(factors).all():
        raise ValueError(f"scale must be 3 finite numbers, got {factors}")
    return factors


def _dot3(a: NDArray, b: NDArray) -> NDArray:
    return a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1] + a[:, 2] * b[:, 2]


def _triangle(vert: NDArray, face: NDArray) -> tuple[NDArray, NDArray, NDArray]:
    """
    user_mesh.cc's ``triangle`` for every face: area, unit normal and centre. A face whose
    doubled area is below mjMINVAL has area 0 (and its raw normal).
    """
    v1, v2, v3 = vert[face[:, 0]], vert[face[:, 1]], vert[face[:, 2]]
    center = (v1 + v2 + v3) / 3
    b, c = v2 - v1, v3 - v1
    normal = np.stack(
        [
            b[:, 1] * c[:, 2] - b[:, 2] * c[:, 1],
            b[:, 2] * c[:, 0] - b[:, 0] * c[:, 2],
            b[:, 0] * c[:, 1] - b[:, 1] * c[:, 0],
        ],
        axis=1,
    )
    length = np.sqrt(_dot3(normal, normal))
    kept = length >= MJMINVAL
    area = np.where(kept, 0.5 * length, 0.0)
    normal = np.where(kept[:, None], normal / np.where(kept, length, 1.0)[:, None], normal)
    return area, normal, center


def _face_centroid(vert: NDArray, face: NDArray) -> NDArray[np.float64]:
    """``ComputeFaceCentroid``: the faces' area-weighted centroid."""
    area, _, center = _triangle(vert, face)
    total = area.sum()
    if not total >= MJMINVAL:
        raise ValueError("mesh surface area is too small")
    return (area[:, None] * center).sum(axis=0) / total


def _volume_centre(vert: NDArray, face: NDArray, facecen: NDArray, absolute: bool) -> NDArray:
    """``ComputeVolume``: the pyramids' centre of mass, each pyramid with apex ``facecen``."""
    area, normal, center = _triangle(vert, face)
    volume = _dot3(center - facecen, normal) * area / 3
    if absolute:
        volume = np.abs(volume)
    total = volume.sum()
    if not total >= MJMINVAL:
        if total < 0:
            raise ValueError("mesh volume is negative (misoriented triangles)")
        raise ValueError("mesh volume is too small. Try setting inertia to shell")
    return (volume[:, None] * (center * 3.0 / 4.0 + facecen / 4.0)).sum(axis=0) / total


def _surface_centre(vert: NDArray, face: NDArray, facecen: NDArray) -> NDArray:
    """``ComputeSurfaceArea``: the faces' centre (weighted as ``ComputeVolume`` weighs it)."""
    area, _, center = _triangle(vert, face)
    total = area.sum()
    if not total >= MJMINVAL:
        raise ValueError("mesh surface area is too small")
    return (area[:, None] * (center * 3.0 / 4.0 + facecen / 4.0)).sum(axis=0) / total


def _unit_inertia(centred: NDArray, face: NDArray, mode: str) -> tuple[NDArray, float]:
    """
    ``ComputeInertia``: the tensor at unit density about the origin of ``centred`` (the centre
    of mass), and the volume (the area for ``shell``) it re-measures from there.
    """
    area, normal, center = _triangle(centred, face)
    if mode == "shell":
        weight, divisor = area, 12
    else:
        weight, divisor = _dot3(center, normal) * area / 3, 20
        if mode == "legacy":
            weight = np.abs(weight)
    d, e, f = centred[face[:, 0]], centred[face[:, 1]], centred[face[:, 2]]
    products = []
    for i, j in ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)):
        pair = 2 * (d[:, i] * d[:, j] + e[:, i] * e[:, j] + f[:, i] * f[:, j])
        cross = d[:, i] * e[:, j] + d[:, j] * e[:, i] + d[:, i] * f[:, j]
        cross = cross + d[:, j] * f[:, i] + e[:, i] * f[:, j] + e[:, j] * f[:, i]
        products.append((weight / divisor * (pair + cross)).sum())
    p = products
    tensor = np.array(
        [
            [p[1] + p[2], -p[3], -p[4]],
            [-p[3], p[0] + p[2], -p[5]],
            [-p[4], -p[5], p[0] + p[1]],
        ]
    )
    return tensor, float(weight.sum())


def _check_orientation(vert: NDArray, face: NDArray) -> None:
    """
    ``Process``'s half-edge check: no two faces (of area above √mjMINVAL, before the scale)
    share a directed edge.
    """
    area, _, _ = _triangle(vert, face)
    kept = face[area > math.sqrt(MJMINVAL)]
    edges = np.concatenate([kept[:, [0, 1]], kept[:, [1, 2]], kept[:, [2, 0]]])
    unique, counts = np.unique(edges, axis=0, return_counts=True)
    if (counts > 1).any():
        a, b = unique[np.argmax(counts > 1)] + 1
        raise ValueError(
            "faces of mesh have inconsistent orientation. Please check the faces containing "
            f"the vertices {a} and {b}."
        )


def _check_hull(vert: NDArray) -> None:
    """``MakeGraph``'s checks before qhull, with its thresholds."""
    offsets = vert[1:] - vert[0]
    dist = np.sqrt(_dot3(offsets, offsets))
    distinct = np.flatnonzero(dist > MJMINVAL)
    if not len(distinct):
        raise ValueError("mesh has colocated vertices, cannot compute convex hull")
    v1 = distinct[0]
    len1, edge1 = dist[v1], offsets[v1]
    others = np.delete(np.arange(len(offsets)), v1)
    others = others[dist[others] >= MJMINVAL]
    normals = np.cross(edge1, offsets[others])
    norms = np.sqrt(_dot3(normals, normals))
    plane = np.flatnonzero(norms > MJMINVAL * len1 * dist[others])
    if not len(plane):
        raise ValueError("mesh has collinear vertices, cannot compute convex hull")
    normal = normals[plane[0]] / norms[plane[0]]
    heights = vert @ normal
    if not (np.abs(heights - normal @ vert[0]) > MJMINVAL * len1).any():
        raise ValueError("mesh has coplanar vertices, cannot compute convex hull")


def geom_mass(measure: float, density: float | None, mass: float | None) -> float:
    """
    ``mjCGeom::Compile``: the geom's mass from its volume (area for a shell) and exactly one
    of ``density`` or ``mass``. Zero gives zero; MuJoCo ignores a ``mass`` of a geom of volume
    at most mjEPS (the geom stays massless).
    """
    if (density is None) == (mass is None):
        raise ValueError("give exactly one of density (kg/m³) or mass (kg)")
    value = float(mass if mass is not None else density)  # type: ignore[arg-type]
    name = "mass" if mass is not None else "density"
    if not (math.isfinite(value) and value >= 0):
        raise ValueError(f"{name} must be finite and not negative, got {value}")
    if value == 0 or (mass is not None and not measure > MJEPS):
        return 0.0
    return value if mass is not None else value * measure
