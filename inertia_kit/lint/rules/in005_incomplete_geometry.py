"""IN005 incomplete-geometry: a `<geometry>` absent, empty, unknown, or a shape without a size."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.geometry import absent_sizes
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.description import model
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.rules import RuleContext

CODE = "IN005"
NAME = "incomplete-geometry"
SEVERITY = Severity.ERROR
SCOPE = "link"
# URDF's shapes and what its readers refuse; an MJCF geom we do not read yet (a primitive
# MuJoCo fits to a mesh) is no fault of the file
DESCRIPTION_FORMATS = ("urdf",)
SUMMARY = (
    "a `<visual>`/`<collision>` without `<geometry>`, with an empty or unknown one, or a shape "
    "without its size (`<sphere/>`, `<box/>`, a `<cylinder>` without `length`)"
)

# urdfdom's words for each refusal (urdf_parser/src/link.cpp: parseSphere, parseBox,
# parseCylinder, parseGeometry); its capsule is no shape at all
URDFDOM = {
    "sphere": "Sphere shape must have a radius attribute",
    "box": "Box shape has no size attribute",
    "cylinder": "Cylinder shape must have both length and radius attributes",
    "capsule": "Unknown geometry type 'capsule'",
    "empty": "Geometry tag contains no child element.",
    "absent": "Could not parse {kind} element for Link [{link}]",
}
# Shapes one engine adds to URDF, and which of the engines below reads each (measured): a file
# meant for that engine, so an info, not a defect; inertia-kit computes none of them
EXTENSIONS = {
    "plane": "PyBullet",  # <plane normal>: an infinite half-space
    "cdf": "PyBullet",  # a signed-distance file
    "drake:capsule": "Drake",
    "drake:ellipsoid": "Drake",
}
# who refuses what urdfdom refuses, measured: PyBullet "Cannot load URDF file."; Drake "Missing
# sphere attribute: radius", "geometry element does not have a recognizable shape type"; MuJoCo
# refuses a collision shape ("required attribute missing: 'radius'", "visual geometry
# specification not found", "missing element: 'geometry'") and drops visual ones unread
ENGINES = ("Gazebo", "Drake", "PyBullet", "MuJoCo")

HELP_SIZE = (
    'write the shape\'s size in metres: `<sphere radius>`, `<box size="x y z">`, '
    "`<cylinder radius length>`"
)
HELP_SHAPE = (
    "write one of URDF's shapes in the `<geometry>`: `<box size>`, `<cylinder radius length>`, "
    "`<sphere radius>` or `<mesh filename>`; or remove the `<{kind}>` if the link needs none"
)
HELP_EXTENSION = (
    "for a file other tools read too, write a `<box>`, `<cylinder>`, `<sphere>` or `<mesh>`; "
    "for a {reader}-only file, nothing to do"
)


def _refusers(kind: str, reader: str | None) -> str:
    """Who refuses the file besides urdfdom: every engine but ``reader``; MuJoCo for collisions."""
    names = [e for e in ENGINES if e != reader and (e != "MuJoCo" or kind == "collision")]
    return ", ".join(names[:-1]) + " and " + names[-1]


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    for shape in (*link.link.visuals, *link.link.collisions):
        geometry = shape.geometry
        reader = EXTENSIONS.get(geometry.tag) if isinstance(geometry, model.Unknown) else None
        help_text = HELP_SHAPE.format(kind=shape.kind)
        if isinstance(geometry, model.Unknown):
            if geometry.absent:
                what = f"its {shape.kind} has no `<geometry>`"
                words = URDFDOM["absent"].format(kind=shape.kind, link=link.name)
            elif geometry.tag is None:
                what = f"its {shape.kind} `<geometry>` is empty"
                words = URDFDOM["empty"]
            else:
                what = f"its {shape.kind} `<geometry>` holds `<{geometry.tag}>`, " + (
                    f"a {reader} extension" if reader else "no shape URDF has"
                )
                words = f"Unknown geometry type '{geometry.tag}'"
                if reader:
                    help_text = HELP_EXTENSION.format(reader=reader)
        else:
            absent = absent_sizes(geometry)
            if not absent:
                continue
            tag = type(geometry).__name__.lower()
            what = f"its {shape.kind} `<{tag}>` has no " + " and no ".join(
                f"`{name}`" for name in absent
            )
            words = URDFDOM[tag]
            help_text = HELP_SIZE
        readers = f"{reader} reads it; " if reader else ""
        dropped = "" if shape.kind == "collision" else " (MuJoCo drops visuals on import)"
        unchecked = (
            "; the link's mass and inertia are not checked against this shape"
            if link.link.inertial is not None
            else ""
        )
        yield ctx.finding(
            f"link `{link.name}`: {what}",
            geometry.source or shape.source,
            link=link.name,
            detail=f'{readers}ROS (urdfdom: "{words}"), {_refusers(shape.kind, reader)} refuse '
            f"the file{dropped}{unchecked}",
            help=help_text,
            severity=Severity.INFO if reader else None,
        )
