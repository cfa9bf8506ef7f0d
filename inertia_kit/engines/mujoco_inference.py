"""
What MuJoCo's compiler makes of each body's mass properties in an MJCF model (the model's
``Robot.inference``, its ``<compiler>``; as ``mjCBody::Compile`` and ``InertiaFromGeom`` do it):
the written ``<inertial>``, or the sum of the body's geoms in the compiler's group range (each
at its own ``mass`` or ``density``, meshes by their ``inertia`` mode: no union, overlaps count
twice), then ``boundmass``/``boundinertia`` and ``balanceinertia``, or the error the compiler
stops with. (A URDF's import is :mod:`.mujoco_compiler`'s.)
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from inertia_kit.analysis.geometry import Solid
from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
from inertia_kit.description import model
from inertia_kit.engines.mujoco_compiler import GEOM_DENSITY
from inertia_kit.engines.mujoco_files import Prediction, change, refusal
from inertia_kit.engines.mujoco_meshes import DEFAULT_MESH_INERTIA, mesh_unit
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.mass import MassProperties

#: MuJoCo's mjMINVAL: the smallest mass and moment a moving body may have
MIN_VALUE = 1e-15
#: MuJoCo's mjEPS: the smallest principal moment a ``fullinertia`` may have
EPS = 1e-14

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
    if weigh is None:  # the default weighing: once per robot, whichever rule asks first
        return analysis.fact("mujoco-compiled", lambda a: _compile(a, weigh_geom))
    return _compile(analysis, weigh)


def _compile(analysis: RobotAnalysis, weigh: GeomWeigher) -> dict[str, Compiled]:
    robot = analysis.robot
    inference = robot.inference
    if inference is None:
        return {}
    bodies = {
        link.name: _compiled(link, inference, weigh)
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
        bodies[joint.child] = Compiled(None, body.inferred, body.raised, body.balanced, MINVAL)
    return _scaled_to_total(bodies, inference.total_mass)


def _scaled_to_total(bodies: dict[str, Compiled], total: float | None) -> dict[str, Compiled]:
    """``settotalmass``: every body's mass and tensor scaled by one factor, so that the masses
    add up to ``total`` (MuJoCo's ``mj_setTotalmass``, after the compile)."""
    weighed = [b.mass_properties for b in bodies.values() if b.mass_properties is not None]
    now = sum(p.mass for p in weighed)
    if total is None or not total > 0 or not now > 0:
        return bodies
    factor = total / now
    return {
        name: body
        if body.mass_properties is None
        else dataclasses.replace(
            body,
            mass_properties=MassProperties(
                body.mass_properties.mass * factor,
                body.mass_properties.com,
                body.mass_properties.inertia * factor,
            ),
        )
        for name, body in bodies.items()
    }


def _weightless(body: Compiled) -> bool:
    """Whether a compiled body has no mass or a moment below mjMINVAL (a refused one: no)."""
    properties = body.mass_properties
    if properties is None:
        return False
    return properties.mass < MIN_VALUE or properties.principal_moments.min() < MIN_VALUE


def _compiled(link: LinkAnalysis, inference: model.Inference, weigh: GeomWeigher) -> Compiled:
    inferred = infers(link.link, inference)
    if not inferred:
        inertial = link.link.inertial
        properties = link.declared if inertial is not None else MassProperties(0.0)
        if properties is None:
            return Compiled(None, False)
        full = inertial is not None and inertial.tensor_form == "fullinertia"
        if full and properties.principal_moments.min() < EPS:
            message = "error 'inertia must have positive eigenvalues' in fullinertia"
            return Compiled(None, False, refusal=message)
        return _bounded(properties, inference, False)
    solids = _counted_solids(link, inference)
    weighed = [(solid.shape, weigh(solid)) for solid in solids]
    unknown = tuple(shape for shape, properties in weighed if properties is None)
    if unknown:
        return Compiled(None, True, unknown=unknown)
    # MuJoCo 4 sums the geoms that weigh something; with none, the body weighs nothing
    parts = [p for _, p in weighed if p is not None and p.mass > 0]
    total = sum(parts[1:], parts[0]) if parts else MassProperties(0.0)
    return _bounded(total, inference, True)


def _counted_solids(link: LinkAnalysis, inference: model.Inference) -> list[Solid]:
    """The link's geoms the compiler counts (its group range), as solids."""
    solids = (*link.visual.solids, *link.collision.solids)
    return [solid for solid in solids if counted(solid.shape, inference)]


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
        message = "mass and inertia cannot be negative"
        return Compiled(None, inferred, tuple(raised), refusal=message)
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
    volume (its area for a shell), placed in the link frame; a mesh by its ``inertia`` mode
    (:mod:`.mujoco_meshes`), a ``shellinertia`` primitive by MuJoCo's shell formulas. ``None``
    for what has no solid, or a mesh MuJoCo refuses.
    """
    shape = solid.shape
    unit = solid.unit
    if unit is None:
        return None
    if solid.mesh is not None:
        mode = getattr(shape.geometry, "inertia", None) or DEFAULT_MESH_INERTIA
        # the analysis weighs an MJCF mesh in its mode already, but for its area (shell)
        unit = mesh_unit(solid, mode) if mode == "shell" or shape.shell else unit
    elif shape.shell:
        unit = _shell_unit(shape)
    if unit is None:
        return None
    density = shape.density if isinstance(shape.density, float) else GEOM_DENSITY
    mass = shape.mass if isinstance(shape.mass, float) else density * unit.mass
    if not (unit.mass > 0 and mass > 0):
        return MassProperties(0.0)
    return unit.with_mass(mass)


def _shell_unit(shape: model.Shape) -> MassProperties | None:
    """A ``shellinertia`` primitive at 1 kg/m², in the link frame (``mass`` is its area)."""
    from inertia_kit.physics.frames import transform
    from inertia_kit.physics.mujoco_primitive_inertia import primitive_mass_properties

    geometry = shape.geometry
    sizes: dict[type, tuple[str, object]] = {
        model.Sphere: ("sphere", lambda g: (g.radius,)),
        model.Capsule: ("capsule", lambda g: (g.radius, g.length / 2)),
        model.Cylinder: ("cylinder", lambda g: (g.radius, g.length / 2)),
        model.Box: ("box", lambda g: tuple(v / 2 for v in g.size)),
        model.Ellipsoid: ("ellipsoid", lambda g: tuple(g.radii)),
    }
    kind, size_of = sizes.get(type(geometry), (None, None))
    if kind is None or not isinstance(shape.origin.xyz, tuple):
        return None
    try:
        value = primitive_mass_properties(kind, size_of(geometry), shell=True, density=1.0)
    except (TypeError, ValueError):
        return None
    return value.transformed(transform(shape.origin.xyz, shape.origin.rpy))


# --- what MuJoCo does with the model, as predictions --------------------------------------------

#: a legacy mesh's volume beyond the solid's by more than this share is told (MuJoCo's own
#: documentation warns of the over-count for non-convex meshes)
LEGACY_EXCESS = 0.01


def predictions(analysis: RobotAnalysis) -> list[Prediction]:
    """
    What MuJoCo's compiler does with an MJCF model: the refusals in the order it meets them
    (body by body, then the check on moving bodies), then the silent changes (bounds raising a
    body, ``balanceinertia`` averaging its moments, ``inertiafromgeom="true"`` ignoring a
    written ``<inertial>``, a legacy mesh counting more volume than it encloses, a geom without
    contacts weighed with the colliding ones).
    """
    bodies = compiled(analysis)
    by_name = {link.name: link for link in analysis.links}
    refusals, changes = [], []
    order = sorted(bodies, key=lambda name: bodies[name].refusal == MINVAL)
    for name in order:
        body, link = bodies[name], by_name[name]
        if body.refusal is not None:
            refusals.append(_refusal(link, body))
        else:
            changes.extend(_changes(link, body, analysis.robot.inference))
    return refusals + changes


MINVAL = "mass and inertia of moving bodies must be larger than mjMINVAL"

_REFUSALS = {
    "error 'inertia must have positive eigenvalues' in fullinertia": (
        "body",
        "a principal moment of its fullinertia below mjEPS",
        "its fullinertia has a principal moment below mjEPS = 1e-14 kg·m²",
    ),
    "mass and inertia cannot be negative": (
        "body",
        "a negative mass or moment",
        "its mass or a principal moment is negative",
    ),
    "inertia must satisfy A + B >= C; use 'balanceinertia' to fix": (
        "body",
        "principal moments break A + B ≥ C",
        "its principal moments break A + B ≥ C (MuJoCo allows no tolerance) and the "
        "compiler's balanceinertia is off",
    ),
    MINVAL: (
        "minval",
        "a moving body without mass or inertia",
        "it moves and its mass or a principal moment is below mjMINVAL = 1e-15, and no body "
        "welded to it weighs something",
    ),
}


def _refusal(link: LinkAnalysis, body: Compiled) -> Prediction:
    assert body.refusal is not None
    stage, claim, detail = _REFUSALS[body.refusal]
    inertial = link.link.inertial
    if body.inferred:
        detail += " (inferred from its geoms)"
    source = link.link.source if inertial is None else inertial.source
    return refusal(
        stage,
        link.name,
        body.refusal,
        claim,
        f"MuJoCo's compiler refuses body `{link.name}`: {detail}",
        source,
        {"name": link.name},
    )


def _changes(link: LinkAnalysis, body: Compiled, inference: model.Inference) -> list[Prediction]:
    found = []
    inertial = link.link.inertial
    where = link.link.source if inertial is None else inertial.source
    compiler = inference.source or where
    properties = body.mass_properties
    if "mass" in body.raised and properties is not None:
        found.append(
            change(
                "bound",
                link.name,
                f"raises its mass to boundmass, {fmt(properties.mass)} kg",
                f"the compiler's boundmass = {fmt(inference.min_mass)} kg is more than its mass",
                compiler,
            )
        )
    if "inertia" in body.raised:
        found.append(
            change(
                "bound",
                link.name,
                f"raises its moments to boundinertia, {fmt(inference.min_inertia)} kg·m²",
                "the compiler's boundinertia is more than a principal moment",
                compiler,
            )
        )
    if body.balanced and properties is not None:
        mean = properties.principal_moments.mean()
        found.append(
            change(
                "balance",
                link.name,
                f"replaces its moments by their mean, {fmt(mean)} kg·m² (balanceinertia)",
                "its principal moments break A + B ≥ C and the compiler's balanceinertia "
                "makes all three their mean: an isotropic tensor nobody wrote",
                compiler,
            )
        )
    if inference.from_geometry == "always" and inertial is not None:
        found.append(
            change(
                "inertiafromgeom",
                link.name,
                "ignores its <inertial> for its geoms' (inertiafromgeom)",
                "the compiler's inertiafromgeom=\"true\" makes every body's mass properties "
                "from its geoms, whatever its <inertial> says",
                inertial.source,
            )
        )
    if body.inferred:
        found.extend(_inferred_changes(link, inference))
    return found


def _inferred_changes(link: LinkAnalysis, inference: model.Inference) -> list[Prediction]:
    found = []
    solids = _counted_solids(link, inference)
    for solid in solids:
        mode = getattr(solid.shape.geometry, "inertia", None)
        if solid.mesh is None or mode != "legacy" or solid.unit is None:
            continue
        legacy = solid.unit  # the analysis weighs an MJCF mesh in its mode
        enclosed = solid.mesh.mass_properties(density=1.0).mass
        if not enclosed > 0:
            continue
        excess = legacy.mass / enclosed - 1
        if excess > LEGACY_EXCESS:
            name = getattr(solid.shape.geometry, "filename", "")
            found.append(
                change(
                    "legacy",
                    link.name,
                    f"weighs mesh `{name}` {_percent(excess)} heavier than it encloses",
                    f"its inertia is inferred from its geoms and the mesh's inertia mode is "
                    f"legacy (MuJoCo 4's default), which counts {fmt(legacy.mass)} m³ for the "
                    f"{fmt(enclosed)} m³ the non-convex mesh encloses",
                    solid.shape.source,
                    excess=excess,
                )
            )
    weighing = [s for s in solids if (weigh_geom(s) or MassProperties(0.0)).mass > 0]
    colliding = [s for s in weighing if s.shape.collides]
    for solid in weighing:
        if colliding and solid.shape.collides is False:
            found.append(
                change(
                    "visual",
                    link.name,
                    "weighs a geom without contacts with its colliding ones",
                    f"its inertia is inferred from its geoms, and geom at {solid.shape.source} "
                    "(contype and conaffinity 0: a visual) has a density and is in the "
                    "compiler's inertiagrouprange, so the part is counted twice",
                    solid.shape.source,
                )
            )
    return found


def _percent(share: float) -> str:
    """``6.4 %``, ``210 %``: two significant digits, no exponent."""
    percent = 100 * share
    return f"{percent:.2g} %" if percent < 100 else f"{round(percent)} %"
