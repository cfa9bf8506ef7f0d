"""
A link's geometry in words: one describer, written two ways.

:data:`MESSAGE` is how findings and notes name a shape, with units: ``box (0.4 × 0.4 × 0.1 m)``,
``cylinder (r = 0.05 m, l = 0.3 m)``, ``mesh `package://arm/pan.stl```. :data:`TABLE` is the
short form of the ``inertia-kit report`` table, which also shows what a value that is not a
number says: ``box 0.4×0.4×0.1``, ``cylinder r0.05 l0.3``, ``mesh pan.stl ×0.001 (not found)``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from inertia_kit.description import model
from inertia_kit.physics.formatting import fmt

# the lengths of the round shapes, in the order they are written; each is labelled by its
# first letter (``r``, ``l``)
_LENGTHS: dict[type, tuple[str, ...]] = {
    model.Cylinder: ("radius", "length"),
    model.Sphere: ("radius",),
    model.Capsule: ("radius", "length"),
}


@dataclass(frozen=True)
class Style:
    """How :func:`describe_geometry` writes a shape."""

    number: Callable[[model.Number], str]  # one dimension (or a whole vector that is not one)
    sides: str  # between the three values of a vector (a box's sides, a mesh's scale)
    box: str  # a box, from its sides
    length: str  # a labelled length, from its label and value
    lengths: str  # between labelled lengths
    shape: str  # a round shape, from its kind and its lengths
    mesh: Callable[[model.Mesh], str]
    unknown: Callable[[model.Unknown], str]


def _vector(value: model.Vector, style: Style) -> str:
    if not isinstance(value, tuple):
        return style.number(value)
    return style.sides.join(style.number(v) for v in value)


def _as_written(value: model.Number) -> str:
    """A number for the table: ``?`` when absent, the text itself when it is not a number."""
    if value is None:
        return "?"
    return f"{value.text!r}" if isinstance(value, model.Invalid) else fmt(value, 4)


def _mesh_entry(mesh: model.Mesh) -> str:
    """``mesh pan.stl ×0.001``: the file name, a scale other than 1, whether it was found."""
    scale = mesh.scale
    if scale == (1.0, 1.0, 1.0):
        scaled = ""
    elif isinstance(scale, tuple) and len(set(scale)) == 1:
        scaled = f" ×{TABLE.number(scale[0])}"
    else:
        scaled = f" ×{_vector(scale, TABLE)}"
    missing = "" if mesh.path else " (not found)"
    return f"mesh {mesh.filename.rsplit('/', 1)[-1]}{scaled}{missing}"


TABLE = Style(
    number=_as_written,
    sides="×",
    box="box {}",
    length="{}{}",
    lengths=" ",
    shape="{} {}",
    mesh=_mesh_entry,
    unknown=lambda unknown: f"<{unknown.tag}>" if unknown.tag else "empty geometry",
)

MESSAGE = Style(
    number=lambda value: fmt(value, 4) if isinstance(value, float) else "?",
    sides=" × ",
    box="box ({} m)",
    length="{} = {} m",
    lengths=", ",
    shape="{} ({})",
    mesh=lambda mesh: f"mesh `{mesh.filename}`",
    unknown=lambda unknown: "unknown geometry",
)


def describe_geometry(geometry: model.Geometry, style: Style = MESSAGE) -> str:
    """A shape and its dimensions, written in ``style`` (default :data:`MESSAGE`)."""
    if isinstance(geometry, model.Mesh):
        return style.mesh(geometry)
    if isinstance(geometry, model.Box):
        return style.box.format(_vector(geometry.size, style))
    if isinstance(geometry, model.Ellipsoid):
        # its semi-axes, as a box's sides: "ellipsoid (0.1 × 0.2 × 0.3 m)"
        return "ellipsoid" + style.box.format(_vector(geometry.radii, style))[3:]
    names = _LENGTHS.get(type(geometry))
    if names is None:
        return style.unknown(geometry)  # type: ignore[arg-type]
    lengths = style.lengths.join(
        style.length.format(name[0], style.number(getattr(geometry, name))) for name in names
    )
    return style.shape.format(type(geometry).__name__.lower(), lengths)


def geometry_summary(link: model.Link) -> str:
    """The report's geometry column: the link's collision shapes, else its visual ones."""
    for shapes, what in ((link.collisions, "collision: "), (link.visuals, "visual only: ")):
        if shapes:
            return what + ", ".join(describe_geometry(s.geometry, TABLE) for s in shapes)
    return "no geometry"


#: a mesh finding's message longer than this leaves out the file name (its detail has it) when
#: the link has no other shape of that kind
MESH_MESSAGE = 100


def mesh_message(link: model.Link, kind: str, filename: str, claim: str) -> str:
    """``link `arm`: collision mesh `arm.stl` <claim>``, without the file name when long."""
    from pathlib import Path

    message = f"link `{link.name}`: {kind} mesh `{Path(filename).name}` {claim}"
    shapes = link.visuals if kind == "visual" else link.collisions
    if len(message) <= MESH_MESSAGE or len(shapes) != 1:
        return message
    return f"link `{link.name}`: {kind} mesh {claim}"
