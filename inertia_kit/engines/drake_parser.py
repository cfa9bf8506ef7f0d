"""
What Drake's URDF parser (``multibody/parsing/detail_urdf_parser.cc``, ``detail_urdf_geometry.cc``,
``detail_common.cc``; Drake 1.51.1) makes of the elements of our model: the values it reads and
the first error it stops at. ``engines/drake.py`` turns them into events.
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from inertia_kit.description import model
from inertia_kit.engines import drake_reading as reading
from inertia_kit.engines.lumping import written_tensor

WATER = 1000.0  # kg/m³: detail_common.cc kPlausibleDensity
CUSTOM_JOINTS = ("ball", "screw", "universal", "curvilinear")  # only as <drake:joint>
KNOWN_JOINTS = ("revolute", "continuous", "fixed", "prismatic", "floating", "planar")


def plausible_sphere(mass: float) -> tuple[float, float, float]:
    """
    The solid sphere Drake's ``ParseSpatialInertia`` substitutes for invalid values: mass (the
    declared one if finite and > 0, else 1 kg), radius at 1000 kg/m³, and its moment 2/5 m r².
    """
    m = mass if math.isfinite(mass) and mass > 0 else 1.0
    radius = (3.0 / (4.0 * math.pi) * (m / WATER)) ** (1.0 / 3.0)
    return m, radius, 0.4 * m * radius**2


# --- reading a link's <inertial> as Drake does ---------------------------------------------------


@dataclass(frozen=True)
class Inertia:
    """
    What Drake makes of one ``<inertial>``: ``kind`` is ``massless`` (mass and tensor 0),
    ``valid``, ``sphere`` (replaced) or ``refused`` (``message`` says why, at ``source``).
    ``mass``, ``xyz``, ``rpy`` and ``tensor`` are the values as Drake read them.
    """

    kind: str
    mass: float = 0.0
    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)
    tensor: NDArray[np.float64] | None = None
    message: str | None = None
    source: model.Source | None = None


class Refused(Exception):
    """Drake's parser stops here: ``message`` is its error, ``source`` the element it names."""

    def __init__(self, message: str, source: model.Source | None):
        super().__init__(message)
        self.message, self.source = message, source


def scalar(value: model.Number, attribute: str) -> float:
    """A scalar attribute as Drake reads it: a missing one is 0."""
    if value is None:
        return 0.0
    if isinstance(value, model.Invalid):
        numbers = reading.read_numbers(value.text)
        if len(numbers) != 1:
            raise Refused(reading.scalar_error(attribute, value.text), value.source)
        return numbers[0]
    return float(value)


def vector(value: model.Vector, attribute: str) -> tuple[float, float, float] | None:
    """A vector attribute as Drake reads it (``None`` when absent)."""
    if value is None:
        return None
    if isinstance(value, model.Invalid):
        numbers = reading.read_numbers(value.text)
        if len(numbers) != 3:
            raise Refused(reading.vector_error(attribute, value.text), value.source)
        return (numbers[0], numbers[1], numbers[2])
    return value


Triple = tuple[float, float, float]


def origin(element: model.Origin) -> tuple[Triple, Triple]:
    """An ``<origin>``'s ``xyz`` and ``rpy`` as Drake reads them (zeros when absent)."""
    xyz = vector(element.xyz, "xyz") or (0.0, 0.0, 0.0)
    rpy = vector(element.rpy, "rpy") or (0.0, 0.0, 0.0)
    return xyz, rpy


def read_inertial(inertial: model.Inertial) -> Inertia:
    """``UrdfParser::ExtractSpatialInertiaAboutBoExpressedInB`` and ``ParseSpatialInertia``."""
    try:
        xyz, rpy = origin(inertial.origin)
        mass = scalar(inertial.mass, "value")
        values = [scalar(v, name) for name, v in inertial.tensor_values().items()]
    except Refused as refused:
        return Inertia("refused", message=refused.message, source=refused.source)
    tensor = written_tensor(values)
    plausible = mass if math.isfinite(mass) and mass > 0 else 1.0
    if 3.0 / (4.0 * math.pi) * (plausible / WATER) == 0.0:  # the sphere is made first, always
        return Inertia("refused", message=reading.ZERO_RADIUS, source=inertial.source)
    read = Inertia("valid", mass, xyz, rpy, tensor)
    if not reading.could_be_physically_valid(tensor):
        return replace(read, kind="sphere", message=reading.invalid_inertia_message(tensor))
    if mass == 0 and not tensor.any():
        return replace(read, kind="massless")
    if not mass > 0:
        return replace(read, kind="sphere", message=reading.NON_POSITIVE_MASS)
    return read


# --- shapes and meshes ---------------------------------------------------------------------


_SHAPES = {
    model.Box: "Box",
    model.Cylinder: "Cylinder",
    model.Sphere: "Sphere",
    model.Capsule: "Capsule",
}


def describe(geometry: model.Geometry) -> str:
    if isinstance(geometry, model.Mesh):
        return f"mesh `{geometry.filename}`"
    if isinstance(geometry, model.Unknown):
        return "geometry"
    return f"<{type(geometry).__name__.lower()}>"


Refusal = tuple[str, str | None, model.Source | None]  # kind, Drake's message, where


def shape_refusal(link: str, shape: model.Shape) -> Refusal | None:
    geometry = shape.geometry
    if isinstance(geometry, model.Unknown) and geometry.source == shape.source:
        if shape.kind == "visual":
            return "geometry", f"Link {link} has a visual element without geometry.", shape.source
        message = f"Link '{link}' has a collision element without geometry"
        return "geometry", message, shape.source
    origin(shape.origin)
    if isinstance(geometry, model.Unknown):
        if geometry.tag in ("drake:capsule", "drake:ellipsoid"):
            return None  # Drake's own shapes (inertia-kit does not read them)
        message = "Warning: geometry element does not have a recognizable shape type"
        return "geometry", message, geometry.source
    if isinstance(geometry, model.Mesh):
        return mesh_refusal(geometry)
    name = _SHAPES[type(geometry)]
    dimensions: list[tuple[str, float]] = []
    if isinstance(geometry, model.Box):
        size = vector(geometry.size, "size")
        if size is None:
            return "geometry", "Missing box attribute: size", geometry.source
        dimensions = list(zip(("width", "depth", "height"), size, strict=True))
    else:
        attributes = ("radius",) if isinstance(geometry, model.Sphere) else ("radius", "length")
        for attribute in attributes:
            value = getattr(geometry, attribute)
            if value is None:
                message = f"Missing {name.lower()} attribute: {attribute}"
                return "geometry", message, geometry.source
            dimensions.append((attribute, scalar(value, attribute)))
    for dimension, value in dimensions:
        ok = value >= 0 if name == "Sphere" else value > 0
        if not (math.isfinite(value) and ok):
            return "geometry", reading.shape_error(name, dimension, value), None
    return None


def mesh_refusal(mesh: model.Mesh) -> Refusal | None:
    """``ParseMesh``: the file (``ResolveUri``), then the scale (``ThrowForBadScale``)."""
    if not mesh.filename:
        return None
    path = drake_path(mesh)
    if path is None and mesh.path is None:
        message = None  # package:// and model://: the words depend on the user's package map
        return "mesh-missing", message, mesh.source
    if path is not None and not os.path.exists(os.path.normpath(path)):
        return (
            "mesh-missing",
            f"URI '{mesh.filename}' resolved to '{path}' which does not exist.",
            mesh.source,
        )
    scale = mesh.scale
    if isinstance(scale, model.Invalid):
        numbers = reading.read_numbers(scale.text)
        if " " in scale.text:
            if len(numbers) != 3:
                return "geometry", reading.vector_error("scale", scale.text), None
        elif len(numbers) != 1:
            return "geometry", reading.scalar_error("scale", scale.text), mesh.source
        scale = tuple(numbers) if len(numbers) == 3 else (numbers[0],) * 3
    values = (1.0, 1.0, 1.0) if scale is None else scale
    if not all(math.isfinite(v) and abs(v) >= 1e-8 for v in values):
        shown = reading.fmt_eigen_row(values)
        return "geometry", f"Mesh |scale| cannot be < 1e-8 on any axis, given [{shown}].", None
    return None


def drake_path(mesh: model.Mesh) -> str | None:
    """
    The file ``ResolveUri`` looks for (before it normalises it): ``file://`` URIs and absolute
    paths as they are, a relative path next to the file that names it, whatever other folders
    inertia-kit searches; ``None`` for ``package://`` and ``model://`` (the user's package map).
    """
    uri = mesh.filename
    found = _URI.match(uri)
    if found:
        return "/" + found[3] if found[1] == "file" else None
    if uri.startswith("/"):
        return uri
    return f"{os.path.dirname(os.path.abspath(mesh.source.path))}/{uri}"


_URI = re.compile(r"([a-z0-9+.-]+)://([^/]*)/+(.*)", re.S)


# --- joints --------------------------------------------------------------------------------

MOVING = ("revolute", "continuous", "prismatic")  # the types with <limit> and <dynamics>


@dataclass(frozen=True)
class JointReading:
    """
    What ``UrdfParser::ParseJoint`` makes of a joint: ``refusal`` (Drake's message and where,
    ``None`` for the source of the joint) stops the parser; ``friction`` is the ignored Coulomb
    friction (0 when none) at ``dynamics``.
    """

    refusal: tuple[str, model.Source | None] | None = None
    friction: float = 0.0
    dynamics: model.Source | None = None


def read_joint(joint: model.Joint) -> JointReading:
    """Origin, axis, type, then (revolute, continuous, prismatic) limits, dynamics and the
    checks of the joint's constructor, in the parser's order."""
    try:
        origin(joint.origin)
        refusal = _axis_refusal(joint) or _type_refusal(joint)
        if refusal is not None:
            return JointReading((refusal, None))
        if joint.type not in MOVING:
            return JointReading()
        limit, dynamics = joint.limit, joint.dynamics
        lower, upper, velocity = -math.inf, math.inf, math.inf
        if limit is not None:
            lower = _given(limit.lower, "lower", lower)
            upper = _given(limit.upper, "upper", upper)
            velocity = _given(limit.velocity, "velocity", velocity)
            _given(limit.effort, "effort", math.inf)
        damping = friction = 0.0
        if dynamics is not None:
            damping = _given(dynamics.damping, "damping", 0.0)
            friction = _given(dynamics.friction, "friction", 0.0)
    except Refused as refused:
        return JointReading((refused.message, refused.source))
    found = JointReading(friction=friction, dynamics=None if dynamics is None else dynamics.source)
    if not lower <= upper:
        return replace(found, refusal=(reading.JOINT_LIMITS, None))
    if damping < 0:
        kind = "Prismatic" if joint.type == "prismatic" else "Revolute"
        return replace(found, refusal=(f"{kind} joint damping must be nonnegative.", None))
    if not -velocity <= velocity:
        return replace(found, refusal=(reading.VELOCITY_LIMITS, None))
    return found


def _given(value: model.Number, attribute: str, default: float) -> float:
    """A scalar attribute as Drake reads it, ``default`` when absent."""
    return default if value is None else scalar(value, attribute)


def _axis_refusal(joint: model.Joint) -> str | None:
    if joint.type in ("fixed", "floating", "ball") or joint.axis is None:
        return None
    axis = vector(joint.axis, "xyz")
    if axis is not None and math.hypot(*axis) < 1e-8:
        return f"Joint '{joint.name}' axis is zero.  Don't do that."
    return None


def _type_refusal(joint: model.Joint) -> str | None:
    if joint.type in CUSTOM_JOINTS:
        return (
            f"Joint {joint.name} of type {joint.type} is a custom joint type, and should be a "
            "<drake:joint>"
        )
    if joint.type not in KNOWN_JOINTS:
        return f"Joint '{joint.name}' has unrecognized type: '{joint.type}'"
    return None
