"""IN024 visual-collision-mismatch: the collision geometry is not where or how big the visual is."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt

CODE = "IN024"
NAME = "visual-collision-mismatch"
SEVERITY = Severity.WARNING
SCOPE = "link"
SUMMARY = "visual and collision geometry differ in size or placement beyond simplification"
OPTIONS = (
    Option("size_factor", float, 3.0, "largest extents more than this factor apart"),
    Option("min_overlap", float, 0.25, "smallest shared fraction of the smaller bounding box"),
    Option("max_offset", float, 0.5, "largest centroid distance as a fraction of the size"),
)

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
    problems = []
    factor = float(ctx.option("size_factor"))
    ratio = largest_c / largest_v
    if ratio > factor or ratio < 1.0 / factor:
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
        problems.append(
            f"their bounding boxes share {fmt(100 * fraction, 2)}% of the smaller one "
            "(misplaced or turned: check both <origin>s)"
        )
    assert collision.unit is not None and visual.unit is not None
    offset = float(np.linalg.norm(collision.unit.com - visual.unit.com))
    size = max(largest_c, largest_v)
    if offset > float(ctx.option("max_offset")) * size:
        problems.append(
            f"their centroids are {fmt(offset, 3)} m apart, {fmt(100 * offset / size, 3)}% of "
            "the geometry's size"
        )
    if not problems:
        return
    shape = link.link.collisions[0]
    yield ctx.finding(
        f"link `{link.name}`: {'; '.join(problems)}; collision {_box(c_bounds)}, "
        f"visual {_box(v_bounds)}",
        shape.source,
        link=link.name,
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
