"""IN026 degenerate-geometry: a shape with a zero or negative size, or thinner than an atom
(1e-10 m, physics/numbers.py), or a mesh with no volume, or one whose moments overflow."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.describe import describe_geometry
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.description import model
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.rules import RuleContext

CODE = "IN026"
NAME = "degenerate-geometry"
SEVERITY = Severity.ERROR
SCOPE = "link"
SUMMARY = (
    "a visual/collision shape has a zero or negative size, or one below 1e-10 m, or a mesh "
    "encloses no volume"
)

# Solid.problem kinds this rule reports; the others belong to IN004 (invalid-number), IN030
# (mesh-not-found) and IN034 (mesh-unreadable)
KINDS = ("degenerate", "mesh-empty")

HELP = {
    "degenerate": "give every dimension a positive size in metres (a mirrored mesh takes a "
    "negative scale factor, never a zero one); a frame with no body needs no shape at all",
    "mesh-empty": "export the part's solid body (not a sketch, a sheet or a curve), or remove "
    "the shape",
}


def _drake_refuses(geometry: model.Geometry) -> bool:
    """
    Drake refuses the model at this shape, visual or collision (``Box()``, ``Cylinder()``,
    ``Capsule()``: each dimension must be > 0; measured with drake 1.51.1); a zero sphere it
    accepts.
    """
    if isinstance(geometry, model.Box):
        dimensions = geometry.size if isinstance(geometry.size, tuple) else ()
    elif isinstance(geometry, (model.Cylinder, model.Capsule)):
        dimensions = (geometry.radius, geometry.length)
    else:
        return False
    return any(isinstance(v, float) and v <= 0 for v in dimensions)


def _named(geometry: model.Geometry) -> str:
    """The shape for the message: with its sizes, a mesh by its file's name alone."""
    if isinstance(geometry, model.Mesh):
        return f"mesh `{geometry.filename.replace(chr(92), '/').rsplit('/', 1)[-1]}`"
    return describe_geometry(geometry)


def _has_mass(link: LinkAnalysis) -> bool:
    inertial = link.link.inertial
    return inertial is not None and isinstance(inertial.mass, float) and inertial.mass > 0


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    element = link.link
    # the visual shapes matter for mass only when there is no collision geometry
    visual_is_basis = not element.collisions and _has_mass(link)
    for shapes, geometry in (
        (element.collisions, lambda: link.collision),
        (element.visuals, lambda: link.visual),
    ):
        if not shapes:
            continue
        for solid in geometry().solids:
            if solid.problem is None or solid.problem[0] not in KINDS:
                continue
            kind, detail = solid.problem
            shape = solid.shape
            severity = None
            if shape.kind == "visual" and not visual_is_basis:
                if kind == "mesh-empty":
                    continue  # a flat decal or ground plane draws fine and weighs nothing
                if not _drake_refuses(shape.geometry):
                    severity = Severity.WARNING
            described = describe_geometry(shape.geometry)
            yield ctx.finding(
                f"link `{link.name}`: its {shape.kind} {_named(shape.geometry)} is degenerate",
                shape.geometry.source or shape.source,
                link=link.name,
                detail=f"its {shape.kind} {described}: {detail}",
                help=HELP[kind],
                severity=severity,
            )
