"""IN070 mujoco-verdict: what MuJoCo's URDF import and compiler do with each link."""

from __future__ import annotations

import os
import posixpath
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
from inertia_kit.description import model
from inertia_kit.engines.vocabulary import Verdict, verdict_expected, verdict_message
from inertia_kit.lint.findings import Finding, Severity, severity_of
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.frames import transform
from inertia_kit.physics.mass import MassProperties

CODE = "IN070"
NAME = "mujoco-verdict"
SEVERITY = Severity.ERROR  # a refusal; a silent change is a warning
SCOPE = "robot"
SUMMARY = (
    "MuJoCo refuses the model (with its own message) or silently changes a link: `--engine mujoco`"
)
ENGINE = "mujoco"
OPTIONS: dict[str, type] = {}
DEFAULTS: dict[str, object] = {}

# MuJoCo's constants (include/mujoco/mjtnum.h): mjMINVAL bounds the mass and principal moments
# of a moving body; mjEPS the smallest eigenvalue of a full inertia (user_util.cc)
MJMINVAL = 1e-15
MJEPS = 1e-14
# the density <geom> takes by default, kg/m³: what a link without <inertial> is given
GEOM_DENSITY = 1000.0
# the mesh decoders MuJoCo ships (stl_decoder, obj_decoder, the .msh reader)
DECODERS = (".stl", ".obj", ".msh")
STL_MAX_FACES = 200_000
MOVING = ("revolute", "continuous", "prismatic", "floating", "planar", "spherical")
KNOWN_JOINTS = (*MOVING, "fixed")
TENSOR_ORDER = ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")  # the order MuJoCo reads them


# --- what MuJoCo does -------------------------------------------------------------------------


@dataclass
class Event:
    """
    One thing MuJoCo does to the model: a refusal (its error, in the order it would raise it)
    or a silent change.

    ``message`` is MuJoCo's own text without its ``Error:``/``XML Error:`` prefix; ``element``
    is what MuJoCo names after it (``{"name": "arm"}`` for a compiled element, ``{"tag":
    "mass", "line": 7}`` for an XML element), ``None`` when it names none.
    """

    verdict: Verdict
    stage: str
    link: str | None
    message: str | None
    detail: str
    source: model.Source | None
    element: dict[str, Any] | None = None
    more: dict[str, Any] = field(default_factory=dict)


@dataclass
class _Body:
    """A link as a MuJoCo body: its own mass properties (link frame) after compilation."""

    link: LinkAnalysis
    moving: bool
    children: list[_Body] = field(default_factory=list)
    parent: _Body | None = None
    value: MassProperties | None = None  # mass ≥ mjMINVAL; None: massless (or clamped to 0)
    known: bool = (
        True  # False: we cannot tell what MuJoCo makes of it (a nan, a mesh we can't read)
    )
    inferred: bool = False  # from its collision geometry (no <inertial>)

    @property
    def name(self) -> str:
        return self.link.name


def predict(robot: RobotAnalysis) -> list[Event]:
    """
    What ``mujoco.MjModel.from_xml_path`` does with the robot, from our model alone: the
    refusals in the order MuJoCo meets them (it reports only the first), then the silent changes.
    An empty list: the model loads as written. Robots whose tree MuJoCo's importer cannot build
    (IN040) get no prediction.
    """
    roots = _tree(robot)
    if roots is None:
        return []
    order = [body for root in roots for body in _preorder(root)]
    refusals = _parse(robot) + _meshes(robot)
    changes: list[Event] = []
    for body in order:
        refusals += _compile(body)
    refusals += _fuse(roots, changes)
    for body in order:
        if body.moving:
            refusals += _minval(body)
    if any(e.stage == "parse" for e in refusals):
        changes = []  # nothing past the parser is certain
    return refusals + changes


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
        if root.name == "world":  # the world body itself: its children hang from the world
            for child in root.children:
                child.parent = None
            tops.extend(root.children)
        else:
            tops.append(root)
    return tops


def _preorder(body: _Body) -> Iterator[_Body]:
    yield body
    for child in body.children:
        yield from _preorder(child)


# --- the XML parser -----------------------------------------------------------------------------


def _parseable(value: model.Number) -> bool:
    """Whether MuJoCo reads the text as a number (it takes nan and inf, with a warning)."""
    if not isinstance(value, model.Invalid):
        return True
    try:
        float(value.text)
    except ValueError:
        return False
    return True


def _parse(robot: RobotAnalysis) -> list[Event]:
    """``<inertial>`` errors of mjXURDF::Body, link by link in document order."""
    events = []
    for link in robot.links:
        inertial = link.link.inertial
        if inertial is None:
            continue
        problem: tuple[str, str, model.Source | None] | None = None
        if inertial.mass_source is None:
            problem = ("missing element: 'mass'", "inertial", inertial.source)
        elif inertial.mass is None:
            problem = ("required attribute missing: 'value'", "mass", inertial.mass_source)
        elif not _parseable(inertial.mass):
            problem = ("bad format in attribute 'value'", "mass", inertial.mass_source)
        elif inertial.inertia_source is None:
            problem = ("missing element: 'inertia'", "inertial", inertial.source)
        else:
            for name in TENSOR_ORDER:
                value = getattr(inertial, name)
                if value is None:
                    problem = (f"required attribute missing: '{name}'", "inertia", None)
                elif not _parseable(value):
                    problem = (f"bad format in attribute '{name}'", "inertia", None)
                if problem is not None:
                    problem = (problem[0], "inertia", inertial.inertia_source)
                    break
        if problem is None:
            continue
        message, tag, source = problem
        line = None if source is None else source.line
        events.append(
            Event(
                Verdict.REFUSES,
                "parse",
                link.name,
                message,
                f"link `{link.name}`: its `<{tag}>` cannot be read",
                source,
                {"tag": tag, "line": line},
            )
        )
    return events


# --- meshes -------------------------------------------------------------------------------------


def mesh_path(robot: model.Robot, filename: str) -> str:
    """
    The file MuJoCo opens for a mesh: the filename joined to the URDF's folder, ``.``/``..``/
    ``//`` reduced; a URI (``package://``, ``file://``) is taken as an absolute path, which no
    file matches.
    """
    if "://" in filename or os.path.isabs(filename):
        return posixpath.normpath(filename)
    folder = os.path.dirname(robot.source.path)
    return (
        posixpath.normpath(posixpath.join(folder, filename))
        if folder
        else (posixpath.normpath(filename))
    )


def _stl_problem(path: str, shown: str) -> str | None:
    """MuJoCo's stl_decoder error for a file, or ``None`` when it reads it."""
    size = os.path.getsize(path)
    if size == 0:
        return f"stl_decoder: STL file '{shown}' is empty"
    if size < 84:
        return f"stl_decoder: invalid header in STL file '{shown}'"
    with open(path, "rb") as stream:
        stream.seek(80)
        faces = int.from_bytes(stream.read(4), "little", signed=True)
    if not 1 <= faces <= STL_MAX_FACES:
        return (
            f"stl_decoder: number of faces should be between 1 and {STL_MAX_FACES} in STL file "
            f"'{shown}'; perhaps this is an ASCII file?"
        )
    if faces * 50 != size - 84:
        return f"stl_decoder: STL file '{shown}' has wrong size; perhaps this is an ASCII file?"
    return None


def _meshes(robot: RobotAnalysis) -> list[Event]:
    """
    Collision meshes, in the order MuJoCo makes them assets (links in document order; visual
    meshes are discarded unread: ``discardvisual`` is on for URDF). One asset per file name and
    scale.
    """
    events = []
    seen: set[tuple[str, Any]] = set()
    for link in robot.links:
        for shape in link.link.collisions:
            geometry = shape.geometry
            if not isinstance(geometry, model.Mesh):
                continue
            stem = posixpath.splitext(posixpath.basename(geometry.filename.replace("\\", "/")))[0]
            key = (stem, geometry.scale)
            if key in seen:
                continue
            seen.add(key)
            path = mesh_path(robot.robot, geometry.filename)
            where = f"link `{link.name}`: collision mesh `{geometry.filename}`"
            if not os.path.isfile(path):
                why = (
                    "MuJoCo resolves no package:// or file:// URI"
                    if "://" in geometry.filename
                    else "no such file beside the URDF"
                )
                # this message names the file as written (reduced), not joined to the folder
                shown = posixpath.normpath(geometry.filename)
                message, element, detail = f"Error opening file '{shown}'", None, why
            else:
                ext = posixpath.splitext(path)[1].lower()
                element = {"name": stem}
                if ext not in DECODERS:
                    message = f"no decoder found for mesh file '{path}'"
                    detail = "MuJoCo reads STL (binary), OBJ and MSH meshes only"
                elif ext == ".stl" and (stl := _stl_problem(path, path)) is not None:
                    message = stl
                    detail = "MuJoCo reads binary STL only"
                else:
                    continue
            events.append(
                Event(
                    Verdict.REFUSES,
                    "mesh",
                    link.name,
                    message,
                    f"{where}: {detail}",
                    geometry.source,
                    element,
                    {"mesh": geometry.filename},
                )
            )
    return events


# --- bodies ---------------------------------------------------------------------------------


def _written(inertial: model.Inertial) -> NDArray[np.float64]:
    v = {name: float(getattr(inertial, name)) for name in model.Inertial.TENSOR}  # type: ignore[arg-type]
    return np.array(
        [
            [v["ixx"], v["ixy"], v["ixz"]],
            [v["ixy"], v["iyy"], v["iyz"]],
            [v["ixz"], v["iyz"], v["izz"]],
        ]
    )


def _eigenvalues(tensor: NDArray[np.float64]) -> NDArray[np.float64]:
    """Ascending; a diagonal tensor's own values (exact, as MuJoCo's Jacobi iteration gives)."""
    if not np.any(tensor - np.diag(np.diag(tensor))):
        return np.sort(np.diag(tensor))
    return np.linalg.eigvalsh(tensor)


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


def _compile(body: _Body) -> list[Event]:
    """mjCBody::Compile: the full inertia's eigenvalues, geom sizes, A + B ≥ C; sets the value."""
    link = body.link
    inertial = link.link.inertial
    events = []
    if inertial is not None:
        values = [inertial.mass, *(getattr(inertial, n) for n in model.Inertial.TENSOR)]
        if (
            not all(isinstance(v, float) for v in values)
            or not isinstance(inertial.origin.xyz, tuple)
            or not isinstance(inertial.origin.rpy, tuple)
        ):
            # nan/inf that MuJoCo reads (or what its parser refused): no value we can predict
            body.known = False
            return events
        written = _written(inertial)
        zero = not np.any(written)  # all six 0: MuJoCo takes the inertia as undefined
        principal = np.zeros(3) if zero else _eigenvalues(written)
        if not zero and principal[0] < MJEPS:
            events.append(
                Event(
                    Verdict.REFUSES,
                    "body",
                    link.name,
                    "error 'inertia must have positive eigenvalues' in fullinertia",
                    f"link `{link.name}`: principal moments {_moments(principal)}, the smallest "
                    f"below mjEPS = 1e-14 kg·m²",
                    inertial.inertia_source or inertial.source,
                    {"name": link.name},
                )
            )
            body.known = False
            return events
    for shape in link.link.collisions:
        index = _geom_size(shape)
        if index is not None:
            events.append(
                Event(
                    Verdict.REFUSES,
                    "body",
                    link.name,
                    f"size {index} must be positive in geom",
                    f"link `{link.name}`: a collision {shape.geometry.__class__.__name__.lower()}"
                    " has a zero or negative size",
                    shape.geometry.source,
                    {"name": shape.name or ""},
                )
            )
            body.known = False
            return events
    if inertial is None:
        body.value, body.known = _from_geometry(link)
        body.inferred = True
        return events
    mass = max(float(inertial.mass), 0.0)  # type: ignore[arg-type]  # boundmass = 0
    moments = np.maximum(principal, 0.0)
    a, b, c = moments
    if a + b < c:
        events.append(
            Event(
                Verdict.REFUSES,
                "body",
                link.name,
                "inertia must satisfy A + B >= C; use 'balanceinertia' to fix",
                f"link `{link.name}`: principal moments {_moments(principal)}: "
                f"{fmt(a, 4)} + {fmt(b, 4)} < {fmt(c, 4)} (MuJoCo allows no tolerance)",
                inertial.inertia_source or inertial.source,
                {"name": link.name},
            )
        )
        body.known = False
        return events
    if mass >= MJMINVAL:
        origin = transform(inertial.origin.xyz, inertial.origin.rpy)
        tensor = np.zeros((3, 3)) if zero else written
        body.value = MassProperties(mass, np.zeros(3), tensor).transformed(origin)
    return events


def _from_geometry(link: LinkAnalysis) -> tuple[MassProperties | None, bool]:
    """
    What ``inertiafromgeom`` gives a link without ``<inertial>``: its collision geoms at 1000
    kg/m³, each counted whole (overlaps twice); ``(None, True)`` without collision geometry.
    """
    solids = link.collision.solids if link.link.collisions else ()
    if any(s.unit is None for s in solids):
        return None, False
    total = None
    for solid in solids:
        assert solid.unit is not None
        part = solid.unit.with_mass(solid.unit.mass * GEOM_DENSITY) if solid.unit.mass else None
        if part is not None:
            total = part if total is None else total + part
    if total is None or total.mass < MJMINVAL:
        return None, True
    return total, True


def _moments(principal: NDArray[np.float64]) -> str:
    return "(" + ", ".join(fmt(float(v), 4) for v in principal) + ") kg·m²"


# --- fusestatic -----------------------------------------------------------------------------


def _joint_pose(body: _Body) -> NDArray[np.float64] | None:
    joint = body.link.parent
    if joint is None:
        return np.eye(4)
    xyz, rpy = joint.origin.xyz, joint.origin.rpy
    if not isinstance(xyz, tuple) or not isinstance(rpy, tuple):
        return None
    return transform(xyz, rpy)


def _fuse(roots: list[_Body], changes: list[Event]) -> list[Event]:
    """
    mjCModel::FuseStatic (``fusestatic`` is on for URDF): every body without a joint, in depth-
    first order, is merged into the moving body above it (its mass added when ≥ mjMINVAL, the
    sum's eigenvalues checked), or into the world, which drops its mass.
    """
    events: list[Event] = []
    for root in roots:
        _drop_root(root, changes)
        for body in _preorder(root):
            if body.moving:
                _note_changes(body, None, changes)
                _fuse_into(body, body, np.eye(4), events, changes)
    return events


def _drop_root(root: _Body, changes: list[Event]) -> None:
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
        Event(
            Verdict.CHANGES,
            "root",
            root.name,
            None,
            f"root link `{root.name}` is fixed to the world (its URDF import adds no free joint) "
            f"and the {fmt(mass)} kg of {whose} are dropped",
            _where(root),
            None,
            {"dropped_mass": mass},
        )
    )


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


def _fuse_into(
    host: _Body,
    body: _Body,
    pose: NDArray[np.float64],
    events: list[Event],
    changes: list[Event],
) -> None:
    """Fuse the static descendants of ``body`` (at ``pose`` in ``host``'s frame) into ``host``."""
    for child in body.children:
        if child.moving:
            continue
        origin = _joint_pose(child)
        if origin is None:
            host.known = False
            return
        at = pose @ origin
        _note_changes(child, host, changes)
        if not child.known:
            host.known = False
        elif child.value is not None and host.known:
            placed = child.value.transformed(at)
            total = placed if host.value is None else host.value + placed
            principal = _eigenvalues(np.asarray(total.inertia))
            if principal[0] < MJEPS:
                events.append(
                    Event(
                        Verdict.REFUSES,
                        "fuse",
                        child.name,
                        "error 'inertia must have positive eigenvalues' in fusing static body "
                        "inertias",
                        f"link `{child.name}` is welded to `{host.name}` and fused into it: their "
                        f"sum has principal moments {_moments(principal)}, the smallest below "
                        "mjEPS = 1e-14 kg·m² (point masses on a line, or a point mass alone)",
                        _where(child),
                        None,
                        {"host": host.name},
                    )
                )
                host.known = False
                return
            host.value = total
        _fuse_into(host, child, at, events, changes)


def _note_changes(body: _Body, host: _Body | None, changes: list[Event]) -> None:
    """Silent changes to a moving link, or to a static one fused into ``host``."""
    into = "" if host is None else f" before it is fused into `{host.name}`"
    inertial = body.link.link.inertial
    if inertial is not None and isinstance(inertial.mass, float) and inertial.mass < 0:
        changes.append(
            Event(
                Verdict.CHANGES,
                "clamp",
                body.name,
                None,
                f"link `{body.name}`'s negative mass ({fmt(inertial.mass)} kg) is clamped to 0 "
                f"(boundmass){into}",
                inertial.mass_source or inertial.source,
                None,
                {"declared_mass": inertial.mass, "mass": 0.0},
            )
        )
    if body.inferred and body.value is not None:
        suffix = "" if host is None else f", fused into `{host.name}`"
        value = body.value
        changes.append(
            Event(
                Verdict.CHANGES,
                "inertiafromgeom",
                body.name,
                None,
                f"link `{body.name}` has no `<inertial>`: MuJoCo gives it the mass of its "
                f"collision geometry at {fmt(GEOM_DENSITY)} kg/m³, {fmt(value.mass)} kg"
                f"{suffix} (inertiafromgeom)",
                body.link.link.source,
                None,
                {
                    "mass": value.mass,
                    "com": [float(v) for v in value.com],
                    "principal_moments": [float(v) for v in _eigenvalues(value.inertia)],
                    "density": GEOM_DENSITY,
                },
            )
        )


def _minval(body: _Body) -> list[Event]:
    """The last check: a moving body's mass and principal moments must be ≥ mjMINVAL."""
    if not body.known:
        inertial = body.link.link.inertial
        nonfinite = inertial is not None and any(
            isinstance(v, model.Invalid) and _parseable(v)
            for v in (inertial.mass, *inertial.tensor_values().values())
        )
        if not nonfinite:
            return []
        what = "nan or inf in its `<inertial>`"
    else:
        value = body.value
        inertial = body.link.link.inertial
        if value is not None:
            principal = _eigenvalues(np.asarray(value.inertia))
            if value.mass >= MJMINVAL and principal[0] >= MJMINVAL:
                return []
            what = (
                f"principal moments {_moments(principal)}, the smallest below mjMINVAL = 1e-15 "
                "kg·m²"
            )
        elif inertial is None:
            what = (
                "no `<inertial>` and no collision geometry to compute one from"
                if not body.link.link.collisions
                else "no `<inertial>`, and its collision geometry at 1000 kg/m³ is too light"
            )
        elif isinstance(inertial.mass, float) and inertial.mass < MJMINVAL:
            what = f"mass {fmt(inertial.mass)} kg (below mjMINVAL = 1e-15 kg)"
        else:
            what = "mass below mjMINVAL"
        welded = [c.name for c in body.children if not c.moving]
        if welded:
            what += f", even with the links welded to it ({', '.join(f'`{n}`' for n in welded)})"
    return [
        Event(
            Verdict.REFUSES,
            "minval",
            body.name,
            "mass and inertia of moving bodies must be larger than mjMINVAL",
            f"link `{body.name}` moves (joint `{body.link.parent.name}`) with {what}"
            if body.link.parent is not None
            else f"link `{body.name}` moves with {what}",
            _where(body),
            {"name": body.name},
        )
    ]


# --- the rule -------------------------------------------------------------------------------


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    events = predict(robot)
    refusals = [e for e in events if e.verdict is Verdict.REFUSES]
    first = refusals[0] if refusals else None
    for event in events:
        if event.verdict is Verdict.REFUSES:
            if event is first:
                what = "refuses the model"
                detail = event.detail
            else:
                what = "would also refuse the model"
                detail = (
                    f"{event.detail}; it stops at the first error, "
                    f"{_first_place(first)}"  # type: ignore[arg-type]
                )
            message = f"{verdict_message('mujoco', event.verdict, event.message, what)} ({detail})"
            help_text = _help(event)
        else:
            message = (
                verdict_message("mujoco", event.verdict, None, "silently changes the model")
                + f": {event.detail}"
            )
            help_text = _help(event)
        yield ctx.finding(
            message,
            event.source,
            link=event.link,
            expected=verdict_expected(
                "mujoco",
                event.verdict,
                event.message,
                stage=event.stage,
                engine_element=event.element,
                first=event is first,
                **event.more,
            ),
            help=help_text,
            severity=severity_of(event.verdict),
        )


def _first_place(event: Event) -> str:
    return f"link `{event.link}`" if event.link else "the first"


def _help(event: Event) -> str:
    return {
        "parse": "write the `<inertial>` completely: `<mass value>` and all six `<inertia>` "
        "attributes as plain numbers",
        "mesh": "give MuJoCo a binary STL or an OBJ (e.g. `trimesh` can convert), at a path "
        "relative to the URDF (no package://), or a primitive collision shape",
        "body": "write a physically possible tensor about the centre of mass "
        "(`inertia-fill --fix invalid`), or a positive collision size",
        "fuse": "give the welded links a tensor (not point masses), or the moving link one",
        "minval": "give the moving link an `<inertial>` with positive mass and moments, or weld "
        "a link that has them to it",
        "root": "add a floating joint from a `world` link if the robot should move freely, and "
        "keep the root massless (its mass counts for nothing in MuJoCo)",
        "clamp": "write the link's real (positive) mass",
        "inertiafromgeom": "write the link's `<inertial>` (`inertia-fill` computes one from the "
        "geometry at a density you choose)",
    }[event.stage]
