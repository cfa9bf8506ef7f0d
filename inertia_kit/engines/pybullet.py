"""
What PyBullet's ``loadURDF`` does with each link's mass and inertia: a link without
``<inertial>`` gets 1 kg, and every tensor is recomputed from the collision shapes' bounding box
unless the model is loaded with ``URDF_USE_INERTIA_FROM_FILE`` (with that flag, a tensor that
fails Bullet's test is zeroed).
"""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
from inertia_kit.analysis.tensors import compare_tensors
from inertia_kit.description import model
from inertia_kit.description.model import WORLD
from inertia_kit.engines.lumping import written_tensor
from inertia_kit.engines.vocabulary import Event, Verdict, event
from inertia_kit.physics.formatting import fmt, vector_text
from inertia_kit.physics.frames import inverse, rpy_matrix, transform
from inertia_kit.physics.mass import MassProperties

ENGINE = "pybullet"
MARGIN = 0.001  # m: URDF2Bullet gUrdfDefaultCollisionMargin
NO_INERTIAL = (
    "No inertial data for link, using mass=1, localinertiadiagonal = 1,1,1, identity local "
    "inertial frame"
)


def _box(mass: float, half: NDArray[np.float64]) -> NDArray[np.float64]:
    lx, ly, lz = 2.0 * half
    return mass / 12.0 * np.array([ly * ly + lz * lz, lx * lx + lz * lz, lx * lx + ly * ly])


def _shape_box(shape: model.Shape, mesh_bounds) -> tuple[NDArray, NDArray, float] | None:
    """
    (center, half extents, padding) of a shape's bounding box in its own frame as Bullet caches
    it; ``padding`` is what ``calculateLocalInertia`` of a lone hull adds to it.
    """
    g = shape.geometry
    if isinstance(g, model.Box) and isinstance(g.size, tuple):
        return np.zeros(3), 0.5 * np.array(g.size), 0.0
    if isinstance(g, model.Sphere) and isinstance(g.radius, float):
        return np.zeros(3), np.full(3, g.radius), 0.0
    if (
        isinstance(g, model.Cylinder)
        and isinstance(g.radius, float)
        and isinstance(g.length, float)
    ):
        # a 32-sided convex hull, whose cached bounding box is two margins larger
        return np.zeros(3), np.array([g.radius, g.radius, 0.5 * g.length]) + 2 * MARGIN, MARGIN
    if isinstance(g, model.Capsule) and isinstance(g.radius, float) and isinstance(g.length, float):
        return np.zeros(3), np.array([g.radius, g.radius, g.radius + 0.5 * g.length]), 0.0
    if isinstance(g, model.Mesh) and mesh_bounds is not None:
        lo, hi = np.asarray(mesh_bounds, dtype=np.float64)
        return 0.5 * (lo + hi), 0.5 * (hi - lo) + 2 * MARGIN, MARGIN
    return None


def predicted_inertia(link: LinkAnalysis, mass: float) -> NDArray[np.float64] | None:
    """
    The local inertia diagonal (3,) kg·m² PyBullet computes for ``link`` without
    ``URDF_USE_INERTIA_FROM_FILE``, in the axes of its ``<inertial><origin>``:

    - one collision shape placed exactly at the inertial frame: the shape's own
      ``calculateLocalInertia`` (a box, 2/5 m r² for a sphere, the bounding box of the 32-sided
      hull plus 3 mm for a cylinder, of the vertices plus 3 mm for a mesh, of the capsule);
    - otherwise the box inertia of the compound's bounding box in the inertial frame (each
      shape's cached box, 2 mm larger for hulls, rotated as a box) plus a 1 mm margin.

    ``None`` when a shape is not understood (unknown geometry, invalid numbers, mesh not read).
    """
    inertial = link.link.inertial
    frame = np.eye(4)
    if inertial is not None:
        xyz, rpy = inertial.origin.xyz, inertial.origin.rpy
        if not isinstance(xyz, tuple) or not isinstance(rpy, tuple):
            return None
        frame = transform(xyz, rpy)
    to_inertial = inverse(frame)
    solids = link.collision.solids if link.link.collisions else ()
    boxes = []
    for index, shape in enumerate(link.link.collisions):
        origin = shape.origin
        if not isinstance(origin.xyz, tuple) or not isinstance(origin.rpy, tuple):
            return None
        bounds = None
        if isinstance(shape.geometry, model.Mesh):
            solid = solids[index] if index < len(solids) else None
            if solid is None or solid.mesh is None:
                return None
            bounds = solid.mesh.bounds
        local = _shape_box(shape, bounds)
        if local is None:
            return None
        boxes.append((to_inertial @ transform(origin.xyz, origin.rpy), shape, local))
    if len(boxes) == 1 and np.allclose(boxes[0][0], np.eye(4), rtol=0.0, atol=1e-12):
        _, shape, (_, half, margin) = boxes[0]
        if isinstance(shape.geometry, model.Sphere):
            return np.full(3, 0.4 * mass * half[0] ** 2)
        # a hull's calculateLocalInertia pads its (already padded) box once more
        return _box(mass, half + margin)
    if not boxes:
        return _box(mass, np.full(3, MARGIN))
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    for pose, _, (center, half, _padding) in boxes:
        rotation = pose[:3, :3]
        c = rotation @ center + pose[:3, 3]
        h = np.abs(rotation) @ half
        lo, hi = np.minimum(lo, c - h), np.maximum(hi, c + h)
    return _box(mass, 0.5 * (hi - lo) + MARGIN)


def bad_tensor(tensor: NDArray[np.float64]) -> bool:
    """BulletUrdfImporter's test before "Bad inertia tensor properties" (no tolerance)."""
    if tensor[0, 1] == 0 and tensor[0, 2] == 0 and tensor[1, 2] == 0:
        x, y, z = np.diag(tensor)
    else:
        x, y, z = np.linalg.eigvalsh(tensor)
    return bool(x < 0 or x > y + z or y < 0 or y > x + z or z < 0 or z > x + y)


def events(robot: RobotAnalysis, *, factor: float, inertia_from_file: bool) -> Iterator[Event]:
    """
    Link by link: ``no-inertial`` (1 kg, and a computed or unit inertia), then, with
    ``inertia_from_file`` (``loadURDF(..., flags=URDF_USE_INERTIA_FROM_FILE)``), ``zeroed`` (a
    tensor that fails Bullet's test), else ``recomputed`` (the tensor computed from the
    bounding box is more than ``factor`` times the declared one about some axis, or the declared
    one is not positive definite: a smaller difference is not worth telling).
    """
    for link in robot.links:
        if link.name == WORLD:
            continue
        inertial = link.link.inertial
        if inertial is None:
            yield _no_inertial(link, inertia_from_file)
            continue
        mass = inertial.mass
        values = inertial.tensor_values().values()
        if not isinstance(mass, float) or not math.isfinite(mass):
            continue
        if not all(isinstance(v, float) for v in values):
            continue
        tensor = written_tensor(values)  # type: ignore[arg-type]  # floats, checked above
        bad = bad_tensor(tensor)
        zeroed = f"Bad inertia tensor properties, setting inertia to zero for link: {link.name}"
        if inertia_from_file:
            if bad:
                yield event(
                    ENGINE,
                    Verdict.CHANGES,
                    "zeroed",
                    "zeroes its inertia",
                    zeroed,
                    inertial.inertia_source or inertial.source,
                    link=link.name,
                    claim="the tensor fails Bullet's test",
                    why="Loaded with URDF_USE_INERTIA_FROM_FILE, PyBullet sets the inertia of "
                    f"link `{link.name}` to (0, 0, 0): its principal moments are not all ≥ 0 "
                    "and each at most the sum of the other two",
                    inertia_diagonal=[0.0, 0.0, 0.0],
                )
            continue
        if mass > 0:
            yield from _recomputed(link, inertial, mass, tensor, factor, zeroed if bad else None)


def stand_in(link: LinkAnalysis) -> MassProperties:
    """What PyBullet simulates for a link without ``<inertial>``: 1 kg at the link origin, the
    inertia diagonal of its collision shapes (a unit one when they are not understood)."""
    diagonal = predicted_inertia(link, 1.0)
    return MassProperties(1.0, np.zeros(3), np.diag(np.ones(3) if diagonal is None else diagonal))


def _no_inertial(link: LinkAnalysis, inertia_from_file: bool) -> Event:
    diagonal = np.ones(3) if inertia_from_file else predicted_inertia(link, 1.0)
    basis = "" if diagonal is None else f" and inertia diagonal {vector_text(diagonal)} kg·m²"
    return event(
        ENGINE,
        Verdict.CHANGES,
        "no-inertial",
        "gives it 1 kg",
        NO_INERTIAL,
        link.link.source,
        link=link.name,
        claim="no <inertial>",
        why=f"Link `{link.name}` has no <inertial>: PyBullet gives it a mass of 1 kg{basis}"
        + ("" if inertia_from_file else " from its collision shapes"),
        mass=1.0,
        inertia_diagonal=None if diagonal is None else diagonal.tolist(),
    )


def _recomputed(
    link: LinkAnalysis,
    inertial: model.Inertial,
    mass: float,
    tensor: NDArray[np.float64],
    factor: float,
    zeroed: str | None,
) -> Iterator[Event]:
    """The tensor PyBullet computes in place of the declared one, when it differs enough."""
    predicted = predicted_inertia(link, mass)
    if predicted is None:
        return
    comparison = compare_tensors(tensor, np.diag(predicted))
    if comparison is not None and comparison.factor <= factor:
        return
    differs = (
        "the declared tensor is not positive definite"
        if comparison is None
        else f"{fmt(comparison.factor, 3)}× the declared moment about some axis"
    )
    shapes = len(link.link.collisions)
    basis = (
        "the bounding box of its collision shape"
        if shapes == 1
        else f"the bounding box of its {shapes} collision shapes"
        if shapes
        else "no collision shape (a 2 mm box)"
    )
    yield event(
        ENGINE,
        Verdict.CHANGES,
        "recomputed",
        "recomputes its inertia",
        zeroed,
        inertial.inertia_source or inertial.source,
        link=link.name,
        claim="the declared one not positive definite"
        if comparison is None
        else f"{fmt(comparison.factor, 3)}× the declared one",
        why=f"Unless loaded with URDF_USE_INERTIA_FROM_FILE, PyBullet replaces the inertia of "
        f"link `{link.name}` by {vector_text(predicted)} kg·m² (in its <inertial> axes) from "
        f"{basis}, {differs}" + ("; with that flag it zeroes the tensor" if zeroed else ""),
        inertia_diagonal=predicted.tolist(),
        rotation=rpy_matrix(inertial.origin.rpy).tolist()
        if isinstance(inertial.origin.rpy, tuple)
        else None,
    )
