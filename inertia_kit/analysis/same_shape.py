"""
Same shape, other place: a link's visual and collision shapes of the same primitive and
dimensions (or the same mesh file at the same scale) paired, and how far apart the two placed
solids are (IN024).

A collision shape simpler than its visual is normal, and only a bounding-box comparison with
generous tolerances can judge it. The *same* shape at another pose is never a simplification:
one of the two is misplaced, however much they overlap. Whether two placements differ is a
geometric question, so symmetries answer themselves: the distance used is the farthest any
point of one placed solid lies from the other (their Hausdorff distance), computed in closed
form for primitives (box corners, capsule segments, sphere centres; cylinder rims finely
sampled), and from the mesh's own triangles for meshes. A sphere turned any way, a cylinder
turned about its axis or end over end, a box turned a quarter about an axis whose two other
edges are equal, or half a turn about any axis: all distance 0.

"Beyond rounding" is tied to the numbers as written (:func:`written_unit`): ``1.5708`` and
``1.57`` are π/2 rounded, so the unit of their last digit is allowed (a turn, times the
shape's reach from its origin); ``0``, ``1``, ``0.05`` or ``1.5`` (fewer than three
significant digits) are taken as meant exactly. Below :data:`REL` of the shape's size nothing
counts.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass
from decimal import Decimal

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.bounds import box_corners
from inertia_kit.analysis.geometry import Solid
from inertia_kit.description import model
from inertia_kit.physics.frames import transform

# distances below this fraction of the shape's largest extent are float noise or the rounding
# of a size: 0.1 mm on a 10 cm part, 1 mrad on a turn
REL = 1e-3
# dimensions this close (relative) are the same: 0.05 and 0.05001, not 0.05 and 0.051
SAME_SIZE = 1e-4
# points sampled on each rim of a cylinder: the largest distance between two placed rims is a
# smooth maximum, which 720 samples (0.5°) find to 4e-5 of the radius
RIM_SAMPLES = 720
# vertices of a mesh whose distance to the other placement is measured (all of a small mesh)
MESH_SAMPLES = 300

TriangleReader = Callable[[Solid], "NDArray[np.float64] | None"]


@dataclass(frozen=True, eq=False)
class Pair:
    """
    A visual and a collision solid of the same shape, and how their placements differ.

    ``distance`` is the farthest a point of one placed solid lies from the other, m (for a
    mesh: the distance between the centroids when they differ, else the farthest sampled
    vertex from the other placement's surface, a lower bound that suffices to decide);
    ``tolerance`` what float noise and the rounding of the written poses allow, m.
    ``angle`` is the turn between them that no symmetry of the shape undoes, rad (``None`` for
    a sphere, which no turn changes); ``offset`` the visual's centroid minus the collision's,
    link frame, m.
    """

    visual: Solid
    collision: Solid
    distance: float
    tolerance: float
    angle: float | None
    offset: NDArray[np.float64]
    size: float

    @property
    def misplaced(self) -> bool:
        return self.distance > self.tolerance


def written_unit(value: float) -> float:
    """
    The unit of the last written digit of ``value`` when it reads as a rounded number, at least
    three significant digits (``1.5708`` → 1e-4, ``3.14`` → 0.01, ``0.785`` → 0.001), else 0:
    integers and values of one or two significant digits (``0``, ``1``, ``0.05``, ``1.5``,
    ``0.12``) are taken as meant exactly, as they usually are in robot descriptions (``1.5``
    read as π/2 rounded would forgive a 4° turn). ``value`` is read back through its shortest
    repr, which is the text written for any number parsed from text; a value xacro computed
    (``${pi/2}``) has 16 digits.
    """
    if not math.isfinite(value) or float(value).is_integer():
        return 0.0
    _sign, digits, exponent = Decimal(repr(float(value))).normalize().as_tuple()
    if not isinstance(exponent, int) or len(digits) < 3:
        return 0.0
    return 10.0**exponent


def _allowance(a: model.Origin, b: model.Origin) -> tuple[float, float]:
    """
    (m, rad): how far the two written origins may differ by rounding alone: per component the
    coarser value's last digit, the translations as a vector, the angles summed (a change of
    each angle turns the frame by at most that angle).
    """
    units = []
    for name in ("xyz", "rpy"):
        va, vb = getattr(a, name), getattr(b, name)
        units.append([max(written_unit(x), written_unit(y)) for x, y in zip(va, vb, strict=True)])  # type: ignore[arg-type]
    return float(np.linalg.norm(units[0])), float(sum(units[1]))


def _close(a: tuple[float, ...], b: tuple[float, ...], rtol: float) -> bool:
    return len(a) == len(b) and all(
        abs(x - y) <= rtol * max(abs(x), abs(y)) for x, y in zip(a, b, strict=True)
    )


def same_shape(a: Solid, b: Solid) -> bool:
    """The same primitive with the same dimensions, or the same mesh file at the same scale."""
    if a.unit is None or b.unit is None:
        return False
    ga, gb = a.shape.geometry, b.shape.geometry
    if isinstance(ga, model.Mesh) and isinstance(gb, model.Mesh):
        return (
            a.mesh is not None
            and b.mesh is not None
            and ga.path == gb.path
            and _close(a.mesh.scale, b.mesh.scale, 1e-9)
        )
    if a.part is None or b.part is None or a.part.kind != b.part.kind:
        return False
    da, db = a.part.dimensions, b.part.dimensions
    if a.part.kind == "box":  # a box written with its edges in another order is the same box
        da, db = tuple(sorted(da)), tuple(sorted(db))
    return _close(da, db, SAME_SIZE)


# --- distances between two placements of one shape ------------------------------------------


def _in_frame(points: NDArray[np.float64], pose: NDArray[np.float64]) -> NDArray[np.float64]:
    """``points`` (link frame) in the frame ``pose`` places."""
    return (points - pose[:3, 3]) @ pose[:3, :3]


def _placed(points: NDArray[np.float64], pose: NDArray[np.float64]) -> NDArray[np.float64]:
    return points @ pose[:3, :3].T + pose[:3, 3]


def _to_box(points: NDArray[np.float64], half: NDArray[np.float64]) -> NDArray[np.float64]:
    """Distance of points (box frame) to the solid box of half-extents ``half``."""
    return np.linalg.norm(np.maximum(np.abs(points) - half, 0.0), axis=1)


def _to_cylinder(points: NDArray[np.float64], radius: float, half: float) -> NDArray[np.float64]:
    radial = np.maximum(np.hypot(points[:, 0], points[:, 1]) - radius, 0.0)
    return np.hypot(radial, np.maximum(np.abs(points[:, 2]) - half, 0.0))


def _to_segment(points: NDArray[np.float64], a: NDArray, b: NDArray) -> NDArray[np.float64]:
    edge = b - a
    length2 = float(edge @ edge)
    t = np.zeros(len(points)) if length2 == 0 else np.clip((points - a) @ edge / length2, 0, 1)
    return np.linalg.norm(points - (a + t[:, None] * edge), axis=1)


def _rim(radius: float, half: float) -> NDArray[np.float64]:
    angle = np.linspace(0.0, 2.0 * np.pi, RIM_SAMPLES, endpoint=False)
    ring = np.column_stack((radius * np.cos(angle), radius * np.sin(angle)))
    return np.concatenate([np.column_stack((ring, np.full(RIM_SAMPLES, z))) for z in (-half, half)])


def _primitive_distance(kind: str, dims: tuple[float, ...], a: NDArray, b: NDArray) -> float:
    """Hausdorff distance between the primitive placed at poses ``a`` and ``b``."""
    if kind == "sphere":
        return float(np.linalg.norm(a[:3, 3] - b[:3, 3]))
    if kind == "capsule":
        half = 0.5 * dims[1]
        ends = np.array([[0.0, 0.0, -half], [0.0, 0.0, half]])
        ea, eb = _placed(ends, a), _placed(ends, b)
        return float(max(_to_segment(ea, *eb).max(), _to_segment(eb, *ea).max()))
    worst = 0.0
    for one, other in ((a, b), (b, a)):
        if kind == "box":
            half = 0.5 * np.asarray(dims)
            corners = box_corners(np.array([-half, half]))
            worst = max(worst, float(_to_box(_in_frame(_placed(corners, one), other), half).max()))
        else:  # cylinder: the farthest point of a convex solid from another is an extreme point
            radius, half_length = dims[0], 0.5 * dims[1]
            rims = _placed(_rim(radius, half_length), one)
            far = _to_cylinder(_in_frame(rims, other), radius, half_length)
            worst = max(worst, float(far.max()))
    return worst


def _to_surface(point: NDArray[np.float64], triangles: NDArray[np.float64]) -> float:
    """Distance of ``point`` to the nearest of ``triangles`` (n, 3, 3)."""
    a, b, c = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    normal = np.cross(b - a, c - a)
    area2 = np.einsum("ij,ij->i", normal, normal)
    flat = area2 > 0
    unit = np.where(flat[:, None], normal / np.sqrt(np.where(flat, area2, 1.0))[:, None], 0.0)
    # the foot of the perpendicular, when it falls inside the triangle
    height = np.einsum("ij,ij->i", point - a, unit)
    foot = point - height[:, None] * unit
    inside = flat.copy()
    for u, v in ((a, b), (b, c), (c, a)):
        inside &= np.einsum("ij,ij->i", np.cross(v - u, foot - u), normal) >= 0
    best = float(np.min(np.abs(height[inside]), initial=np.inf))
    # else the nearest point of an edge
    for u, v in ((a, b), (b, c), (c, a)):
        edge = v - u
        length2 = np.einsum("ij,ij->i", edge, edge)
        t = np.einsum("ij,ij->i", point - u, edge) / np.where(length2 > 0, length2, 1.0)
        gap = point - (u + np.clip(t, 0.0, 1.0)[:, None] * edge)
        best = min(best, float(np.sqrt(np.einsum("ij,ij->i", gap, gap).min())))
    return best


def _samples(vertices: NDArray[np.float64]) -> NDArray[np.float64]:
    """The extreme vertices along each axis and evenly spaced others, at most MESH_SAMPLES."""
    if len(vertices) <= MESH_SAMPLES:
        return vertices
    extreme = np.concatenate((vertices.argmin(axis=0), vertices.argmax(axis=0)))
    spread = np.linspace(0, len(vertices) - 1, MESH_SAMPLES - len(extreme)).astype(int)
    return vertices[np.unique(np.concatenate((extreme, spread)))]


def _mesh_distance(
    triangles: NDArray[np.float64], a: NDArray, b: NDArray, tolerance: float
) -> float:
    """
    How far the mesh (``triangles``, its own frame) placed at ``a`` lies from itself placed at
    ``b``: the largest distance of a sampled vertex of either placement from the other's
    surface, stopping at the first beyond ``tolerance`` (enough to decide; a lower bound).
    A vertex that lands on a vertex is on the surface; for the others only the triangles
    whose bounding box comes nearer than the nearest vertex are measured.
    """
    vertices = np.unique(triangles.reshape(-1, 3), axis=0)
    low, high = triangles.min(axis=1), triangles.max(axis=1)
    moved = np.linalg.inv(b) @ a
    worst = 0.0
    for turn in (moved, np.linalg.inv(moved)):
        for point in _placed(_samples(vertices), turn):
            nearest = float(np.sqrt(((vertices - point) ** 2).sum(axis=1).min()))
            if nearest <= tolerance:
                continue
            gap = np.maximum(np.maximum(low - point, point - high), 0.0)
            near = np.einsum("ij,ij->i", gap, gap) <= nearest**2
            found = min(nearest, _to_surface(point, triangles[near])) if near.any() else nearest
            worst = max(worst, found)
            if worst > tolerance:
                return worst
    return worst


# --- the turn no symmetry undoes ------------------------------------------------------------


def _angle(rotation: NDArray[np.float64]) -> float:
    return float(np.arccos(np.clip(0.5 * (np.trace(rotation) - 1.0), -1.0, 1.0)))


_SIGNED_PERMUTATIONS = [
    m
    for perm in itertools.permutations(range(3))
    for signs in itertools.product((1.0, -1.0), repeat=3)
    if np.linalg.det(m := np.eye(3)[list(perm)] * np.array(signs)[:, None]) > 0
]


def _residual_angle(kind: str, da: tuple, db: tuple, a: NDArray, b: NDArray) -> float | None:
    """The smallest turn between the two placements once the shape's symmetries are undone."""
    turn = b[:3, :3].T @ a[:3, :3]  # a's axes in b's frame
    if kind == "sphere":
        return None
    if kind in ("cylinder", "capsule"):
        return float(np.arccos(np.clip(abs(turn[2, 2]), 0.0, 1.0)))
    if kind == "box":
        # signed permutations taking a's edges onto b's of the same lengths
        sa, sb = np.asarray(da), np.asarray(db)
        fits = [m for m in _SIGNED_PERMUTATIONS if np.allclose(np.abs(m) @ sa, sb, rtol=SAME_SIZE)]
        return min(_angle(turn @ m.T) for m in fits) if fits else _angle(turn)
    return _angle(turn)


# --- pairing --------------------------------------------------------------------------------


def _pose(solid: Solid) -> NDArray[np.float64]:
    if solid.part is not None:
        return solid.part.pose
    origin = solid.shape.origin
    return transform(origin.xyz, origin.rpy)  # type: ignore[arg-type]


def _extent(solid: Solid) -> tuple[float, float]:
    """(largest extent, reach: the farthest point of the shape from its own origin), m."""
    if solid.part is not None:
        kind, dims = solid.part.kind, solid.part.dimensions
        if kind == "box":
            return max(dims), 0.5 * float(np.linalg.norm(dims))
        if kind == "sphere":
            return 2 * dims[0], dims[0]
        if kind == "capsule":
            return max(2 * dims[0], dims[1] + 2 * dims[0]), 0.5 * dims[1] + dims[0]
        return max(2 * dims[0], dims[1]), math.hypot(dims[0], 0.5 * dims[1])
    assert solid.mesh is not None
    bounds = solid.mesh.bounds
    return float((bounds[1] - bounds[0]).max()), float(
        np.linalg.norm(box_corners(bounds), axis=1).max()
    )


def compare(visual: Solid, collision: Solid, read: TriangleReader) -> Pair:
    """How the placements of two solids of the same shape (:func:`same_shape`) differ."""
    a, b = _pose(visual), _pose(collision)
    size, reach = _extent(visual)
    shift, turn = _allowance(visual.shape.origin, collision.shape.origin)
    tolerance = REL * size + shift + turn * reach
    assert visual.unit is not None and collision.unit is not None
    offset = visual.unit.com - collision.unit.com
    if visual.part is not None and collision.part is not None:
        kind = visual.part.kind
        dims_v, dims_c = visual.part.dimensions, collision.part.dimensions
        if kind == "box" and dims_v != dims_c:
            # the same box written with its edges in another order: compare as solids
            distance = _boxes_distance(dims_v, dims_c, a, b)
        else:
            distance = _primitive_distance(kind, dims_v, a, b)
        angle = _residual_angle(kind, dims_v, dims_c, a, b)
        return Pair(visual, collision, distance, tolerance, angle, offset, size)
    # a mesh: the poses, compared over the corners of its bounding box, bound how far any of its
    # points moves; beyond rounding, different centroids are different solids, and only a turn
    # about the centroid (a symmetry of the part, perhaps) needs its triangles
    assert visual.mesh is not None
    corners = box_corners(visual.mesh.bounds)
    moved = float(np.linalg.norm(_placed(corners, a) - _placed(corners, b), axis=1).max())
    angle = _angle(b[:3, :3].T @ a[:3, :3])
    apart = float(np.linalg.norm(offset))
    if moved <= tolerance:
        return Pair(visual, collision, moved, tolerance, angle, offset, size)
    if apart > tolerance:
        return Pair(visual, collision, apart, tolerance, angle, offset, size)
    triangles = read(visual)
    # unreadable now: nothing tells the turn from a symmetry of the part, so no finding
    distance = apart if triangles is None else _mesh_distance(triangles, a, b, tolerance)
    return Pair(visual, collision, distance, tolerance, angle, offset, size)


def _boxes_distance(da: tuple, db: tuple, a: NDArray, b: NDArray) -> float:
    worst = 0.0
    for (d1, p1), (d2, p2) in (((da, a), (db, b)), ((db, b), (da, a))):
        half1, half2 = 0.5 * np.asarray(d1), 0.5 * np.asarray(d2)
        corners = _placed(box_corners(np.array([-half1, half1])), p1)
        worst = max(worst, float(_to_box(_in_frame(corners, p2), half2).max()))
    return worst


def read_triangles_in_metres(solid: Solid) -> NDArray[np.float64] | None:
    """The mesh's triangles in its own frame, metres and URDF scale applied; ``None`` unread."""
    from inertia_kit.errors import MeshError
    from inertia_kit.physics.mesh_formats import read_triangles

    if solid.mesh is None:
        return None
    try:
        triangles, _ = read_triangles(solid.mesh.path)
    except (MeshError, OSError, ValueError):
        return None
    # the unit the solid was computed in, so that its bounds and these triangles agree
    return triangles * (solid.mesh.unit_scale * np.asarray(solid.mesh.scale))


def pair_shapes(
    visuals: tuple[Solid, ...],
    collisions: tuple[Solid, ...],
    read: TriangleReader = read_triangles_in_metres,
) -> list[Pair]:
    """
    Each visual paired with a collision solid of the same shape, closest placements first,
    each solid in one pair at most: two identical wheels drawn and collided pair left with
    left. A visual whose same-shape partners are all taken, or that has none, is in no pair.
    """
    candidates = [compare(v, c, read) for v in visuals for c in collisions if same_shape(v, c)]
    candidates.sort(key=lambda p: p.distance / max(p.tolerance, 1e-300))
    pairs, used = [], set()
    for pair in candidates:
        if id(pair.visual) in used or id(pair.collision) in used:
            continue
        used.update((id(pair.visual), id(pair.collision)))
        pairs.append(pair)
    return pairs
