"""
MuJoCo's compiler on a URDF: the bodies it makes of the links, each body's inertia and geoms
(``mjCBody::Compile``), the fusion of welded links into the moving body above them
(``fusestatic``, on for URDF) and the last check on moving bodies (mjMINVAL).

The checks share one mutable tree of bodies: compiling a body sets the mass properties that
fusing adds up and the last check reads, or marks them unknown (a value we cannot predict), so
they stay together in one module.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
from inertia_kit.description import model
from inertia_kit.description.model import WORLD
from inertia_kit.engines.lumping import joint_pose, written_tensor
from inertia_kit.engines.mujoco_files import Prediction, change, parseable, refusal
from inertia_kit.engines.mujoco_meshes import DEFAULT_MESH_INERTIA, mesh_unit
from inertia_kit.physics.formatting import fmt, vector_text
from inertia_kit.physics.frames import transform
from inertia_kit.physics.mass import MassProperties

# MuJoCo's constants (include/mujoco/mjtnum.h): mjMINVAL bounds the mass and principal moments
# of a moving body; mjEPS the smallest eigenvalue of a full inertia (user_util.cc)
MJMINVAL = 1e-15
MJEPS = 1e-14
# the density <geom> takes by default, kg/m³: what a link without <inertial> is given
GEOM_DENSITY = 1000.0
MOVING = ("revolute", "continuous", "prismatic", "floating", "planar", "spherical")
KNOWN_JOINTS = (*MOVING, "fixed")


def compile_robot(robot: RobotAnalysis) -> tuple[list[Prediction], list[Prediction]] | None:
    """
    The compiler's refusals in the order it meets them (each body depth first from the root,
    then fusion, then the moving bodies' last check) and its silent changes; ``None`` when
    MuJoCo's importer cannot build the tree (IN040).
    """
    roots = _tree(robot)
    if roots is None:
        return None
    order = [body for root in roots for body in _preorder(root)]
    refusals: list[Prediction] = []
    changes: list[Prediction] = []
    for body in order:
        refusals += _compile(body)
    refusals += _fuse(roots, changes)
    for body in order:
        if body.moving:
            refusals += _minval(body)
    return refusals, changes


# --- bodies ---------------------------------------------------------------------------------


@dataclass
class _Body:
    """A link as a MuJoCo body: its own mass properties (link frame) after compilation."""

    link: LinkAnalysis
    moving: bool
    children: list[_Body] = field(default_factory=list)
    parent: _Body | None = None
    value: MassProperties | None = None  # mass ≥ mjMINVAL; None: massless (or clamped to 0)
    # False: we cannot tell what MuJoCo makes of it (a nan, a mesh we can't read)
    known: bool = True
    inferred: bool = False  # from its collision geometry (no <inertial>)

    @property
    def name(self) -> str:
        return self.link.name


def _tree(robot: RobotAnalysis) -> list[_Body] | None:
    """MuJoCo's bodies: roots in document order, children in joint order; ``world`` is world."""
    names = [link.name for link in robot.links]
    if len(set(names)) != len(names):
        return None
    bodies = {link.name: _Body(link, link.moves) for link in robot.links}
    parent_of: dict[str, str] = {}
    for joint in robot.robot.joints:
        if joint.type not in KNOWN_JOINTS or joint.parent not in bodies:
            return None
        if joint.child not in bodies or joint.child in parent_of:
            return None
        parent_of[joint.child] = joint.parent
        bodies[joint.parent].children.append(bodies[joint.child])
        bodies[joint.child].parent = bodies[joint.parent]
    roots = [bodies[name] for name in names if name not in parent_of]
    reached = sum(len(list(_preorder(root))) for root in roots)
    if reached != len(names):
        return None  # a cycle
    tops: list[_Body] = []
    for root in roots:
        if root.name == WORLD:  # the world body itself: its children hang from the world
            for child in root.children:
                child.parent = None
            tops.extend(root.children)
        else:
            tops.append(root)
    return tops


def _preorder(body: _Body) -> Iterator[_Body]:
    """``body`` and its descendants, each before its children (a stack: a chain of any length)."""
    stack = [body]
    while stack:
        current = stack.pop()
        yield current
        stack.extend(reversed(current.children))


def _eigenvalues(tensor: NDArray[np.float64]) -> NDArray[np.float64]:
    """Ascending; a diagonal tensor's own values (exact, as MuJoCo's Jacobi iteration gives)."""
    if not np.any(tensor - np.diag(np.diag(tensor))):
        return np.sort(np.diag(tensor))
    return np.linalg.eigvalsh(tensor)


def _moments(principal: NDArray[np.float64]) -> str:
    return f"{vector_text(principal)} kg·m²"


def _geom_size(shape: model.Shape) -> int | None:
    """The index MuJoCo names in `size N must be positive in geom`, or ``None``."""
    geometry = shape.geometry
    if isinstance(geometry, model.Box):
        sizes: tuple[model.Number, ...] = geometry.size if isinstance(geometry.size, tuple) else ()
    elif isinstance(geometry, (model.Cylinder, model.Capsule)):
        sizes = (geometry.radius, geometry.length)
    elif isinstance(geometry, model.Sphere):
        sizes = (geometry.radius,)
    else:
        return None
    for index, size in enumerate(sizes):
        if isinstance(size, float) and size <= 0:
            return index
    return None


def _compile(body: _Body) -> list[Prediction]:
    """mjCBody::Compile: the full inertia's eigenvalues, geom sizes, A + B ≥ C; sets the value."""
    link = body.link
    inertial = link.link.inertial
    if inertial is not None:
        values = [inertial.mass, *inertial.tensor_values().values()]
        if (
            not all(isinstance(v, float) for v in values)
            or not isinstance(inertial.origin.xyz, tuple)
            or not isinstance(inertial.origin.rpy, tuple)
        ):
            # nan/inf that MuJoCo reads (or what its parser refused): no value we can predict
            body.known = False
            return []
        written = written_tensor(values[1:])  # type: ignore[arg-type]  # floats, checked above
        zero = not np.any(written)  # all six 0: MuJoCo takes the inertia as undefined
        principal = np.zeros(3) if zero else _eigenvalues(written)
        if not zero and principal[0] < MJEPS:
            return _refuse_body(
                body,
                "error 'inertia must have positive eigenvalues' in fullinertia",
                f"principal moment {fmt(principal[0])} kg·m², below mjEPS",
                f"its principal moments are {_moments(principal)}, the smallest below mjEPS = "
                "1e-14 kg·m²",
                inertial.inertia_source or inertial.source,
            )
    for shape in link.link.collisions:
        index = _geom_size(shape)
        if index is not None:
            kind = shape.geometry.__class__.__name__.lower()
            return _refuse_body(
                body,
                f"size {index} must be positive in geom",
                f"a collision {kind} with a size ≤ 0",
                f"size {index} of its collision {kind} (as MuJoCo numbers them) is zero or "
                "negative",
                shape.geometry.source,
                shape.name or "",
            )
    if inertial is None:
        body.value, body.known = _from_geometry(link)
        body.inferred = True
        return []
    mass = max(float(inertial.mass), 0.0)  # type: ignore[arg-type]  # boundmass = 0
    a, b, c = np.maximum(principal, 0.0)
    if a + b < c:
        return _refuse_body(
            body,
            "inertia must satisfy A + B >= C; use 'balanceinertia' to fix",
            "principal moments break A + B ≥ C",
            f"its principal moments are {_moments(principal)}: {fmt(a, 4)} + {fmt(b, 4)} < "
            f"{fmt(c, 4)} (MuJoCo allows no tolerance)",
            inertial.inertia_source or inertial.source,
        )
    if mass >= MJMINVAL:
        origin = transform(inertial.origin.xyz, inertial.origin.rpy)
        tensor = np.zeros((3, 3)) if zero else written
        body.value = MassProperties(mass, np.zeros(3), tensor).transformed(origin)
    return []


def _refuse_body(
    body: _Body,
    message: str,
    claim: str,
    detail: str,
    source: model.Source,
    name: str | None = None,
) -> list[Prediction]:
    """The compiler refuses ``body`` (naming the element ``name``, by default the body)."""
    body.known = False
    element = {"name": body.name if name is None else name}
    why = f"MuJoCo's compiler refuses link `{body.name}`: {detail}"
    return [refusal("body", body.name, message, claim, why, source, element)]


def _from_geometry(link: LinkAnalysis) -> tuple[MassProperties | None, bool]:
    """
    What ``inertiafromgeom`` gives a link without ``<inertial>``: its collision geoms at 1000
    kg/m³, each counted whole (overlaps twice), meshes by MuJoCo's default mesh inertia
    (:data:`~.mujoco_meshes.DEFAULT_MESH_INERTIA`, which overcounts a non-convex mesh's
    volume); ``(None, True)`` without collision geometry.
    """
    solids = link.collision.solids if link.link.collisions else ()
    if any(s.unit is None for s in solids):
        return None, False
    total = None
    for solid in solids:
        assert solid.unit is not None
        unit = solid.unit
        if solid.mesh is not None:
            unit = mesh_unit(solid)
            if unit is None:
                return None, False  # its triangles unreadable: no value we can predict
        part = unit.with_mass(unit.mass * GEOM_DENSITY) if unit.mass else None
        if part is not None:
            total = part if total is None else total + part
    if total is None or total.mass < MJMINVAL:
        return None, True
    return total, True


def _mass_of(body: _Body) -> float:
    inertial = body.link.link.inertial
    if inertial is not None and isinstance(inertial.mass, float):
        return max(inertial.mass, 0.0)
    return 0.0 if body.value is None else body.value.mass


def _where(body: _Body) -> model.Source:
    inertial = body.link.link.inertial
    if inertial is not None:
        return inertial.mass_source or inertial.source
    return body.link.link.source


# --- fusestatic -----------------------------------------------------------------------------


def _fuse(roots: list[_Body], changes: list[Prediction]) -> list[Prediction]:
    """
    mjCModel::FuseStatic (``fusestatic`` is on for URDF): every body without a joint, in depth-
    first order, is merged into the moving body above it (its mass added when ≥ mjMINVAL, the
    sum's eigenvalues checked), or into the world, which drops its mass.
    """
    refusals: list[Prediction] = []
    for root in roots:
        _drop_root(root, changes)
        for body in _preorder(root):
            if body.moving:
                _note_changes(body, None, changes)
                _fuse_into(body, body, np.eye(4), refusals, changes)
    return refusals


def _drop_root(root: _Body, changes: list[Prediction]) -> None:
    """A root link and the links welded to it are fused into the world: their mass is gone."""
    if root.moving or root.link.parent is not None:
        return  # a joint from a `world` link: moving, or fixed to the world on purpose
    group = [root]
    stack = list(root.children)
    while stack:
        body = stack.pop()
        if not body.moving:
            group.append(body)
            stack.extend(body.children)
    mass = sum(_mass_of(body) for body in group)
    if mass <= 0:
        return
    others = [f"`{b.name}`" for b in group[1:] if _mass_of(b) > 0]
    whose = f"`{root.name}`" + (
        f" and the links welded to it ({', '.join(others)})" if others else ""
    )
    changes.append(
        change(
            "root",
            root.name,
            f"fixes the root to the world, dropping {fmt(mass)} kg",
            f"MuJoCo's URDF import adds no free joint: root link `{root.name}` is fixed to the "
            f"world and the {fmt(mass)} kg of {whose} are dropped",
            _where(root),
            dropped_mass=mass,
        )
    )


def _fuse_into(
    host: _Body,
    body: _Body,
    pose: NDArray[np.float64],
    refusals: list[Prediction],
    changes: list[Prediction],
) -> None:
    """
    Fuse the static descendants of ``body`` (at ``pose`` in ``host``'s frame) into ``host``,
    depth first. A welded chain may be thousands of links long: the levels being visited are a
    stack here, not Python's; leaving a level is where a recursive visit would return.
    """
    levels = [(iter(body.children), pose)]  # each: the children left to visit, their parent's pose
    while levels:
        children, pose = levels[-1]
        child = next(children, None)
        if child is None:
            levels.pop()
            continue
        if child.moving:
            continue
        origin = joint_pose(child.link.parent)  # type: ignore[arg-type]  # a child has a joint
        if origin is None:
            host.known = False
            levels.pop()
            continue
        at = pose @ origin
        _note_changes(child, host, changes)
        if not child.known:
            host.known = False
        elif child.value is not None and host.known:
            placed = child.value.transformed(at)
            total = placed if host.value is None else host.value + placed
            principal = _eigenvalues(np.asarray(total.inertia))
            if principal[0] < MJEPS:
                refusals.append(
                    refusal(
                        "fuse",
                        child.name,
                        "error 'inertia must have positive eigenvalues' in fusing static body "
                        "inertias",
                        f"fused: principal moment {fmt(principal[0])} kg·m², below mjEPS",
                        f"Link `{child.name}` is welded to `{host.name}` and fused into it: their "
                        f"sum has principal moments {_moments(principal)}, the smallest below "
                        "mjEPS = 1e-14 kg·m² (point masses on a line, or a point mass alone)",
                        _where(child),
                        host=host.name,
                    )
                )
                host.known = False
                levels.pop()
                continue
            host.value = total
        levels.append((iter(child.children), at))


def _note_changes(body: _Body, host: _Body | None, changes: list[Prediction]) -> None:
    """Silent changes to a moving link, or to a static one fused into ``host``."""
    into = "" if host is None else f" before it is fused into `{host.name}`"
    inertial = body.link.link.inertial
    if inertial is not None and isinstance(inertial.mass, float) and inertial.mass < 0:
        changes.append(
            change(
                "clamp",
                body.name,
                f"clamps its mass {fmt(inertial.mass)} kg to 0",
                f"MuJoCo clamps the negative mass ({fmt(inertial.mass)} kg) of link "
                f"`{body.name}` to 0 (boundmass){into}",
                inertial.mass_source or inertial.source,
                declared_mass=inertial.mass,
                mass=0.0,
            )
        )
    if body.inferred and body.value is not None:
        suffix = "" if host is None else f", fused into `{host.name}`"
        value = body.value
        meshes = any(s.mesh is not None for s in body.link.collision.solids)
        mode = f", meshes by its default mesh inertia `{DEFAULT_MESH_INERTIA}`" if meshes else ""
        changes.append(
            change(
                "inertiafromgeom",
                body.name,
                f"gives it {fmt(value.mass)} kg from collision geometry (no <inertial>)",
                f"Link `{body.name}` has no <inertial>: MuJoCo gives it the mass of its "
                f"collision geometry at {fmt(GEOM_DENSITY)} kg/m³, {fmt(value.mass)} kg"
                f"{suffix} (inertiafromgeom{mode})",
                body.link.link.source,
                mass=value.mass,
                com=[float(v) for v in value.com],
                principal_moments=[float(v) for v in _eigenvalues(value.inertia)],
                density=GEOM_DENSITY,
                mesh_inertia=DEFAULT_MESH_INERTIA if meshes else None,
            )
        )


# --- the last check -------------------------------------------------------------------------


def _minval(body: _Body) -> list[Prediction]:
    """A moving body's mass and principal moments must be ≥ mjMINVAL."""
    if not body.known:
        inertial = body.link.link.inertial
        nonfinite = inertial is not None and any(
            isinstance(v, model.Invalid) and parseable(v)
            for v in (inertial.mass, *inertial.tensor_values().values())
        )
        if not nonfinite:
            return []
        claim = what = "nan or inf in its <inertial>"
    else:
        value = body.value
        inertial = body.link.link.inertial
        if value is not None:
            principal = _eigenvalues(np.asarray(value.inertia))
            if value.mass >= MJMINVAL and principal[0] >= MJMINVAL:
                return []
            claim = f"principal moment {fmt(principal[0])} kg·m², below mjMINVAL"
            what = (
                f"principal moments {_moments(principal)}, the smallest below mjMINVAL = 1e-15 "
                "kg·m²"
            )
        elif inertial is None:
            what = (
                "no <inertial> and no collision geometry to compute one from"
                if not body.link.link.collisions
                else "no <inertial>, and its collision geometry at 1000 kg/m³ is too light"
            )
            claim = (
                "no <inertial>, collision geometry too light"
                if body.link.link.collisions
                else "no <inertial> or collision geometry"
            )
        elif isinstance(inertial.mass, float) and inertial.mass < MJMINVAL:
            claim = f"mass {fmt(inertial.mass)} kg, below mjMINVAL"
            what = f"mass {fmt(inertial.mass)} kg (below mjMINVAL = 1e-15 kg)"
        else:
            claim = what = "mass below mjMINVAL"
        welded = [c.name for c in body.children if not c.moving]
        if welded:
            what += f", even with the links welded to it ({', '.join(f'`{n}`' for n in welded)})"
    joint = body.link.parent
    return [
        refusal(
            "minval",
            body.name,
            "mass and inertia of moving bodies must be larger than mjMINVAL",
            claim,
            f"Link `{body.name}` moves (joint `{joint.name}`) with {what}"
            if joint is not None
            else f"Link `{body.name}` moves with {what}",
            _where(body),
            {"name": body.name},
        )
    ]
