"""
``inertia-kit mass``: the mass properties of one part, a primitive or a mesh, for people: mass,
centre of mass, the inertia tensor about the centre of mass (and about any point), principal
moments, radii of gyration and a ready-to-paste URDF ``<inertial>`` block; as text or JSON.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from inertia_kit.physics.formatting import fmt, vector_text
from inertia_kit.physics.tensor_names import DIAGONAL, INDEX, PRODUCTS
from inertia_kit.printable import printable

if TYPE_CHECKING:
    from inertia_kit.physics.mass import MassProperties

Triple = tuple[float, float, float]


@dataclass(frozen=True)
class Part:
    """
    A part at unit density, so that its mass is its volume: ``description`` says what it is as
    the command line gave it (``shape`` and its dimensions in m; a mesh's ``path`` and
    ``scale``), ``mesh`` how a mesh was integrated.
    """

    description: dict[str, Any]
    unit: MassProperties
    mesh: dict[str, Any] | None = None

    @property
    def volume(self) -> float:
        return self.unit.mass


def mesh_part(path: str, scale: Triple) -> Part:
    """A mesh file's part; ``MeshError`` when it cannot be read."""
    from inertia_kit.physics.meshes import mesh_solid

    solid = mesh_solid(path, scale)
    diagnostics = {
        "method": solid.method,
        "closed": solid.closed,
        "inverted": solid.inverted,
        "volume_error": solid.volume_error,
        "triangles": solid.triangle_count,
        "unit_scale": solid.unit_scale,
        "bounds": solid.bounds.tolist(),
    }
    return Part(
        {"shape": "mesh", "path": path, "scale": list(scale)},
        solid.mass_properties(density=1.0),
        diagnostics,
    )


def render(
    part: Part,
    *,
    density: float | None,
    mass_kg: float | None,
    xyz: Triple,
    rpy: Triple,
    about: Triple | None,
    about_rpy: Triple | None,
    output_format: str,
    withheld: str | None = None,
) -> str:
    """
    The report of ``part`` at ``density`` (kg/m³; 1000 when neither it nor ``mass_kg`` is
    given) or weighing ``mass_kg``, placed in the link frame by ``xyz`` and ``rpy`` (as a URDF
    ``<origin>``), with its tensor also about the point ``about`` in the axes rotated by
    ``about_rpy`` when either is given; no URDF block when ``withheld`` says why not.
    ``ValueError`` for a density or mass out of range.
    """
    import numpy as np

    from inertia_kit.description.writing import inertial_text, unwritable
    from inertia_kit.physics.frames import rpy_matrix
    from inertia_kit.physics.primitives import body_mass

    if density is None and mass_kg is None:
        density = 1000.0
    total = body_mass(part.volume, density, mass_kg)
    body = part.unit.with_mass(total).placed(xyz, rpy).cleaned()
    point = None if about is None and about_rpy is None else np.asarray(about or (0.0, 0.0, 0.0))
    axes = None if about_rpy is None else rpy_matrix(about_rpy)
    about_tensor = None if point is None else body.inertia_about(point, axes)
    problem = withheld or unwritable(body)
    block = inertial_text(body) if problem is None else None

    if output_format == "json":
        payload = {
            **part.description,
            "placement": {"xyz": list(xyz), "rpy": list(rpy)},
            "density": total / part.volume,
            "volume": part.volume,
            "mass": body.mass,
            "com": body.com.tolist(),
            "inertia": body.inertia.tolist(),
            "principal_moments": body.principal_moments.tolist(),
            "principal_axes": body.principal_axes.tolist(),
            "radii_of_gyration": body.radii_of_gyration.tolist(),
            "about": None
            if point is None
            else {
                "point": point.tolist(),
                "rpy": None if about_rpy is None else list(about_rpy),
                "inertia": about_tensor.tolist(),
            },
            "mesh": part.mesh,
            "urdf": block,
        }
        return json.dumps(payload, indent=2)

    basis = f"density {fmt(density)} kg/m³" if mass_kg is None else f"mass {fmt(mass_kg)} kg"
    lines = [f"{_title(part.description)}, {basis}"]
    if part.mesh is not None:
        lines += _mesh_lines(part.mesh)
    lines += [
        f"mass:   {fmt(body.mass, 6)} kg   "
        f"(volume {fmt(part.volume, 6)} m³, density {fmt(total / part.volume)} kg/m³)",
        f"centre of mass: {_vector(body.com)} m",
        "inertia about the centre of mass, link axes (kg·m²):",
        *_tensor_rows(body.inertia),
        f"principal moments: {_vector(body.principal_moments)} kg·m²;"
        f" radii of gyration {_vector(body.radii_of_gyration)} m",
    ]
    if about_tensor is not None:
        axes_note = "" if about_rpy is None else f", axes rotated by rpy {_vector(about_rpy)}"
        lines += [
            f"inertia about {_vector(point)} m{axes_note} (kg·m²):",
            *_tensor_rows(about_tensor),
        ]
    lines += ["URDF:", block] if block is not None else [f"URDF: none: {problem}"]
    return "\n".join(lines)


def _vector(values: Sequence[float]) -> str:
    return vector_text(values, 5)


def _tensor_rows(tensor: Any) -> list[str]:
    """The moments on one row and the products on the next, in aligned columns."""
    return [
        "  " + "   ".join(f"{name} {fmt(tensor[INDEX[name]]):>11}" for name in names)
        for names in (DIAGONAL, PRODUCTS)
    ]


def _title(description: dict[str, Any]) -> str:
    """``cylinder radius 0.35 m, length 0.4 m``; ``mesh part.stl scale (0.001, 0.001, 0.001)``."""
    shape = description["shape"]
    if shape == "mesh":
        path = printable(description["path"])  # a file name may hold a newline
        return f"{shape} {path} scale {_vector(description['scale'])}"
    dimensions = ", ".join(
        f"{key} {_vector(value) if isinstance(value, list) else fmt(value)} m"
        for key, value in description.items()
        if key != "shape"
    )
    return f"{shape} {dimensions}"


def _mesh_lines(mesh: dict[str, Any]) -> list[str]:
    """How the mesh was integrated, and its bounds."""
    return [
        f"mesh: {mesh['triangles']} triangles, {mesh['method']}"
        + (
            f" (volume error up to {fmt(100 * mesh['volume_error'], 3)} %)"
            if mesh["volume_error"]
            else ""
        )
        + (
            ", INVERTED: triangles wound inside-out, computed from the flipped surface"
            if mesh["inverted"]
            else ""
        )
        + (f", file unit {fmt(mesh['unit_scale'])} m" if mesh["unit_scale"] != 1 else ""),
        f"bounds: {_vector(mesh['bounds'][0])} to {_vector(mesh['bounds'][1])} m",
    ]
