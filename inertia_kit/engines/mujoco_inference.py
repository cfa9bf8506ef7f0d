"""
What MuJoCo's compiler makes of each body's mass properties in an MJCF model (the model's
``Robot.inference``, its ``<compiler>``; as ``mjCBody::Compile`` and ``InertiaFromGeom`` do it):
the written ``<inertial>``, or the sum of the body's geoms in the compiler's group range (each
at its own ``mass`` or ``density``, meshes by their ``inertia`` mode: no union, overlaps count
twice), then ``boundmass``/``boundinertia`` and ``balanceinertia``, or the error the compiler
stops with. (A URDF's import is :mod:`.mujoco_compiler`'s.)
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from inertia_kit.analysis.geometry import Solid
from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
from inertia_kit.description import model
from inertia_kit.engines.mujoco_compiler import GEOM_DENSITY
from inertia_kit.engines.mujoco_meshes import DEFAULT_MESH_INERTIA, mesh_unit
from inertia_kit.physics.mass import MassProperties

#: MuJoCo's mjMINVAL: the smallest mass and moment a moving body may have
MIN_VALUE = 1e-15

#: a geom's mass properties as MuJoCo weighs it, in the link frame; ``None`` when it has none
#: we can compute (a missing mesh file, an unknown shape)
GeomWeigher = Callable[[Solid], "MassProperties | None"]


@dataclass(frozen=True)
class Compiled:
    """
    A body's mass properties as the engine will integrate them, in the link frame.

    ``inferred``: from the geoms (no ``<inertial>``, or the compiler ignores it);
    ``raised``: what the bounds raised (``mass``, ``inertia``); ``balanced``: the moments made
    their mean (``balanceinertia``); ``refusal``: the compiler's error instead (the model does
    not load); ``unknown``: a geom that counts has no mass properties we can compute.
    """

    mass_properties: MassProperties | None
    inferred: bool
    raised: tuple[str, ...] = ()
    balanced: bool = False
    refusal: str | None = None
    unknown: tuple[model.Shape, ...] = ()


def counted(shape: model.Shape, inference: model.Inference) -> bool:
    """Whether the compiler counts ``shape`` when it infers its body's mass properties."""
    low, high = inference.groups
    group = shape.group if shape.group is not None else 0
    return low <= group <= high


def infers(link: model.Link, inference: model.Inference) -> bool:
    """Whether the compiler makes this body's mass properties from its geoms."""
    if inference.from_geometry == "always":
        return True
    return inference.from_geometry == "missing" and link.inertial is None


def compiled(analysis: RobotAnalysis, weigh: GeomWeigher | None = None) -> dict[str, Compiled]:
    """
    Every body's mass properties as compiled, by name (empty for a robot whose format infers
    nothing: URDF). ``weigh`` gives each geom's (default :func:`weigh_geom`). A moving body
    (one with a joint) must weigh something, unless a welded child does (``mjCModel``'s
    check).
    """
    robot = analysis.robot
    inference = robot.inference
    if inference is None:
        return {}
    bodies = {
        link.name: _compiled(link, inference, weigh or weigh_geom)
        for link in analysis.links
        if link.name != model.WORLD
    }
    welded_children: dict[str, list[str]] = {}
    for joint in robot.joints:
        if joint.type == "fixed" and joint.parent is not None and joint.child is not None:
            welded_children.setdefault(joint.parent, []).append(joint.child)
    for joint in robot.joints:
        body = bodies.get(joint.child or "")
        if joint.type == "fixed" or body is None or not _weightless(body):
            continue
        if any(not _weightless(bodies[c]) for c in welded_children.get(joint.child, ())):
            continue
        refusal = "mass and inertia of moving bodies must be larger than mjMINVAL"
        bodies[joint.child] = Compiled(None, body.inferred, body.raised, body.balanced, refusal)
    return bodies


def _weightless(body: Compiled) -> bool:
    """Whether a compiled body has no mass or a moment below mjMINVAL (a refused one: no)."""
    properties = body.mass_properties
    if properties is None:
        return False
    return properties.mass < MIN_VALUE or properties.principal_moments.min() < MIN_VALUE


def _compiled(link: LinkAnalysis, inference: model.Inference, weigh: GeomWeigher) -> Compiled:
    inferred = infers(link.link, inference)
    if not inferred:
        properties = link.declared if link.link.inertial is not None else MassProperties(0.0)
        if properties is None:
            return Compiled(None, False)
        return _bounded(properties, inference, False)
    solids = [
        s for s in (*link.visual.solids, *link.collision.solids) if counted(s.shape, inference)
    ]
    weighed = [(solid.shape, weigh(solid)) for solid in solids]
    unknown = tuple(shape for shape, properties in weighed if properties is None)
    if unknown:
        return Compiled(None, True, unknown=unknown)
    # MuJoCo 4 sums the geoms that weigh something; with none, the body weighs nothing
    parts = [p for _, p in weighed if p is not None and p.mass > 0]
    total = sum(parts[1:], parts[0]) if parts else MassProperties(0.0)
    return _bounded(total, inference, True)


def _bounded(properties: MassProperties, inference: model.Inference, inferred: bool) -> Compiled:
    moments = properties.principal_moments.copy()
    axes = properties.principal_axes
    raised = []
    mass = properties.mass
    if mass < inference.min_mass:
        mass, raised = inference.min_mass, ["mass"]
    if np.any(moments < inference.min_inertia):
        moments = np.maximum(moments, inference.min_inertia)
        raised.append("inertia")
    if mass < 0 or np.any(moments < 0):
        refusal = "mass and inertia cannot be negative"
        return Compiled(None, inferred, tuple(raised), refusal=refusal)
    a, b, c = moments
    balanced = False
    if a + b < c or a + c < b or b + c < a:
        if not inference.balance:
            return Compiled(
                None,
                inferred,
                tuple(raised),
                refusal="inertia must satisfy A + B >= C; use 'balanceinertia' to fix",
            )
        moments = np.full(3, moments.sum() / 3.0)
        balanced = True
    tensor = axes @ np.diag(moments) @ axes.T
    return Compiled(MassProperties(mass, properties.com, tensor), inferred, tuple(raised), balanced)


def weigh_geom(solid: Solid) -> MassProperties | None:
    """
    A geom as MuJoCo weighs it (``mjCGeom::Compile``): its ``mass``, else ``density`` × its
    volume, placed in the link frame; a mesh by its ``inertia`` mode (``legacy``: the
    tetrahedra's absolute volumes, :mod:`.mujoco_meshes`; ``exact``: the solid). ``None`` for
    what we cannot weigh yet (a shell, a ``convex`` or ``shell`` mesh) or what has no solid.
    """
    shape = solid.shape
    unit = solid.unit
    if unit is None or shape.shell:
        return None
    if solid.mesh is not None:
        mode = getattr(shape.geometry, "inertia", None) or DEFAULT_MESH_INERTIA
        if mode == "legacy":
            unit = mesh_unit(solid)
        elif mode != "exact":
            return None
        if unit is None:
            return None
    density = shape.density if isinstance(shape.density, float) else GEOM_DENSITY
    mass = shape.mass if isinstance(shape.mass, float) else density * unit.mass
    if not (unit.mass > 0 and mass > 0):
        return MassProperties(0.0)
    return unit.with_mass(mass)
