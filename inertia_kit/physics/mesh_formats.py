"""
Mesh files read into a triangle surface, in the file's own unit: which formats, and how.

STL is read and integrated in one pass by :func:`.stl.read_stl`, without trimesh (the fast
path); its triangles are read again, through trimesh, only when the surface is not closed.
COLLADA and OBJ are read by :mod:`.collada` and :mod:`.obj_soup` (numpy and lxml: the
triangles trimesh gives, without importing it). PLY, GLB and glTF go through trimesh, whose
scene graph is flattened into one triangle soup. The file's own unit (COLLADA ``<unit meter>``)
is returned, not applied: the caller scales the integrals analytically. trimesh is imported only
for a file that needs it.
:func:`read_mujoco_triangles` reads OBJ without trimesh, into the triangles MuJoCo builds
(:mod:`.obj_polygons`), the ones MuJoCo's mass properties are computed from.

trimesh and pycollada log what they cannot do for a renderer, textures first ("unable to load
bumpmap", with a full traceback, when Pillow is absent or an image file is missing): a texture
is irrelevant to mass. While a file is read, :func:`library_logs_quiet` keeps their records from
the terminal (and from a library user's handlers), passing each on to this module's logger at
DEBUG level, one line without traceback; a file that cannot be read still raises ``MeshError``.
"""

from __future__ import annotations

import contextlib
import math
import os
import threading
from collections.abc import Iterator
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from inertia_kit.errors import MeshError
from inertia_kit.physics.frames import transformed_points
from inertia_kit.physics.numbers import MAX_MAGNITUDE
from inertia_kit.physics.polyhedra import SurfaceIntegrator, integrate
from inertia_kit.physics.stl import binary_triangles, read_stl

if TYPE_CHECKING:
    import logging

    import trimesh

# file suffix -> (trimesh file type, name for messages); STL is read without trimesh
FORMATS = {
    ".stl": ("stl", "STL"),
    ".obj": ("obj", "Wavefront OBJ"),
    ".dae": ("dae", "COLLADA"),
    ".ply": ("ply", "PLY"),
    ".glb": ("glb", "binary glTF"),
    ".gltf": ("gltf", "glTF"),
}

#: The largest mesh file read whole (every format trimesh reads, which holds several times the
#: file in memory, and ASCII STL); a binary STL is streamed, and may be up to MAX_STL_BYTES.
MAX_MESH_BYTES = 256 << 20
#: The largest binary STL integrated (streamed: memory bounded; 4 GB is 86 M triangles, ~4 s).
MAX_STL_BYTES = 4 << 30

# what to do about a MeshError of each kind, for messages that do not say it yet
ADVICE = {
    "not-found": "check the path and the package it names",
    "unreadable": "re-export it from the CAD tool as a binary STL",
    "empty": "export the part's solid body",
}


def read_surface(
    path: str | Path,
) -> tuple[
    SurfaceIntegrator,
    NDArray[np.float64] | None,
    float,
    tuple[NDArray[np.float64], NDArray[np.intp]] | None,
]:
    """
    The surface a mesh file holds, integrated in the file's own unit.

    Parameters
    ----------
    path : str or Path
      STL (binary or ASCII), OBJ, DAE, PLY, GLB or glTF file.

    Returns
    -------
    integrator : SurfaceIntegrator
      Volume integrals, closure and bounds of every triangle, in the file's unit.
    triangles : (n, 3, 3) float or None
      The triangles, in the file's unit; ``None`` for a closed STL, which is not read twice
      (they are needed only to repair or replace a surface that is not closed).
    unit_scale : float
      Metres per file unit.
    shared : ((m, 3) float, (n, 3) int) or None
      For a COLLADA file, the vertices the triangles share and their faces
      (``vertices[faces]`` is ``triangles``): its distinct corners are found among the
      vertices, several times fewer than the corners (:func:`.mesh_closure.classify`).

    Raises
    ------
    MeshError
      ``not-found`` for a missing file; ``unreadable`` for a corrupt file or an unsupported
      format; ``empty`` for a file with no triangles.
    """
    file, suffix = _readable(path)
    if suffix == ".dae":
        from inertia_kit.physics.collada import read_collada_shared

        vertices, faces, unit_scale = read_collada_shared(_read_bytes(file), file)
        triangles = vertices[faces]
        return integrate(triangles), triangles, unit_scale, (vertices, faces)
    if suffix != ".stl":
        triangles, unit_scale = _read_triangles(file, suffix)
        return integrate(triangles), triangles, unit_scale, None
    try:
        integrator = read_stl(file)
    except OSError as error:
        raise _cannot_read(path, error) from None
    except MeshError as error:
        raise MeshError(error.path, error.kind, f"{error.message}; {ADVICE[error.kind]}") from None
    triangles = None if integrator.closed else _open_stl_triangles(file)
    return integrator, triangles, 1.0, None


def _open_stl_triangles(file: Path) -> NDArray[np.float64]:
    """The triangles of an STL whose surface is not closed: a binary one's records as trimesh
    reads them (:func:`.stl.binary_triangles`, without importing trimesh, which costs more
    than reading a robot's meshes), an ASCII one through trimesh."""
    _check_size(file, MAX_MESH_BYTES)  # read whole, and held several times over
    try:
        triangles = binary_triangles(file)
    except OSError as error:
        raise _cannot_read(file, error) from None
    return _read_scene(file, ".stl")[0] if triangles is None else triangles


def read_triangles(path: str | Path) -> tuple[NDArray[np.float64], float]:
    """
    Every triangle of a mesh file, read as :func:`read_surface` reads it (STL too, through
    trimesh), for a display: ``(n, 3, 3)`` triangles in the file's unit, and metres per unit.

    Raises ``MeshError`` as :func:`read_surface` does.
    """
    file, suffix = _readable(path)
    return _read_triangles(file, suffix)


def _read_triangles(file: Path, suffix: str) -> tuple[NDArray[np.float64], float]:
    """A file's triangles: COLLADA and OBJ as trimesh reads them, without it (:mod:`.collada`,
    :mod:`.obj_soup`); the other formats through trimesh."""
    if suffix == ".dae":
        from inertia_kit.physics.collada import read_collada

        return read_collada(_read_bytes(file), file)
    if suffix == ".obj":
        return _read_obj(file, as_mujoco=False), 1.0
    return _read_scene(file, suffix)


def read_mujoco_triangles(path: str | Path) -> tuple[NDArray[np.float64], float]:
    """
    The triangles MuJoCo builds from a mesh file, which its mass properties are computed from:
    as :func:`read_triangles`, but for OBJ those of MuJoCo's OBJ decoder (:mod:`.obj_polygons`:
    tinyobjloader's triangulation of quads and polygons, and the first object or group only; an
    OBJ file has no unit: 1.0), read without trimesh.

    Raises ``MeshError`` as :func:`read_surface` does.
    """
    file, suffix = _readable(path)
    if suffix == ".obj":
        return _read_obj(file), 1.0
    return _read_scene(file, suffix)


def _read_obj(path: Path, as_mujoco: bool = True) -> NDArray[np.float64]:
    """
    The triangles of an OBJ file: those MuJoCo builds (:mod:`.obj_polygons`, see
    :func:`read_mujoco_triangles`), or, not ``as_mujoco``, those trimesh gives
    (:mod:`.obj_soup`: every object, its faces fanned), read without trimesh.
    """
    name = FORMATS[".obj"][1]
    data = _read_bytes(path)
    try:
        with np.errstate(all="ignore"):
            if as_mujoco:
                from inertia_kit.physics.obj_polygons import obj_triangles

                vertices, faces = obj_triangles(data)
                triangles = vertices[faces]
            else:
                from inertia_kit.physics.obj_soup import obj_soup

                triangles = obj_soup(data)
    except (ValueError, OverflowError, MemoryError) as error:
        text = str(error).strip().splitlines()[0][:200] if str(error).strip() else ""
        detail = f"{type(error).__name__}: {text}".rstrip(": ")
        raise MeshError(
            path,
            "unreadable",
            f"cannot read the file as {name} ({detail}); re-export it, or convert it to STL",
        ) from None
    if not len(triangles):
        raise MeshError(
            path, "empty", f"the {name} file holds no triangles; export the part's solid body"
        )
    return _usable(triangles, path, name)


def _usable(triangles: NDArray[np.float64], path: Path, name: str) -> NDArray[np.float64]:
    """``triangles``, unless a coordinate is not finite or beyond ±``MAX_MAGNITUDE`` (1e50, the
    project's bound on every position: physics.numbers), whose squares and cubes the
    integrals would overflow (an OBJ of ``v 1e200 0 0`` lines was an internal error)."""
    if not np.isfinite(triangles).all():
        raise MeshError(path, "unreadable", f"the {name} file holds non-finite vertex coordinates")
    if len(triangles) and float(np.abs(triangles).max()) > MAX_MAGNITUDE:
        raise MeshError(
            path,
            "unreadable",
            f"the {name} file holds vertex coordinates beyond ±{MAX_MAGNITUDE:g}: no part is "
            "that large; re-export it in metres or millimetres",
        )
    return triangles


def _cannot_read(path: str | Path, error: OSError) -> MeshError:
    return MeshError(path, "unreadable", f"cannot read the file ({error}); check its permissions")


def _read_bytes(path: Path) -> bytes:
    """A mesh file's bytes, at most :data:`MAX_MESH_BYTES` (``MeshError`` beyond, or when it
    cannot be read)."""
    from inertia_kit.reading import open_regular, read_at_most

    _check_size(path, MAX_MESH_BYTES)
    try:
        with open_regular(path) as stream:  # a pipe swapped in since _readable never blocks
            data = read_at_most(stream, MAX_MESH_BYTES)
    except OSError as error:
        raise _cannot_read(path, error) from None
    if len(data) > MAX_MESH_BYTES:  # grown since it was measured
        raise MeshError(path, "unreadable", "the mesh file grew while it was read")
    return data


def _readable(path: str | Path) -> tuple[Path, str]:
    """The file and its lower-case suffix; ``MeshError`` when it is missing or not a mesh."""
    file = Path(path)
    # os.path: False in a folder that may not be searched, where Path.is_file raises
    if not os.path.isfile(file):
        what = "is a directory, not a mesh file" if os.path.isdir(file) else "does not exist"
        raise MeshError(
            path, "not-found", f"the mesh file {what}; check the path and the package it names"
        )
    suffix = file.suffix.lower()
    _check_size(file, MAX_STL_BYTES if suffix == ".stl" else MAX_MESH_BYTES)
    if suffix not in FORMATS:
        raise MeshError(
            path,
            "unreadable",
            f"unsupported mesh format `{file.suffix or '(no suffix)'}`, expected one of "
            f"{', '.join(FORMATS)}; convert the mesh to STL",
        )
    return file, suffix


def _check_size(file: Path, limit: int) -> None:
    """``MeshError`` for a file larger than ``limit`` bytes (before reading any of it)."""
    from inertia_kit.reading import size_text

    try:
        size = file.stat().st_size
    except OSError as error:
        raise MeshError(file, "unreadable", f"cannot read the file ({error})") from None
    if size > limit:
        raise MeshError(
            file,
            "unreadable",
            f"the mesh file is larger than {size_text(limit)} (nothing was read); decimate it, "
            "or give a simpler collision mesh",
        )


def _bounded_resolver(path: Path):
    """
    A trimesh resolver for the files a mesh names (a glTF's buffers, an OBJ's materials): only
    below the mesh's folder (trimesh 5 does that, 4 does not), only regular files, each at
    most :data:`MAX_MESH_BYTES`.
    """
    import os

    from trimesh.resolvers import FilePathResolver

    from inertia_kit.errors import InputError
    from inertia_kit.reading import read_regular

    class Bounded(FilePathResolver):
        def get(self, name: str) -> bytes:
            try:
                folder = Path(self.parent).resolve()
                for candidate in (name.strip(), name.strip().lstrip("/"), os.path.basename(name)):
                    target = (folder / candidate).resolve()
                    if target.is_relative_to(folder) and target.exists():
                        return read_regular(target, MAX_MESH_BYTES, name, what="mesh file")
            except (OSError, RuntimeError, ValueError) as error:  # a loop of links, a NUL
                raise FileNotFoundError(f"{name}: {error}") from None
            except InputError as error:
                raise ValueError(str(error)) from None
            raise FileNotFoundError(name)

        def namespaced(self, namespace: str) -> Bounded:
            return Bounded(os.path.join(self.parent, namespace))

    return Bounded(str(path))


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
        with library_logs_quiet(path):
            _check_size(path, MAX_MESH_BYTES)  # read whole, and held several times over
            scene = trimesh.load_scene(
                str(path), file_type=file_type, resolver=_bounded_resolver(path), process=False
            )
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
    return _usable(np.concatenate(parts), path, name), factors.pop()


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
        vertices = transformed_points(np.asarray(geometry.vertices, dtype=np.float64), matrix)
        faces = np.asarray(geometry.faces)
        if np.linalg.det(matrix[:3, :3]) < 0:
            # a mirroring node turns the winding inside-out: undo it, as a renderer does
            faces = faces[:, ::-1]
        parts.append(vertices[faces])
        units.append(geometry.units or "meters")
    return parts, units


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


# --- the logs of trimesh and pycollada ---------------------------------------------------------

#: The loggers whose records a read keeps from the terminal, with every logger below them.
LIBRARY_LOGGERS = ("trimesh", "collada")


class _QuietWhileReading:
    """
    A logger-level filter on each library logger: while the current thread is inside
    :func:`library_logs_quiet`, a record is passed on to this module's logger (DEBUG, one line)
    and dropped; otherwise, and in every other thread, it passes untouched. (Not a subclass of
    ``logging.Filter``: logging asks only for ``filter``, and importing logging costs start-up.)
    """

    def __init__(self) -> None:
        self.reading = threading.local()

    def filter(self, record: logging.LogRecord) -> bool:
        path = getattr(self.reading, "path", None)
        if path is None:
            return True
        message = record.getMessage().strip()
        if record.exc_info and record.exc_info[1] is not None:
            error = record.exc_info[1]
            message = f"{message} ({type(error).__name__}: {str(error).strip()[:200]})"
        import logging

        logging.getLogger(__name__).debug("%s (reading %s): %s", record.name, path, message)
        return False


_QUIET = _QuietWhileReading()


@contextlib.contextmanager
def library_logs_quiet(path: str | Path) -> Iterator[None]:
    """
    While reading ``path`` in this thread, keep the records of trimesh's and pycollada's loggers
    from every handler (the terminal's last resort, a library user's own), passing each on to
    this module's logger at DEBUG level without its traceback.

    No global logging setting changes: a filter is attached to those loggers (once; it lets
    every record through outside this context and in other threads), and their levels,
    handlers and propagation stay as the user set them.
    """
    _attach()
    reading = _QUIET.reading
    outer = getattr(reading, "path", None)
    reading.path = str(path)
    try:
        yield
    finally:
        reading.path = outer


def _attach() -> None:
    """The filter on every logger of :data:`LIBRARY_LOGGERS` and below, those made since too
    (a few hundred dictionary items: nothing beside reading a file)."""
    import logging  # here: trimesh has imported it already

    for name, logger in list(logging.Logger.manager.loggerDict.items()):
        if isinstance(logger, logging.Logger) and name.split(".", 1)[0] in LIBRARY_LOGGERS:
            logger.addFilter(_QUIET)  # once: addFilter skips a filter already there
