"""IN072 drake-verdict: what Drake's URDF parser and MultibodyPlant do with each link."""

from __future__ import annotations

import math
from collections.abc import Iterator
from pathlib import PurePosixPath

import numpy as np

from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
from inertia_kit.description import model
from inertia_kit.engines.vocabulary import Verdict, verdict_expected, verdict_message
from inertia_kit.lint.findings import Finding, Severity, severity_of
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt

CODE = "IN072"
NAME = "drake-verdict"
ENGINE = "drake"
SEVERITY = Severity.WARNING
SCOPE = "robot"
SUMMARY = (
    "Drake replaces an invalid tensor by a water-density sphere, fails at run time on a "
    "massless moving link, and refuses collision meshes that are not .obj"
)
OPTIONS: dict[str, type] = {}
DEFAULTS: dict[str, object] = {}

WATER = 1000.0  # kg/m³: detail_common.cc kPlausibleDensity
PROXIMITY_MESHES = (".obj", ".vtk")
SINGULAR = (
    "Encountered singular articulated body hinge inertia for body node index …. Please ensure "
    "that this body has non-zero inertia along all axes of motion."
)


def plausible_sphere(mass: float) -> tuple[float, float, float]:
    """
    The solid sphere Drake's ``ParseSpatialInertia`` substitutes for invalid values: mass (the
    declared one if finite and > 0, else 1 kg), radius at 1000 kg/m³, and its moment 2/5 m r².
    """
    m = mass if math.isfinite(mass) and mass > 0 else 1.0
    radius = (3.0 / (4.0 * math.pi) * (m / WATER)) ** (1.0 / 3.0)
    return m, radius, 0.4 * m * radius**2


def _values(inertial: model.Inertial) -> tuple[float, np.ndarray] | None:
    """Mass and the (3, 3) tensor as written, Drake's missing attributes reading as 0."""
    numbers = [inertial.mass, *inertial.tensor_values().values()]
    if any(isinstance(v, model.Invalid) for v in numbers):
        return None
    mass, ixx, ixy, ixz, iyy, iyz, izz = (0.0 if v is None else float(v) for v in numbers)
    return mass, np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])


def could_be_physically_valid(tensor: np.ndarray) -> bool:
    """Drake ``RotationalInertia::CouldBePhysicallyValid``: moments ≥ 0 and A + B ≥ C (± ε)."""
    if not np.isfinite(tensor).all():
        return False
    a, b, c = np.linalg.eigvalsh(0.5 * (tensor + tensor.T))
    eps = 16 * np.finfo(np.float64).eps * max(abs(c), abs(a))
    return bool(a >= -eps and a + b + eps >= c)


def drake_mass(link: LinkAnalysis) -> float:
    """The mass Drake gives the body: 0 when massless, the sphere's when substituted."""
    inertial = link.link.inertial
    if inertial is None:
        return 0.0
    values = _values(inertial)
    if values is None:
        return math.nan
    mass, tensor = values
    if mass == 0 and not tensor.any():
        return 0.0
    if mass > 0 and could_be_physically_valid(tensor):
        return mass
    return plausible_sphere(mass)[0]


def _outboard_massless(robot: RobotAnalysis, link: LinkAnalysis) -> bool:
    stack, seen = [link], set()
    while stack:
        current = stack.pop()
        if current.name in seen:
            continue
        seen.add(current.name)
        if drake_mass(current) != 0:
            return False
        stack.extend(robot.by_name[j.child] for j in current.children if j.child in robot.by_name)
    return True


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    for link in robot.links:
        inertial = link.link.inertial
        values = None if inertial is None else _values(inertial)
        if inertial is not None and values is not None:
            mass, tensor = values
            massless = mass == 0 and not tensor.any()
            if not massless and (not could_be_physically_valid(tensor) or not mass > 0):
                m, radius, moment = plausible_sphere(mass)
                if could_be_physically_valid(tensor):
                    message = (
                        "While re-expressing as central inertia: Spatial inertia fails "
                        f"SpatialInertia::IsPhysicallyValid(). (mass = {fmt(mass)})"
                    )
                else:
                    message = (
                        "While parsing inertia matrix: MakeFromMomentsAndProductsOfInertia(): "
                        "The rotational inertia … did not pass the test "
                        "CouldBePhysicallyValid()."
                    )
                yield ctx.finding(
                    verdict_message(
                        ENGINE,
                        Verdict.CHANGES,
                        message,
                        f"replaces the inertia of link `{link.name}` by a solid sphere of "
                        f"{fmt(WATER)} kg/m³: {fmt(m)} kg, radius {fmt(radius, 4)} m, "
                        f"moment {fmt(moment, 4)} kg·m² about each axis",
                    ),
                    inertial.inertia_source or inertial.source,
                    link=link.name,
                    expected=verdict_expected(
                        ENGINE,
                        Verdict.CHANGES,
                        message,
                        mass=m,
                        radius=radius,
                        ixx=moment,
                        iyy=moment,
                        izz=moment,
                    ),
                    severity=severity_of(Verdict.CHANGES),
                    help="write a physically valid tensor about the centre of mass (every "
                    "principal moment ≥ 0, A + B ≥ C) and a mass > 0",
                )
        if link.moves and link.parent.type != "floating" and _outboard_massless(robot, link):
            yield ctx.finding(
                verdict_message(
                    ENGINE,
                    Verdict.REFUSES,
                    SINGULAR,
                    f"fails at simulation time on link `{link.name}`: it moves on joint "
                    f"`{link.parent.name}` and neither it nor anything outboard has mass",
                ),
                (inertial.source if inertial is not None else link.link.source),
                link=link.name,
                joint=link.parent.name,
                expected=verdict_expected(ENGINE, Verdict.REFUSES, SINGULAR),
                severity=severity_of(Verdict.REFUSES),
                help="give the link (or a link welded to it) a mass and inertia; a massless "
                "frame belongs on a fixed joint",
            )
        for shape in link.link.collisions:
            geometry = shape.geometry
            if not isinstance(geometry, model.Mesh):
                continue
            suffix = PurePosixPath(geometry.filename).suffix.lower()
            if suffix in PROXIMITY_MESHES:
                continue
            shown = geometry.path or geometry.filename
            message = (
                f"ProximityEngine: expect an Obj file for non-hydroelastics but get {suffix} "
                f"file {shown}) instead."
            )
            yield ctx.finding(
                verdict_message(
                    ENGINE,
                    Verdict.REFUSES,
                    message,
                    f"refuses the {suffix or 'extension-less'} collision mesh of link "
                    f"`{link.name}` (proximity geometry must be .obj, or a tetrahedral .vtk)",
                ),
                geometry.source,
                link=link.name,
                expected=verdict_expected(ENGINE, Verdict.REFUSES, message, mesh=shown),
                severity=severity_of(Verdict.REFUSES),
                help="convert the collision mesh to .obj (e.g. with trimesh or meshlab) and "
                "reference that file; visual meshes may stay as they are",
            )
