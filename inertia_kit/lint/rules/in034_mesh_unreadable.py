"""IN034 mesh-unreadable: a mesh file that is corrupt or in a format that cannot be read."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.description import model
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.rules import RuleContext

CODE = "IN034"
NAME = "mesh-unreadable"
SEVERITY = Severity.ERROR
SCOPE = "link"
SUMMARY = "a visual/collision mesh file is corrupt or in an unsupported format"


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    robot = link.robot
    if robot is not None and robot.robot.format == "mjcf" and robot.welded_to_world(link.name):
        return  # MJCF scenery: a static body's mass moves nothing, nothing is lost unread
    for solid in link.mesh_kind_solids():
        kind = solid.shape.kind
        if solid.problem is None or solid.problem[0] != "mesh-unreadable":
            continue
        # the mesh readers only for an unreadable mesh: a robot of primitives needs none
        from inertia_kit.physics.mesh_formats import FORMATS

        mesh = solid.shape.geometry
        assert isinstance(mesh, model.Mesh)
        suffix = Path(mesh.path or mesh.filename).suffix.lower()
        name = Path(mesh.filename).name  # the URI whole is in the detail
        if suffix not in FORMATS:
            # a format some engines read (Drake's .vtk, assimp's .3ds) but we do not:
            # the file may be fine, the geometry checks are what is lost
            yield ctx.finding(
                f"link `{link.name}`: {kind} mesh `{name}` is in a format inertia-kit does "
                "not read",
                mesh.source,
                link=link.name,
                detail=f"{kind} mesh `{mesh.filename}` is in a format inertia-kit does not "
                f"read (`{suffix or '(no suffix)'}`; it reads {', '.join(FORMATS)}): its "
                "geometry checks are skipped",
                help="convert the mesh to STL, OBJ or DAE (MuJoCo reads STL and OBJ, "
                "Drake OBJ, PyBullet OBJ and STL), or ignore IN034 for this link",
                severity=Severity.WARNING,
            )
            continue
        yield ctx.finding(
            f"link `{link.name}`: {kind} mesh `{name}` cannot be read",
            mesh.source,
            link=link.name,
            detail=f"{kind} mesh `{mesh.filename}` cannot be read: {solid.problem[1]}",
            help="re-export the part from the CAD tool (binary STL is read by every "
            "engine); until then no engine can use it and its geometry checks are skipped",
        )
