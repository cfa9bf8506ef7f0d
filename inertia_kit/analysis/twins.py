"""
Twin links: a left and a right link whose names differ only by a side marker and whose
geometry mirrors across a plane of the robot, and what their declared mass properties say
about each other.

A body reflected across the plane through ``o`` with unit normal ``n`` has the same mass, its
centre of mass at ``o + P (c - o)`` and the tensor ``P I P`` (same axes), with the reflection
``P = 1 - 2 n nᵀ``: a product of inertia that involves the normal's axis changes sign, the
others and the moments stay. Each link's frame is its own, so both links' values are compared
in the root frame at zero joint positions, where physics decides: a right link whose frame the
author turned so that its URDF numbers equal the left's is right when its values mirror there.

Pairing is deliberately narrow. A name pair counts only when the names differ in one token,
and that token is a left/right marker (``l``/``r``, ``left``/``right``, or a two-letter leg
code ``fl``/``fr``, ``lh``/``rh``, ``rl``/``rr``...: the letter that differs must be the side,
so ``fl``/``rl``, front and rear, never pair). The pair is then compared only when its
geometry demonstrably mirrors: the same shapes (the same primitive sizes, the same mesh file
or one whose name differs by the side marker, at the same scale), and the volume, centroid and
second moment of the two geometries mirror across the perpendicular bisector of the two link
origins within :data:`GEOMETRY_TOLERANCE`. Anything less (no geometry, a mesh that cannot be
read, a bad number, links at the same place) and the pair is not compared.

Symmetric geometry cannot tell a mirrored part from the same part moved (two copies of one
drive in a symmetric housing): when both links use the same files placed by one rigid motion,
values that are the left's moved by that motion are right too, and only what neither the
mirror nor the motion explains is a disagreement.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.declared import declared
from inertia_kit.description import model
from inertia_kit.physics.frames import rpy_matrix, transform
from inertia_kit.physics.mass import MassProperties

if TYPE_CHECKING:
    from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis

#: the two geometries' volumes, centroids (relative to their size) and second moments
#: (relative to the largest principal one) must mirror this closely: mirrored CAD meshes and
#: repeated primitives agree far better; a different part does not
GEOMETRY_TOLERANCE = 0.02

_WORDS = re.compile(r"[A-Z]+(?=[A-Z][a-z])|[A-Z]?[a-z]+|[A-Z]+|[0-9]+")
_SIDE = {"l": "left", "r": "right", "left": "left", "right": "right"}
# the other letter of a two-letter leg code: front, back, hind, middle, rear
_PLACE = "fbhmr"


@dataclass(frozen=True)
class Marker:
    """One reading of a name token as a side marker: the side and the token without it."""

    side: str  # left | right
    blank: str  # the token with the side replaced by "?": "f?" for "fl", "?" for "l"


def tokens(name: str) -> list[str]:
    """``LHipYaw`` → ``[l, hip, yaw]``; ``FL_thigh`` → ``[fl, thigh]``; ``hip_r`` → ``[hip, r]``."""
    return [word.lower() for word in _WORDS.findall(name)]


def markers(token: str) -> list[Marker]:
    """
    Every reading of ``token`` as a left/right marker. ``rr`` has two (rear-right and
    right-rear), both right; ``fl`` one; ``rl`` one (rear-left: ``l`` is never a place).
    """
    if token in _SIDE:
        return [Marker(_SIDE[token], "?" if len(token) == 1 else "?word")]
    found = []
    if len(token) == 2:
        first, second = token
        if second in "lr" and first in _PLACE:
            found.append(Marker(_SIDE[second], f"{first}?"))
        if first in "lr" and second in _PLACE:
            found.append(Marker(_SIDE[first], f"?{second}"))
    return found


def name_keys(name: str) -> Iterator[tuple[tuple[str, ...], str]]:
    """``(key, side)`` for each token of ``name`` read as a side marker; twins share a key."""
    words = tokens(name)
    for index, word in enumerate(words):
        for marker in markers(word):
            yield (*words[:index], marker.blank, *words[index + 1 :], f"@{index}"), marker.side


def name_pairs(names: list[str]) -> list[tuple[str, str]]:
    """
    ``(left, right)`` name pairs that differ only by a side marker, in file order of the left
    name; a key with more than one name on a side (ambiguous) gives no pair.
    """
    sides: dict[tuple[str, ...], dict[str, list[str]]] = {}
    for name in names:
        for key, side in name_keys(name):
            bucket = sides.setdefault(key, {"left": [], "right": []})
            if name not in bucket[side]:
                bucket[side].append(name)
    pairs: list[tuple[str, str]] = []
    for bucket in sides.values():
        if len(bucket["left"]) == 1 and len(bucket["right"]) == 1:
            pair = (bucket["left"][0], bucket["right"][0])
            if pair[0] != pair[1] and pair not in pairs:
                pairs.append(pair)
    order = {name: i for i, name in enumerate(names)}
    return sorted(pairs, key=lambda p: order[p[0]])


def world_poses(robot: RobotAnalysis) -> dict[str, NDArray[np.float64]]:
    """
    Each link's pose in its root's frame at zero joint positions (4×4); links below a joint
    whose ``<origin>`` is not a number, or in a cycle, are left out.
    """
    poses: dict[str, NDArray[np.float64]] = {}
    for root in robot.robot.roots:
        poses.setdefault(root, np.eye(4))
        stack = [root]
        while stack:
            parent = stack.pop()
            link = robot.by_name.get(parent)
            if link is None:
                continue
            for joint in link.children:
                child = joint.child
                origin = joint.origin
                if child is None or child in poses:
                    continue
                if not isinstance(origin.xyz, tuple) or not isinstance(origin.rpy, tuple):
                    continue
                pose = poses[parent] @ transform(origin.xyz, origin.rpy)
                if not np.isfinite(pose).all():
                    continue
                poses[child] = pose
                stack.append(child)
    return poses


def reflection(normal: NDArray[np.float64]) -> NDArray[np.float64]:
    """``P = 1 - 2 n nᵀ`` for a unit normal."""
    return np.eye(3) - 2.0 * np.outer(normal, normal)


@dataclass(frozen=True)
class Plane:
    point: NDArray[np.float64]
    normal: NDArray[np.float64]

    @property
    def matrix(self) -> NDArray[np.float64]:
        return reflection(self.normal)

    def mirror(self, body: MassProperties) -> MassProperties:
        """The body reflected across the plane (same axes)."""
        p = self.matrix
        return MassProperties(
            body.mass, self.point + p @ (body.com - self.point), p @ body.inertia @ p
        )

    def axis(self) -> str | None:
        """``y`` when the normal is a root axis (within 1°), else ``None``."""
        index = int(np.argmax(np.abs(self.normal)))
        return "xyz"[index] if abs(self.normal[index]) > math.cos(math.radians(1.0)) else None


def _shape_signature(shape: model.Shape) -> tuple | None:
    """What must be equal between twin shapes: the primitive and its sizes, or the mesh."""
    g = shape.geometry
    try:
        if isinstance(g, model.Box):
            return ("box", *sorted(round(float(abs(v)), 6) for v in g.size))
        if isinstance(g, model.Cylinder):
            return ("cylinder", round(float(g.radius), 6), round(float(g.length), 6))
        if isinstance(g, model.Capsule):
            return ("capsule", round(float(g.radius), 6), round(float(g.length), 6))
        if isinstance(g, model.Sphere):
            return ("sphere", round(float(g.radius), 6))
        if isinstance(g, model.Ellipsoid):
            return ("ellipsoid", *sorted(round(float(abs(v)), 6) for v in g.radii))
        if isinstance(g, model.Mesh):
            stem = re.split(r"[/\\]", g.filename)[-1].rsplit(".", 1)[0]
            words = tokens(stem)
            sided = [
                (*words[:i], m.blank, *words[i + 1 :])
                for i, w in enumerate(words)
                for m in markers(w)
            ]
            scale = tuple(sorted(round(abs(float(v)), 6) for v in g.scale))
            # a mirrored mesh file: the name with its marker blanked; the same file: its words
            return ("mesh", tuple(sorted(sided)) if sided else tuple(words), scale)
    except (TypeError, ValueError):
        return None
    return None


def _exact(shape: model.Shape) -> tuple:
    """The shape as written, file and signed scale included: equal for the same part."""
    g = shape.geometry
    if isinstance(g, model.Mesh):
        return ("mesh", g.path or g.filename, tuple(g.scale))
    sizes = tuple(repr(getattr(g, name, None)) for name in ("size", "radius", "length"))
    return (type(g).__name__, *sizes)


def _shape_pose(shape: model.Shape) -> NDArray[np.float64] | None:
    origin = shape.origin
    if not isinstance(origin.xyz, tuple) or not isinstance(origin.rpy, tuple):
        return None
    return transform(origin.xyz, origin.rpy)


def _same_part(
    left: LinkAnalysis, right: LinkAnalysis, kind: str, left_pose: NDArray, right_pose: NDArray
) -> NDArray[np.float64] | None:
    """
    The rigid motion (4×4, root frame) carrying the left link's shapes onto the right's when
    they are the same shapes (the same files at the same scale) placed alike: then the right
    link may be the same part moved (two copies of one drive), whose values are the left's
    moved, not mirrored. ``None`` when a shape differs (a mirrored mesh file) or the shapes
    are not placed by one motion.
    """
    shapes_a = left.link.collisions if kind == "collision" else left.link.visuals
    shapes_b = right.link.collisions if kind == "collision" else right.link.visuals
    if len(shapes_a) != len(shapes_b):
        return None
    poses = []
    for a, b in zip(shapes_a, shapes_b, strict=True):
        if _exact(a) != _exact(b):
            return None
        pose_a, pose_b = _shape_pose(a), _shape_pose(b)
        if pose_a is None or pose_b is None:
            return None
        poses.append((left_pose @ pose_a, right_pose @ pose_b))
    first_a, first_b = poses[0]
    motion = first_b @ np.linalg.inv(first_a)
    for world_a, world_b in poses[1:]:
        if not np.allclose(motion @ world_a, world_b, atol=1e-6, rtol=1e-4):
            return None
    return motion


def _signatures(link: LinkAnalysis, kind: str) -> list | None:
    shapes = link.link.collisions if kind == "collision" else link.link.visuals
    found = [_shape_signature(s) for s in shapes]
    return None if not found or None in found else sorted(found, key=repr)


def _kind(link: LinkAnalysis) -> str | None:
    if link.link.collisions:
        return "collision"
    if link.link.visuals:
        return "visual"
    return None


@dataclass(frozen=True)
class Twins:
    """Two links whose names and geometry mirror, with what is known of them."""

    left: LinkAnalysis
    right: LinkAnalysis
    plane: Plane
    left_pose: NDArray[np.float64]
    right_pose: NDArray[np.float64]
    size: float  # the geometry's size: the largest extent of its bounding boxes, m
    #: the rigid motion carrying the left link onto the right when they may be the same
    #: part moved (the same files, placed alike), root frame; ``None`` for mirrored parts
    motion: NDArray[np.float64] | None = None

    def in_root(self, link: LinkAnalysis) -> MassProperties | None:
        """The link's declared mass properties in the root frame, or ``None``."""
        value = declared(link.link)
        pose = self.left_pose if link is self.left else self.right_pose
        return None if value is None else value.transformed(pose)


def _mirrors(a: MassProperties, b: MassProperties, plane: Plane, size: float) -> bool:
    """Whether ``b`` is ``a`` mirrored, to :data:`GEOMETRY_TOLERANCE` (unit-density solids)."""
    if not (a.mass > 0 and b.mass > 0):
        return False
    image = plane.mirror(a)
    tol = GEOMETRY_TOLERANCE
    if abs(image.mass - b.mass) > tol * max(image.mass, b.mass):
        return False
    if np.linalg.norm(image.com - b.com) > tol * size:
        return False
    scale = max(np.abs(np.linalg.eigvalsh(image.inertia)).max(), 1e-300)
    return bool(np.abs(image.inertia - b.inertia).max() <= tol * scale)


def _size(link: LinkAnalysis, kind: str) -> float | None:
    geometry = link.collision if kind == "collision" else link.visual
    corners = geometry.corners
    if corners is None or not np.isfinite(corners).all():
        return None
    extent = float((corners.max(axis=0) - corners.min(axis=0)).max())
    return extent if extent > 0 else None


def twins(robot: RobotAnalysis) -> tuple[list[tuple[str, str]], list[Twins]]:
    """
    The name pairs of the robot (left, right), and those of them whose geometry mirrors across
    the perpendicular bisector of their origins at zero joint positions.
    """
    names = [link.name for link in robot.links]
    pairs = name_pairs(names)
    if not pairs:
        return pairs, []
    poses = world_poses(robot)
    found: list[Twins] = []
    for left_name, right_name in pairs:
        left, right = robot.by_name.get(left_name), robot.by_name.get(right_name)
        if left is None or right is None or left_name not in poses or right_name not in poses:
            continue
        twin = _geometric_twins(left, right, poses[left_name], poses[right_name])
        if twin is not None:
            found.append(twin)
    return pairs, found


def _geometric_twins(
    left: LinkAnalysis, right: LinkAnalysis, left_pose: NDArray, right_pose: NDArray
) -> Twins | None:
    kind = _kind(left)
    if kind is None or kind != _kind(right):
        return None
    if _signatures(left, kind) != _signatures(right, kind):
        return None
    gap = left_pose[:3, 3] - right_pose[:3, 3]
    distance = float(np.linalg.norm(gap))
    size = _size(left, kind)
    if size is None or not distance > 1e-6 * max(size, 1e-3):
        return None
    plane = Plane((left_pose[:3, 3] + right_pose[:3, 3]) / 2.0, gap / distance)
    try:
        a = (left.collision if kind == "collision" else left.visual).unit
        b = (right.collision if kind == "collision" else right.visual).unit
        if a is None or b is None:
            return None
        if not _mirrors(a.transformed(left_pose), b.transformed(right_pose), plane, size):
            return None
    except (ValueError, FloatingPointError, np.linalg.LinAlgError):
        return None
    motion = _same_part(left, right, kind, left_pose, right_pose)
    return Twins(left, right, plane, left_pose, right_pose, size, motion)


def written_axes(link: LinkAnalysis, pose: NDArray[np.float64]) -> NDArray[np.float64] | None:
    """The rotation from the axes the link's ``<inertia>`` is written in to the root axes."""
    inertial = link.link.inertial
    if inertial is None or not isinstance(inertial.origin.rpy, tuple):
        return None
    return pose[:3, :3] @ rpy_matrix(inertial.origin.rpy)


#: masses may differ by this fraction of the larger (a connector on one side, a cable)
MASS_TOLERANCE = 0.05
#: the centres of mass, mirrored, may lie this fraction of the link's size apart
COM_TOLERANCE = 0.05
#: tensor entries, mirrored and scaled to the same mass, may differ by this fraction of the
#: largest principal moment: values printed to two digits round by up to 3.3 % each (0.015
#: against 0.016), and twins carry small asymmetric details (a connector, a cable)
TENSOR_TOLERANCE = 0.10

_NAMES = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
_INDEX = {"ixx": (0, 0), "ixy": (0, 1), "ixz": (0, 2), "iyy": (1, 1), "iyz": (1, 2), "izz": (2, 2)}


def six(tensor: NDArray[np.float64]) -> dict[str, float]:
    return {name: float(tensor[i, j]) for name, (i, j) in _INDEX.items()}


@dataclass(frozen=True)
class Disagreement:
    """
    How a pair of geometric twins' declared values fail to mirror. ``expected_*`` are the right
    link's values the left one's give, mirrored (the tensor scaled to the right link's mass),
    in the right link's frame (COM) and in the axes its ``<inertia>`` is written in (tensor).
    """

    twins: Twins
    left_mass: float
    right_mass: float
    mass_ratio: float | None  # heavier / lighter, when beyond MASS_TOLERANCE
    com_gap: float | None  # m, when beyond COM_TOLERANCE × size
    declared_com: NDArray[np.float64]  # the right link's, its link frame
    expected_com: NDArray[np.float64]
    declared_tensor: dict[str, float]  # the right link's six values as written
    expected_tensor: dict[str, float]
    left_tensor: dict[str, float]  # the left link's six values as written
    tensor_off: tuple[str, ...]  # the entries beyond TENSOR_TOLERANCE
    unflipped: tuple[str, ...]  # products the right link has as the left's, not mirrored
    scale: float  # the largest principal moment, kg·m²


def _agree(expected: MassProperties, declared: MassProperties, size: float) -> bool:
    """Whether ``declared`` is ``expected`` within the tolerances of :func:`compare`."""
    if abs(expected.mass - declared.mass) > MASS_TOLERANCE * max(expected.mass, declared.mass):
        return False
    if np.linalg.norm(expected.com - declared.com) > COM_TOLERANCE * size:
        return False
    scale = np.abs(np.linalg.eigvalsh(declared.inertia)).max()
    tensor = expected.inertia * (declared.mass / expected.mass)
    return bool(np.abs(tensor - declared.inertia).max() <= TENSOR_TOLERANCE * scale)


def compare(twin: Twins) -> Disagreement | None:
    """The disagreement of a pair's declared values, or ``None`` when they mirror."""
    left, right = twin.in_root(twin.left), twin.in_root(twin.right)
    left_axes = written_axes(twin.left, twin.left_pose)
    right_axes = written_axes(twin.right, twin.right_pose)
    if left is None or right is None or left_axes is None or right_axes is None:
        return None
    if not (left.validity().ok and right.validity().ok):
        return None  # an impossible tensor is IN002/IN010/IN011's business, not a twin's
    moved = None if twin.motion is None else left.transformed(twin.motion)
    if moved is not None and _agree(moved, right, twin.size):
        return None  # the same part moved: two copies of one drive need not mirror
    with np.errstate(all="ignore"):
        image = twin.plane.mirror(left)
        ratio = max(left.mass, right.mass) / min(left.mass, right.mass)
        gap = float(np.linalg.norm(image.com - right.com))
        expected_root = image.inertia * (right.mass / left.mass)
        expected = right_axes.T @ expected_root @ right_axes
        written = right_axes.T @ right.inertia @ right_axes
        unmirrored = right_axes.T @ left.inertia * (right.mass / left.mass) @ right_axes
        moments = np.concatenate(
            [np.linalg.eigvalsh(right.inertia), np.linalg.eigvalsh(expected_root)]
        )
    if not (np.isfinite(moments).all() and np.isfinite(expected).all() and np.isfinite(gap)):
        return None
    scale = float(np.abs(moments).max())
    if not scale > 0:
        return None
    limit = TENSOR_TOLERANCE * scale
    off = tuple(n for n, (i, j) in _INDEX.items() if abs(expected[i, j] - written[i, j]) > limit)
    unflipped: tuple[str, ...] = ()
    if off and np.abs(unmirrored - written).max() <= limit:
        # the right link has the left's tensor as it stands, not mirrored: name every product
        # that should have changed sign, also those too small to pass the tolerance alone
        unflipped = tuple(
            n
            for n, (i, j) in _INDEX.items()
            if i != j and abs(expected[i, j] - written[i, j]) > 1e-3 * scale
        )
    inverse = np.linalg.inv(twin.right_pose)
    expected_com = inverse[:3, :3] @ image.com + inverse[:3, 3]
    declared_com = inverse[:3, :3] @ right.com + inverse[:3, 3]
    mass_off = ratio > 1.0 + MASS_TOLERANCE
    com_off = gap > COM_TOLERANCE * twin.size
    if moved is not None:
        # the same part moved may explain the centre of mass or the tensor: only what neither
        # the mirror nor the motion explains is named
        if np.linalg.norm(moved.com - right.com) <= COM_TOLERANCE * twin.size:
            com_off = False
        same = moved.inertia * (right.mass / left.mass)
        if np.abs(same - right.inertia).max() <= limit:
            off, unflipped = (), ()
    if not (mass_off or com_off or off):
        return None
    left_written = left_axes.T @ left.inertia @ left_axes
    return Disagreement(
        twin,
        left.mass,
        right.mass,
        ratio if mass_off else None,
        gap if com_off else None,
        declared_com,
        expected_com,
        six(written),
        six(expected),
        six(left_written),
        off,
        unflipped,
        scale,
    )
