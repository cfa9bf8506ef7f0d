"""
What Drake's URDF parser and MultibodyPlant do with each link: an invalid inertia is replaced by
a solid sphere of water density (``detail_common.cc`` ``ParseSpatialInertia``), a moving link
with no mass anywhere outboard fails at simulation time (a singular articulated body inertia),
and a collision mesh must be ``.obj`` (or a tetrahedral ``.vtk``).
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from pathlib import PurePosixPath

import numpy as np

from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
from inertia_kit.description import model
from inertia_kit.engines.lumping import written_tensor
from inertia_kit.engines.vocabulary import Event, Verdict, event
from inertia_kit.physics.formatting import fmt

ENGINE = "drake"
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
    mass, *tensor = (0.0 if v is None else float(v) for v in numbers)
    return mass, written_tensor(tensor)


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


def events(robot: RobotAnalysis) -> Iterator[Event]:
    """
    Link by link: ``sphere`` (the inertia is replaced), ``singular`` (the plant fails at
    simulation time), ``mesh`` (a collision mesh is refused).
    """
    for link in robot.links:
        inertial = link.link.inertial
        values = None if inertial is None else _values(inertial)
        if inertial is not None and values is not None:
            mass, tensor = values
            massless = mass == 0 and not tensor.any()
            if not massless and (not could_be_physically_valid(tensor) or not mass > 0):
                yield _sphere(link.name, inertial, mass, tensor)
        if link.moves and link.parent.type != "floating" and _outboard_massless(robot, link):
            yield event(
                ENGINE,
                Verdict.REFUSES,
                "singular",
                f"fails at simulation time on link `{link.name}`: it moves on joint "
                f"`{link.parent.name}` and neither it nor anything outboard has mass",
                SINGULAR,
                inertial.source if inertial is not None else link.link.source,
                link=link.name,
                joint=link.parent.name,
            )
        for shape in link.link.collisions:
            geometry = shape.geometry
            if not isinstance(geometry, model.Mesh):
                continue
            suffix = PurePosixPath(geometry.filename).suffix.lower()
            if suffix in PROXIMITY_MESHES:
                continue
            shown = geometry.path or geometry.filename
            yield event(
                ENGINE,
                Verdict.REFUSES,
                "mesh",
                f"refuses the {suffix or 'extension-less'} collision mesh of link "
                f"`{link.name}` (proximity geometry must be .obj, or a tetrahedral .vtk)",
                f"ProximityEngine: expect an Obj file for non-hydroelastics but get {suffix} "
                f"file {shown}) instead.",
                geometry.source,
                link=link.name,
                mesh=shown,
            )


def _sphere(link: str, inertial: model.Inertial, mass: float, tensor: np.ndarray) -> Event:
    """The sphere Drake puts in place of an invalid inertia, with the error it logs."""
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
    return event(
        ENGINE,
        Verdict.CHANGES,
        "sphere",
        f"replaces the inertia of link `{link}` by a solid sphere of {fmt(WATER)} kg/m³: "
        f"{fmt(m)} kg, radius {fmt(radius, 4)} m, moment {fmt(moment, 4)} kg·m² about each axis",
        message,
        inertial.inertia_source or inertial.source,
        link=link,
        mass=m,
        radius=radius,
        ixx=moment,
        iyy=moment,
        izz=moment,
    )
