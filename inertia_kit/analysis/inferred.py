"""
What a format's engine makes of a body's mass properties when it loads the description
(``Robot.inference``; MJCF's ``<compiler>``, as MuJoCo's ``mjCBody::Compile`` and
``InertiaFromGeom`` do it): the written ``<inertial>``, or the sum of the body's geoms in the
compiler's group range (each at its own ``mass`` or ``density``, meshes by their ``inertia``
mode: no union, overlaps count twice), then ``boundmass``/``boundinertia`` and
``balanceinertia``, or the error the compiler stops with. URDF infers nothing: ``None``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from inertia_kit.description import model
from inertia_kit.physics.mass import MassProperties

#: MuJoCo's mjMINVAL: the smallest mass and moment a moving body may have
MIN_VALUE = 1e-15

#: a shape's mass properties as the engine weighs it, in the link frame; ``None`` when it has
#: none to give (a missing mesh file, an unknown shape)
GeomWeigher = Callable[[model.Shape], "MassProperties | None"]


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


def compiled(
    robot: model.Robot,
    written: Callable[[model.Link], MassProperties | None],
    weigh: GeomWeigher,
) -> dict[str, Compiled]:
    """
    Every body's mass properties as compiled, by name (``None`` for a robot whose format
    infers nothing). ``written`` gives a link's ``<inertial>`` as mass properties in the link
    frame (``None`` when absent or unusable); ``weigh`` each geom's. A moving body (one with a
    joint) must weigh something, unless a welded child does (``mjCModel``'s check).
    """
    inference = robot.inference
    if inference is None:
        return {}
    bodies = {
        link.name: _compiled(link, inference, written(link), weigh)
        for link in robot.links
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


def _compiled(
    link: model.Link,
    inference: model.Inference,
    written: MassProperties | None,
    weigh: GeomWeigher,
) -> Compiled:
    if link.name == model.WORLD:
        return Compiled(None, False)
    inferred = infers(link, inference)
    if not inferred:
        properties = written if link.inertial is not None else MassProperties(0.0)
        if properties is None:
            return Compiled(None, False)
        return _bounded(properties, inference, False)
    shapes = [s for s in (*link.visuals, *link.collisions) if counted(s, inference)]
    weighed = [(shape, weigh(shape)) for shape in shapes]
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


def weigh_primitive(shape: model.Shape) -> MassProperties | None:
    """
    A primitive geom as MuJoCo weighs it (``mjCGeom::Compile``): its ``mass``, else
    ``density`` × volume, solid, placed by its origin; ``None`` for what is not a solid
    primitive with usable sizes.
    """
    from inertia_kit.physics import primitives
    from inertia_kit.physics.frames import transform

    geometry = shape.geometry
    if shape.shell or not isinstance(shape.origin.xyz, tuple):
        return None
    try:
        unit = _unit_primitive(geometry, primitives)
    except (TypeError, ValueError):
        return None
    if unit is None:
        return None
    density = shape.density if isinstance(shape.density, float) else 1000.0
    mass = shape.mass if isinstance(shape.mass, float) else density * unit.mass
    weighed = unit.with_mass(mass) if unit.mass > 0 and mass > 0 else MassProperties(0.0)
    return weighed.transformed(transform(shape.origin.xyz, shape.origin.rpy))


def _unit_primitive(geometry: model.Geometry, primitives) -> MassProperties | None:
    if isinstance(geometry, model.Sphere):
        return primitives.sphere(geometry.radius, density=1.0)
    if isinstance(geometry, model.Capsule):
        return primitives.capsule(geometry.radius, geometry.length, density=1.0)
    if isinstance(geometry, model.Cylinder):
        return primitives.cylinder(geometry.radius, geometry.length, density=1.0)
    if isinstance(geometry, model.Box):
        return primitives.box(geometry.size, density=1.0)
    if isinstance(geometry, model.Ellipsoid):
        return primitives.ellipsoid(geometry.radii, density=1.0)
    return None
