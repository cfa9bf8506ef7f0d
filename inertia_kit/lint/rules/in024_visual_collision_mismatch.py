"""IN024 visual-collision-mismatch: the collision geometry is not where or how big the visual is.

Two tests. The same shape drawn and collided (the same primitive and dimensions, or the same
mesh file and scale) at poses that differ beyond rounding is misplaced, whatever the overlap
(:mod:`inertia_kit.analysis.same_shape`). Shapes that differ, a simplified collision around a
detailed visual, are compared by their bounding boxes with generous tolerances.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import PurePosixPath

import numpy as np

from inertia_kit.analysis.describe import describe_geometry
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.analysis.same_shape import Pair, pair_shapes
from inertia_kit.description import model
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt

CODE = "IN024"
NAME = "visual-collision-mismatch"
SEVERITY = Severity.WARNING
SCOPE = "link"
# URDF's visual and collision elements; an MJCF geom is both
DESCRIPTION_FORMATS = ("urdf",)
SUMMARY = (
    "the same shape drawn and collided at different poses, or visual and collision geometry "
    "differing in size or placement beyond simplification"
)
OPTIONS = (
    Option("size_factor", float, 3.0, "largest extents more than this factor apart"),
    Option("min_overlap", float, 0.25, "smallest shared fraction of the smaller bounding box"),
    Option("max_offset", float, 0.5, "largest centroid distance as a fraction of the size"),
)

# a message longer than this leaves out what the detail says (the shape's file or dimensions)
LONG = 100
# boxes are padded by this fraction of the larger geometry's size, so that a flat plate
# (zero thickness) still overlaps the box around it
PAD = 0.02


def _box(bounds: np.ndarray) -> str:
    size = bounds[1] - bounds[0]
    centre = 0.5 * (bounds[0] + bounds[1])
    return (
        " × ".join(fmt(v, 3) for v in size) + " m at (" + ", ".join(fmt(v, 3) for v in centre) + ")"
    )


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    if not link.link.collisions or not link.link.visuals:
        return
    misplaced = [p for p in pair_shapes(link.visual.solids, link.collision.solids) if p.misplaced]
    for pair in misplaced:
        yield _misplaced(link, pair, ctx)
    if misplaced:
        return  # the misplaced twin explains any difference of the bounding boxes
    yield from _bounding_boxes(link, ctx)


# the declared centre of mass within this fraction of the distance between the two placements
# from one of them, or the declared tensor within RIGHT_TENSOR of one (and twice as far, plus
# 0.2, from the other), says which placement the link's author meant
RIGHT_COM = 0.25
RIGHT_TENSOR = 0.3


def _length(metres: float) -> str:
    return f"{fmt(metres, 3)} m" if abs(metres) >= 1 else f"{fmt(1000 * metres, 3)} mm"


def likely_right(link: LinkAnalysis, pair: Pair) -> tuple[str | None, str]:
    """
    (``visual`` or ``collision`` or ``None``, the basis): which placement the declared
    ``<inertial>`` agrees with, when the link has this one shape of each kind; otherwise, or
    when the inertial agrees with both or neither, no guess.
    """
    declared = link.declared
    if declared is None or not declared.mass > 0:
        return None, ""
    if len(link.link.visuals) != 1 or len(link.link.collisions) != 1:
        return None, ""
    assert pair.visual.unit is not None and pair.collision.unit is not None
    apart = float(np.linalg.norm(pair.offset))
    if apart > pair.tolerance:
        near = {
            kind: float(np.linalg.norm(declared.com - solid.unit.com)) / apart  # type: ignore[union-attr]
            for kind, solid in (("visual", pair.visual), ("collision", pair.collision))
        }
        kind = min(near, key=near.__getitem__)
        if near[kind] <= RIGHT_COM:
            return kind, (
                f"the declared centre of mass lies {_length(near[kind] * apart)} from the "
                f"{kind}'s centroid, {_length(near[_other(kind)] * apart)} from the "
                f"{_other(kind)}'s"
            )
        return None, ""
    scale = float(np.linalg.norm(declared.inertia))
    if not scale > 0:
        return None, ""
    error = {
        kind: float(np.linalg.norm(declared.inertia - solid.unit.with_mass(declared.mass).inertia))  # type: ignore[union-attr]
        / scale
        for kind, solid in (("visual", pair.visual), ("collision", pair.collision))
    }
    kind = min(error, key=error.__getitem__)
    if error[kind] <= RIGHT_TENSOR and error[_other(kind)] >= 2 * error[kind] + 0.2:
        return kind, (
            f"the declared inertia tensor is within {fmt(100 * error[kind], 2)}% of the "
            f"{kind}'s orientation at the declared mass, {fmt(100 * error[_other(kind)], 2)}% "
            f"from the {_other(kind)}'s"
        )
    return None, ""


def _other(kind: str) -> str:
    return "collision" if kind == "visual" else "visual"


def _misplaced(link: LinkAnalysis, pair: Pair, ctx: RuleContext) -> Finding:
    """
    The finding for a misplaced twin, said of the likely wrong one against the likely right one
    (the visual against the collision when undecided), at the wrong one's line. A misplaced
    collision, what the engines collide and PyBullet integrates, is an error; a misplaced visual
    (what the user sees) or an undecided pair, a warning.
    """
    right, basis = likely_right(link, pair)
    subject = "visual" if right is None else _other(right)
    reference = _other(subject)
    offset = pair.offset if subject == "visual" else -pair.offset
    apart = float(np.linalg.norm(offset))
    moves, short = [], []
    if pair.angle is not None and pair.angle * 0.5 * pair.size > pair.tolerance:
        moves.append(f"turned {fmt(np.degrees(pair.angle), 3)}°")
        short.append(moves[-1])
    if apart > pair.tolerance:
        unit = "m" if apart >= 1 else "mm"
        scale = 1.0 if unit == "m" else 1000.0
        vector = ", ".join(fmt(scale * v, 3) for v in offset)
        moves.append(f"moved {_length(apart)} ({vector} {unit})")
        short.append(f"moved {_length(apart)}")
    if not moves:
        moves.append(f"placed so that their points lie up to {_length(pair.distance)} apart")
        short.append(f"up to {_length(pair.distance)} off")
    geometry = getattr(pair, subject).shape.geometry
    shape = describe_geometry(geometry)
    # a mesh by its file name, a primitive with its dimensions: two twins of one xacro call
    # must differ in their message; the link's only shape of its kind needs neither when the
    # message would be long
    named = (
        f"mesh `{PurePosixPath(geometry.filename).name}`"
        if isinstance(geometry, model.Mesh)
        else shape
    )
    alone = len(link.link.visuals if subject == "visual" else link.link.collisions) == 1
    for what in (named, type(geometry).__name__.lower()):
        message = (
            f"link `{link.name}`: {subject} {what} {', '.join(short)} from its {reference} twin"
        )
        if len(message) <= LONG or not alone:
            break
    if right is None:
        severity, agrees = None, ""
        which = (
            "which of the two is right is not decidable here: compare both <origin>s with the "
            "part and give the wrong one the other's (xyz and rpy)"
        )
    else:
        severity = Severity.ERROR if subject == "collision" else None
        agrees = ", which the <inertial> agrees with"
        which = (
            f"the {right} is likely right: {basis}; give the {subject} the {reference}'s "
            "<origin> (xyz and rpy)"
        )
    consequence = (
        "simulators collide with the collision shape and draw the visual one, so the robot "
        "touches things where nothing is drawn and passes through what is drawn; MuJoCo "
        "(which discards visuals) and PyBullet (which takes the inertia from the collision "
        "shapes by default) simulate the collision placement"
    )
    return ctx.finding(
        message,
        getattr(pair, subject).shape.source,
        link=link.name,
        severity=severity,
        detail=f"the {subject} {shape} is {' and '.join(moves)} from its identical "
        f"{reference} shape{agrees}: the same shape at two poses is no simplification",
        expected={
            "same_shape": True,
            "distance": pair.distance,
            "tolerance": pair.tolerance,
            "angle_deg": None if pair.angle is None else float(np.degrees(pair.angle)),
            "offset": pair.offset.tolist(),
            "likely_right": right,
        },
        help=f"{which}; {consequence}",
    )


def _bounding_boxes(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    collision, visual = link.collision, link.visual
    if collision.hull is None or visual.hull is None or collision.unit is None:
        return
    if visual.unit is None:
        return
    c_bounds, v_bounds = collision.hull.bounds, visual.hull.bounds
    c_size, v_size = c_bounds[1] - c_bounds[0], v_bounds[1] - v_bounds[0]
    largest_c, largest_v = float(c_size.max()), float(v_size.max())
    if not (largest_c > 0 and largest_v > 0):
        return
    problems, short = [], []
    factor = float(ctx.option("size_factor"))
    ratio = largest_c / largest_v
    if ratio > factor or ratio < 1.0 / factor:
        short.append(f"collision {fmt(ratio, 4)} times the visual's size")
        problems.append(
            f"its collision geometry is {fmt(ratio, 4)} times the size of its visual geometry "
            f"({fmt(largest_c, 3)} m against {fmt(largest_v, 3)} m across)"
        )
    pad = PAD * max(largest_c, largest_v)
    overlap = np.clip(
        np.minimum(c_bounds[1], v_bounds[1]) - np.maximum(c_bounds[0], v_bounds[0]) + pad, 0.0, None
    )
    smaller = min(float(np.prod(c_size + pad)), float(np.prod(v_size + pad)))
    fraction = float(np.prod(overlap)) / smaller
    if fraction < float(ctx.option("min_overlap")):
        short.append(f"bounding boxes share {fmt(100 * fraction, 2)}%")
        problems.append(
            f"their bounding boxes share {fmt(100 * fraction, 2)}% of the smaller one "
            "(misplaced or turned: check both <origin>s)"
        )
    assert collision.unit is not None and visual.unit is not None
    offset = float(np.linalg.norm(collision.unit.com - visual.unit.com))
    size = max(largest_c, largest_v)
    if offset > float(ctx.option("max_offset")) * size:
        short.append(f"centroids {fmt(offset, 3)} m apart")
        problems.append(
            f"their centroids are {fmt(offset, 3)} m apart, {fmt(100 * offset / size, 3)}% of "
            "the geometry's size"
        )
    if not problems:
        return
    shape = link.link.collisions[0]
    yield ctx.finding(
        f"link `{link.name}`: {', '.join(short)}",
        shape.source,
        link=link.name,
        detail=f"{'; '.join(problems)}; collision {_box(c_bounds)}, visual {_box(v_bounds)}",
        expected={
            "collision_bounds": c_bounds.tolist(),
            "visual_bounds": v_bounds.tolist(),
            "size_ratio": ratio,
            "overlap": fraction,
            "centroid_offset": offset,
        },
        help="give the <collision> the visual's origin, rpy and mesh scale (or a simpler shape "
        "around the visual); simulators collide with one and draw the other",
    )
