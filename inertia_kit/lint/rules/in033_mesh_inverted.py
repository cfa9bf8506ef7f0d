"""IN033 mesh-inverted: a closed mesh wound inside-out, so its signed volume is negative."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import numpy as np

from inertia_kit.analysis.describe import mesh_message
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.description import model
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt

CODE = "IN033"
NAME = "mesh-inverted"
SEVERITY = Severity.ERROR
SCOPE = "link"
SUMMARY = "a closed mesh is wound inside-out: its signed volume is negative"


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    for solid in link.mesh_kind_solids():
        kind = solid.shape.kind
        mesh = solid.mesh
        if mesh is None or not mesh.inverted:
            continue
        element = solid.shape.geometry
        assert isinstance(element, model.Mesh)
        size = mesh.bounds[1] - mesh.bounds[0]
        # a whole part wound inside-out fills its box as much as any part does; a small
        # |volume| in a large box says one shell of several is inverted and cancels others
        fill = mesh.volume / float(np.prod(size)) if np.all(size > 0) else 0.0
        shells = (
            ""
            if fill >= 0.05
            else f" (only {fmt(100 * fill, 2)}% of its bounding box: probably one shell "
            "of several is inside-out and cancels the others' volume)"
        )
        name = f"{kind} mesh `{Path(element.filename).name}`"
        claim = f"is inside-out, volume {fmt(-mesh.volume, 4)} m³"
        yield ctx.finding(
            mesh_message(link.link, kind, element.filename, claim),
            element.source,
            link=link.name,
            detail=f"{name} is wound inside-out: its signed volume is "
            f"{fmt(-mesh.volume, 4)} m³{shells}",
            expected={"signed_volume": -float(mesh.volume), "triangles": mesh.triangle_count},
            help="flip the triangles' winding (normals) in a mesh tool, e.g. Blender's "
            "Recalculate Outside or trimesh's `mesh.invert()`, and export again",
        )
