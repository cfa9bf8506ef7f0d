"""Why a link's geometry cannot give its mass properties, or the values cannot be written."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from inertia_kit.analysis.links import LinkAnalysis
    from inertia_kit.physics.mass import MassProperties


def geometry_refusal(link: LinkAnalysis) -> str | None:
    """Why the link's geometry cannot give its mass properties (with what to do), or ``None``."""
    geometry = link.geometry
    if link.skeletal:
        return (
            "muscles act on this model: its shapes are bones, wrapping surfaces and skin, not "
            "the body's flesh; write its <inertial> from the model's anthropometry"
        )
    if not geometry.solids:
        if link.parent is None:
            return (
                "the robot's base has no <visual> or <collision> geometry to compute its mass "
                "from: write its <inertial> by hand, or hang the robot from a `world` link by "
                "a fixed joint if its base is fixed"
            )
        return (
            "it has no <visual> or <collision> geometry to compute from: write its <inertial> "
            "by hand, or give it geometry"
        )
    for solid, (kind, message) in geometry.problems:
        what = _shape_name(solid)
        hint = {
            "mesh-not-found": "fix the mesh path (or --package-path)",
            "mesh-unreadable": "re-export the mesh as STL, OBJ or PLY",
            "mesh-empty": "re-export the mesh",
        }.get(kind, "fix the shape")
        return f"its {what}: {kind.replace('-', ' ')}: {message}; {hint}, then run again"
    for solid in geometry.solids:
        if solid.mesh is not None and solid.mesh.inverted:
            return (
                f"its {_shape_name(solid)} is wound inside-out (negative volume): "
                "re-export it with outward normals, then run again"
            )
    if geometry.unit is None or not geometry.unit.mass > 0:
        return "its geometry has no volume"
    return None


def spoiled(code: str, message: str, expected: dict | None) -> str:
    """The reason for a link whose geometry a finding (``code``, ``message``) spoils."""
    scale = (expected or {}).get("scale")
    suggestion = (
        f'; set scale="{" ".join(f"{v:g}" for v in scale)}" if that is its unit' if scale else ""
    )
    return f"its geometry cannot be trusted ({code}): {message}{suggestion}"


def unwritable(properties: MassProperties) -> str | None:
    """
    Why ``properties`` must not be written (:func:`~inertia_kit.description.writing.
    unwritable`: never a number the linter refuses), with what to do, or ``None``.
    """
    from inertia_kit.description.writing import unwritable as why

    problem = why(properties)
    if problem is None:
        return None
    return (
        f"{problem.replace('its ', 'its computed ', 1)}; check the geometry's dimensions, the "
        "density and the mass, then run again"
    )


def _shape_name(solid) -> str:
    from inertia_kit.analysis.describe import describe_geometry

    return f"{solid.shape.kind} {describe_geometry(solid.shape.geometry)}"
