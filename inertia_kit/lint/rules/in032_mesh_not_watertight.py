"""IN032 mesh-not-watertight: an open or inconsistently wound mesh whose volume mass comes from."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

from inertia_kit.analysis.describe import mesh_message
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.description import model
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt

CODE = "IN032"
NAME = "mesh-not-watertight"
SEVERITY = Severity.WARNING
SCOPE = "link"
SUMMARY = "a collision mesh (or the visual mesh mass comes from) is open or wound inconsistently"
OPTIONS = (
    Option("tolerance", float, 0.05, "open meshes with a volume_error up to this pass"),
    Option("repaired", bool, True, "flag closed meshes with inconsistent triangle winding"),
)


def _kinds(link: LinkAnalysis) -> tuple[str, ...]:
    """
    Where a mesh's volume matters: collision meshes always (engines derive mass, contact
    volumes and hulls from them); visual meshes only when the link has no collision geometry
    and has mass or moves, so that mass properties come from them.
    """
    if link.link.collisions:
        return ("collision",)
    if link.link.visuals and (link.link.inertial is not None or link.moves):
        return ("visual",)
    return ()


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    tolerance = float(ctx.option("tolerance"))
    if link.robot is not None and link.robot.robot.format == "mjcf":
        yield from _weighed_by_mujoco(link, ctx, tolerance)
        return
    for solid in link.mesh_kind_solids(tuple(_kinds(link))):
        kind = solid.shape.kind
        mesh = solid.mesh
        if mesh is None:
            continue
        element = solid.shape.geometry
        assert isinstance(element, model.Mesh)
        name = Path(element.filename).name
        count = f"{mesh.triangle_count} triangles"
        if mesh.method == "convex-hull" and mesh.volume_error > tolerance:
            yield ctx.finding(
                mesh_message(
                    link.link,
                    kind,
                    element.filename,
                    f"is open, hull volume {fmt(100 * mesh.volume_error, 3)}% off",
                ),
                element.source,
                link=link.name,
                detail=f"{kind} mesh `{name}` is not closed ({count}): its mass properties "
                f"are those of its convex hull, whose volume ({fmt(mesh.volume, 4)} m³) "
                f"differs from the open surface's by {fmt(100 * mesh.volume_error, 3)}%",
                expected={
                    "method": mesh.method,
                    "volume": float(mesh.volume),
                    "volume_error": float(mesh.volume_error),
                },
                help="export the part as a closed solid (fill its holes, e.g. with "
                "Blender's 3D-Print Toolbox or `trimesh.repair.fill_holes`); engines that "
                "integrate the surface itself (Drake, MuJoCo's exact inertia) get "
                "another, wrong volume",
            )
        elif mesh.method == "repaired" and ctx.option("repaired"):
            yield ctx.finding(
                mesh_message(
                    link.link, kind, element.filename, "is closed but wound inconsistently"
                ),
                element.source,
                link=link.name,
                detail=f"{kind} mesh `{name}` is closed ({count}) but its triangles are wound "
                "inconsistently: computed after repairing the winding, but engines that "
                "integrate the triangles as given get a wrong volume",
                expected={
                    "method": mesh.method,
                    "volume": float(mesh.volume),
                    "volume_error": 0.0,
                },
                help="re-export the mesh with consistent outward normals (Blender: "
                "Recalculate Outside; `trimesh.repair.fix_normals`)",
            )


def _weighed_by_mujoco(link: LinkAnalysis, ctx: RuleContext, tolerance: float) -> Iterator[Finding]:
    """
    An MJCF mesh matters only where MuJoCo weighs it: a counted geom of a body whose mass
    properties it infers, in the ``legacy`` or ``exact`` mode, which add up the triangles as
    they are (``convex`` weighs the hull, and MuJoCo collides with the hull whatever the mode).
    An open mesh there gives MuJoCo another volume than the part's.
    """
    from inertia_kit.engines.mujoco_inference import infers

    inference = link.robot.robot.inference if link.robot is not None else None
    if (
        inference is None
        or not infers(link.link, inference)
        or link.robot is None
        or link.robot.welded_to_world(link.name)  # static: its mass moves nothing
    ):
        return
    for solid in link.collision.solids:
        mesh, element = solid.mesh, solid.shape.geometry
        if mesh is None or solid.unit is None or mesh.method != "convex-hull":
            continue
        assert isinstance(element, model.Mesh)
        mode = element.inertia or "legacy"
        hull = float(mesh.volume)
        if mode not in ("legacy", "exact") or not hull > 0:
            continue
        error = abs(solid.unit.mass - hull) / hull
        if error <= tolerance:
            continue
        name = Path(element.filename).name
        yield ctx.finding(
            mesh_message(
                link.link,
                "counted",
                element.filename,
                f"is open: MuJoCo weighs {fmt(100 * error, 3)}% off its hull",
            ),
            element.source,
            link=link.name,
            detail=f"mesh `{name}` is not closed ({mesh.triangle_count} triangles) and MuJoCo "
            f"infers the body's mass properties from it in its `{mode}` inertia mode, which "
            f"adds up the triangles as they are: {fmt(solid.unit.mass, 4)} m³, where its "
            f"convex hull holds {fmt(hull, 4)} m³",
            expected={
                "method": mesh.method,
                "mode": mode,
                "volume": solid.unit.mass,
                "hull_volume": hull,
                "volume_error": error,
            },
            help='close the mesh, or weigh its hull (`inertia="convex"` on the <mesh>), or '
            "write the body's <inertial> (its CAD values)",
        )
