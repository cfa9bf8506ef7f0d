"""IN031 mesh-units: a mesh whose size says it was authored in mm, cm or inches."""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from inertia_kit.analysis.declared import declared_mass
from inertia_kit.analysis.describe import describe_geometry
from inertia_kit.analysis.geometry import Solid
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.description import model
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt, xml_number

if TYPE_CHECKING:
    # imported where a mesh is judged: a robot of primitives needs none of it
    from inertia_kit.analysis.mesh_units import Evidence

CODE = "IN031"
NAME = "mesh-units"
SEVERITY = Severity.WARNING
SCOPE = "link"
# a mesh in other units gives wrong values: no fix from this geometry until it is scaled
SPOILS_GEOMETRY = True
SUMMARY = "a mesh's size says it was authored in mm, cm or inches: suggests the exact `scale`"
OPTIONS = (
    Option("min_size", float, 0.001, "the smallest size a robot part can have, m", above=True),
    Option("max_size", float, 5.0, "the largest size a robot part can have, m", above=True),
    Option("min_density", float, 1.0, "the lowest density a part can have, kg/m³", above=True),
    Option("max_density", float, 1e7, "the highest density a part can have, kg/m³", above=True),
    Option("min_evidence", int, 2, "how many observations must be out of line"),
)

# A mesh's size compared with the link's other evidence, as log10 ratios, and the bands real
# robots fall in (measured on the 8 781 meshes of 1 245 published robot files: see the rule's
# document). Joint offsets and the link's primitives are written in metres in the URDF itself,
# so they cannot share a mesh's unit slip.
JOINT_BAND = (-1.5, 1.2)  # log10(mesh extent / largest joint offset at the link)
PEER_BAND = (-1.5, 1.5)  # log10(mesh extent / extent of the link's other shapes)
# joint offsets shorter than this say nothing about a link's size
MIN_OFFSET = 0.001
# the unit a slip that shrinks the mesh says it is in, for the message (SLIPS says how it
# happened); a slip that grows it says it is in metres already
_AUTHORED = {0.001: "mm", 0.01: "cm", 0.0254: "inches"}
# a mesh vouches for the size of the link's other meshes when this many observations of its
# own, all in band, back it (its size alone would let a tiny slipped mesh accuse a sound one)
TRUST = 2


def _extent(solid: Solid) -> float:
    """Largest dimension of the solid's bounding box in its own frame, m."""
    if solid.mesh is not None:
        bounds = solid.mesh.bounds
    elif solid.corners is not None:
        bounds = np.array([solid.corners.min(axis=0), solid.corners.max(axis=0)])
    else:
        return 0.0
    return float(np.max(bounds[1] - bounds[0]))


def _joint_offset(link: LinkAnalysis) -> float | None:
    """The longest offset of the joints at the link (parent and children), m."""
    lengths = []
    for joint in (link.parent, *link.children):
        if joint is not None and isinstance(joint.origin.xyz, tuple):
            lengths.append(math.sqrt(sum(v * v for v in joint.origin.xyz)))
    longest = max(lengths, default=0.0)
    return longest if longest >= MIN_OFFSET else None


def _same_file(a: Solid, b: Solid) -> bool:
    """Two shapes that use the same file at the same scale share any unit slip."""
    ga, gb = a.shape.geometry, b.shape.geometry
    return (
        isinstance(ga, model.Mesh)
        and isinstance(gb, model.Mesh)
        and ga.path == gb.path
        and ga.scale == gb.scale
    )


def _authored(slips: tuple[float, ...]) -> str:
    """``in mm``, ``in cm or inches``, ``already in metres``: the units the slips say."""
    units = list(dict.fromkeys(_AUTHORED[s] for s in slips if s in _AUTHORED))
    grown = any(s not in _AUTHORED for s in slips)
    words = []
    if units:
        words.append("in " + (", ".join(units[:-1]) + " or " if len(units) > 1 else "") + units[-1])
    if grown:
        words.append("already in metres")
    return " or ".join(words)


def _describe(solid: Solid) -> str:
    geometry = solid.shape.geometry
    if isinstance(geometry, model.Mesh):
        return f"{solid.shape.kind} mesh `{Path(geometry.filename).name}`"
    return f"{solid.shape.kind} {describe_geometry(geometry)}"


def _evidence(
    link: LinkAnalysis, solid: Solid, peers: list[Solid], ctx: RuleContext
) -> list[Evidence]:
    from inertia_kit.analysis.mesh_units import Evidence, density_evidence, size_evidence

    mesh = solid.mesh
    assert mesh is not None
    extent = _extent(solid)
    if not extent > 0:
        return []
    size = math.log10(extent)
    found = []
    # a shape's size alone says something only of a robot part: a link with mass, one that
    # moves, or one of several links (a lone massless 120 m mesh is a scene, not a slip)
    several = link.robot is not None and len(link.robot.links) > 1
    if declared_mass(link.link) is not None or link.moves or several:
        band = (float(ctx.option("min_size")), float(ctx.option("max_size")))
        found.append(size_evidence(extent, band))
    offset = _joint_offset(link)
    if offset is not None:
        found.append(
            Evidence(
                "joints",
                lambda r: size + r - math.log10(offset),
                JOINT_BAND,
                lambda r: f"the link's longest joint offset is {fmt(offset, 3)} m",
            )
        )
    # the link's other shapes are one witness of its size, the largest of them: three contact
    # spheres of a fingertip (ALOHA's 0.6 mm pads) are not three votes for a 100 mm mesh in inches
    sized = [(other, peer) for peer in peers if (other := _extent(peer)) > 0]
    for other, peer in sorted(sized, key=lambda pair: pair[0])[-1:]:
        if other > 0:
            found.append(
                Evidence(
                    "peer",
                    lambda r, other=other: size + r - math.log10(other),
                    PEER_BAND,
                    lambda r, peer=peer, other=other: (
                        f"its {_describe(peer)} spans {fmt(other, 3)} m"
                    ),
                )
            )
    mass = declared_mass(link.link)
    basis = link.geometry
    if mass is not None and basis.unit is not None and any(s is solid for s in basis.solids):
        own, total = mesh.volume, basis.volume
        rest = max(total - own, 0.0)
        band = (float(ctx.option("min_density")), float(ctx.option("max_density")))
        found.append(
            density_evidence(
                mass, own, rest, band, lambda m, d: f"{fmt(m, 3)} kg in it is {fmt(d, 4)} kg/m³"
            )
        )
    return found


@dataclass(frozen=True)
class Verdict:
    solid: Solid
    slip: float | None  # the unit slip that explains the evidence, None when none is needed
    evidence: tuple[Evidence, ...]
    others: tuple[float, ...] = ()  # other slips that explain it as well (cm or inches?)


def _judge(link: LinkAnalysis, solid: Solid, peers: list[Solid], ctx: RuleContext) -> Verdict:
    from inertia_kit.analysis.mesh_units import suspected_unit

    evidence = _evidence(link, solid, peers, ctx)
    suspicion = suspected_unit(evidence, int(ctx.option("min_evidence")))
    return Verdict(solid, suspicion.slip, tuple(evidence), suspicion.others)


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    kinds = [
        kind
        for kind, shapes in (("visual", link.link.visuals), ("collision", link.link.collisions))
        if shapes
    ]
    solids = [s for kind in kinds for s in getattr(link, kind).solids]
    meshes = [s for s in solids if s.mesh is not None]
    if not meshes:
        return
    # primitives are sized in metres in the URDF itself: always trusted peers. Meshes first
    # judged on everything else; one that passes then vouches for the others, so that a
    # visual mesh in mm next to its collision mesh in m is told apart, and a robot exported
    # all in mm is not excused by its own meshes
    primitives = [s for s in solids if s.part is not None]
    first = {id(s): _judge(link, s, primitives, ctx) for s in meshes}
    trusted = [
        s
        for s in meshes
        if first[id(s)].slip is None and len(first[id(s)].evidence) >= TRUST
        if all(e.excess() == 0 for e in first[id(s)].evidence)
    ]
    verdicts = []
    for solid in meshes:
        verdict = first[id(solid)]
        if verdict.slip is None:
            peers = [
                p
                for p in trusted
                if p is not solid and p.shape.kind != solid.shape.kind and not _same_file(p, solid)
            ]
            if peers:
                verdict = _judge(link, solid, primitives + peers, ctx)
        verdicts.append(verdict)
    for verdict in verdicts:
        if verdict.slip is None:
            # the same file at the same scale as a slipped shape has slipped the same way (a
            # visual mesh that is also the collision mesh, where only the latter has a density)
            twin = next(
                (v for v in verdicts if v.slip is not None and _same_file(v.solid, verdict.solid)),
                None,
            )
            if twin is None:
                continue
            verdict = Verdict(verdict.solid, twin.slip, twin.evidence, twin.others)
        yield _finding(link, verdict, ctx)


def _finding(link: LinkAnalysis, verdict: Verdict, ctx: RuleContext) -> Finding:
    from inertia_kit.analysis.mesh_units import SLIPS, VIOLATION

    solid, slip = verdict.solid, verdict.slip
    assert slip is not None and solid.mesh is not None
    element = solid.shape.geometry
    assert isinstance(element, model.Mesh)
    scale = element.scale if isinstance(element.scale, tuple) else (1.0, 1.0, 1.0)
    new = tuple(v * slip for v in scale)
    uniform = len(set(new)) == 1
    text = " ".join(xml_number(v, 6) for v in new)
    extent = _extent(solid)
    r = math.log10(slip)
    against = [e.text(0.0) for e in verdict.evidence if e.excess() > VIOLATION]
    written = (
        "no scale" if scale == (1.0, 1.0, 1.0) else f'scale="{" ".join(fmt(v) for v in scale)}"'
    )
    density = [e.text(r) for e in verdict.evidence if e.kind == "density"]
    alternatives = [
        f'scale="{" ".join(xml_number(v * other, 6) for v in scale)}" '
        f"({SLIPS[other].removeprefix('as if ')})"
        for other in verdict.others
    ]
    also = f"; {' or '.join(alternatives)} would fit too" if alternatives else ""
    # the message: the mesh, its size and the unit it looks authored in; the evidence, the
    # scale that fits and its alternatives are in the detail (and ``expected``)
    if scale == (1.0, 1.0, 1.0):
        at = ""
    elif len(set(scale)) == 1:
        at = f" at scale {fmt(scale[0])}"
    else:
        at = " at its scale"
    return ctx.finding(
        f"link `{link.name}`: {_describe(solid)} spans {fmt(extent, 3)} m{at}, "
        f"as if {_authored((slip, *verdict.others))}",
        element.source,
        link=link.name,
        detail=f"{_describe(solid)} spans {fmt(extent, 3)} m with {written}, "
        f'{SLIPS[slip]}: {"; ".join(against)}; with scale="{text}" it spans '
        f"{fmt(extent * slip, 3)} m" + (f" and {density[0]}" if density else "") + also,
        expected={
            "scale": list(new),
            "factor": slip,
            "extent": float(extent * slip),
            "uniform": uniform,
            "filename": element.filename,
            "kind": solid.shape.kind,
            "alternatives": [[v * other for v in scale] for other in verdict.others],
        },
        help=f'set <mesh ... scale="{text}"/>, or re-export the mesh in metres'
        if slip < 1
        else f'set <mesh ... scale="{text}"/>: the mesh is in metres already',
    )
