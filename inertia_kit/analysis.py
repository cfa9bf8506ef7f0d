"""
Per-link analysis shared by report, lint and fill: the declared mass properties, as the
simulators will read them, and (later stages) the geometry-derived ones.
"""

from __future__ import annotations

from inertia_kit import model
from inertia_kit.mass import MassProperties


def _finite(value: model.Number) -> float | None:
    return value if isinstance(value, float) else None


def declared(link: model.Link) -> MassProperties | None:
    """
    The link's ``<inertial>`` as mass properties in the link frame, or ``None`` when it is
    absent or incomplete (a value missing or not a finite number).
    """
    inertial = link.inertial
    if inertial is None:
        return None
    mass = _finite(inertial.mass)
    tensor = [_finite(v) for v in inertial.tensor_values().values()]
    xyz, rpy = inertial.origin.xyz, inertial.origin.rpy
    if mass is None or None in tensor or not isinstance(xyz, tuple) or not isinstance(rpy, tuple):
        return None
    ixx, ixy, ixz, iyy, iyz, izz = tensor
    return MassProperties.from_urdf(mass, ixx, ixy, ixz, iyy, iyz, izz, xyz=xyz, rpy=rpy)  # type: ignore[arg-type]


def _number(value: model.Number) -> str:
    from inertia_kit.text import fmt

    if value is None:
        return "?"
    return f"{value.text!r}" if isinstance(value, model.Invalid) else fmt(value, 4)


def _vector(value: model.Vector) -> str:
    if value is None:
        return "?"
    if isinstance(value, model.Invalid):
        return repr(value.text)
    return "×".join(_number(v) for v in value)


def describe_geometry(geometry: model.Geometry) -> str:
    """A short summary: ``box 0.4×0.4×0.1``, ``cylinder r0.35 l0.4``, ``mesh pan.stl ×0.001``."""
    if isinstance(geometry, model.Box):
        return f"box {_vector(geometry.size)}"
    if isinstance(geometry, model.Cylinder):
        return f"cylinder r{_number(geometry.radius)} l{_number(geometry.length)}"
    if isinstance(geometry, model.Sphere):
        return f"sphere r{_number(geometry.radius)}"
    if isinstance(geometry, model.Capsule):
        return f"capsule r{_number(geometry.radius)} l{_number(geometry.length)}"
    if isinstance(geometry, model.Mesh):
        name = geometry.filename.rsplit("/", 1)[-1]
        scale = geometry.scale
        scaled = (
            ""
            if scale == (1.0, 1.0, 1.0)
            else (
                f" ×{_number(scale[0])}"
                if isinstance(scale, tuple) and len(set(scale)) == 1
                else f" ×{_vector(scale)}"
            )
        )
        missing = "" if geometry.path else " (not found)"
        return f"mesh {name}{scaled}{missing}"
    return f"<{geometry.tag}>" if geometry.tag else "empty geometry"


def geometry_summary(link: model.Link) -> str:
    """What geometry the link has: collision shapes, else visual ones."""
    if link.collisions:
        return "collision: " + ", ".join(describe_geometry(s.geometry) for s in link.collisions)
    if link.visuals:
        return "visual only: " + ", ".join(describe_geometry(s.geometry) for s in link.visuals)
    return "no geometry"
