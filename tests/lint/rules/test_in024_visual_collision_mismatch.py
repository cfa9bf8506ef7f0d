"""
IN024 visual-collision-mismatch: the same shape at two poses (whatever the overlap), and the size,
overlap and centroid offset of geometries that differ.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from kit import write
from kit.meshes import binary_stl, box_triangles
from kit.urdf import box, collision, cylinder, inertial, mesh, moving, sphere, visual

from inertia_kit.analysis.same_shape import pair_shapes, written_unit
from inertia_kit.lint.findings import Severity
from inertia_kit.physics.meshes import mesh_solid

CYLINDER = cylinder(0.02, 0.3)
# not the same cylinder: the bounding-box test judges it
THICKER = cylinder(0.025, 0.3)
ALONG_X = "0 1.5707963267948966 0"


def test_identical_geometry_is_quiet(lint):
    body = visual(CYLINDER, rpy=ALONG_X) + collision(CYLINDER, rpy=ALONG_X)
    assert lint(moving(body), "IN024") == []


def test_simplified_box_around_a_cylinder_is_quiet(lint):
    body = visual(CYLINDER, rpy=ALONG_X) + collision(box(0.32, 0.05, 0.05))
    assert lint(moving(body), "IN024") == []


def test_collision_turned_the_other_way_fires(lint):
    """
    Visual along x, a thicker collision left along z: the boxes share 0.05 × 0.04 × 0.04 of
    the smaller one, 0.3 × 0.04 × 0.04 (each padded by 2 % of 0.3 m).
    """
    body = visual(CYLINDER, rpy=ALONG_X) + collision(THICKER)
    findings = lint(moving(body), "IN024")
    assert len(findings) == 1
    assert "bounding boxes share " in findings[0].message
    assert "misplaced or turned" in findings[0].detail
    pad = 0.02 * 0.3
    expected = (0.05 + pad) * (0.04 + pad) ** 2 / ((0.3 + pad) * (0.04 + pad) ** 2)
    assert findings[0].expected["overlap"] == pytest.approx(expected, rel=1e-2)


def test_millimetre_scale_missing_on_one_side_fires(lint):
    body = visual(box(0.1, 0.1, 0.1)) + collision(box(100, 100, 100))
    findings = lint(moving(body), "IN024")
    assert len(findings) == 1
    assert findings[0].expected["size_ratio"] == pytest.approx(1000.0)
    assert findings[0].message == "link `arm`: collision 1000 times the visual's size"
    assert "(100 m against 0.1 m across)" in findings[0].detail


def test_misplaced_collision_fires_on_the_centroid_offset(lint):
    """A sphere drawn 6 cm above a slightly larger collision sphere: offset 0.06 > 0.051."""
    body = visual(sphere(0.05), xyz="0 0 0.06") + collision(sphere(0.051))
    findings = lint(moving(body), "IN024")
    assert len(findings) == 1
    assert findings[0].expected["centroid_offset"] == pytest.approx(0.06)
    assert "centroids 0.06 m apart" in findings[0].message
    assert "centroids are 0.06 m apart" in findings[0].detail


def test_options(lint):
    body = visual(box(0.1, 0.1, 0.1)) + collision(box(0.25, 0.25, 0.25))
    assert lint(moving(body), "IN024") == []  # 2.5 times: within the default 3
    assert len(lint(moving(body), "IN024", options={"IN024": {"size_factor": 2.0}})) == 1
    turned = visual(CYLINDER, rpy=ALONG_X) + collision(THICKER)
    assert lint(moving(turned), "IN024", options={"IN024": {"min_overlap": 0.1}}) == []
    shifted = visual(sphere(0.05), xyz="0 0 0.04") + collision(sphere(0.051))
    assert lint(moving(shifted), "IN024") == []
    assert len(lint(moving(shifted), "IN024", options={"IN024": {"max_offset": 0.3}})) == 1


def test_several_collision_shapes_covering_the_visual_are_quiet(lint):
    """A capsule-like arm drawn as one cylinder, collided as a cylinder and two end spheres."""
    body = (
        visual(cylinder(0.05, 0.4))
        + collision(cylinder(0.05, 0.3))
        + collision(sphere(0.05), xyz="0 0 0.15")
        + collision(sphere(0.05), xyz="0 0 -0.15")
    )
    assert lint(moving(body), "IN024") == []


def test_only_one_kind_or_an_unusable_shape_is_not_its_business(lint):
    assert lint(moving(visual(CYLINDER)), "IN024") == []
    assert lint(moving(collision(CYLINDER)), "IN024") == []
    missing = visual(mesh("missing.stl")) + collision(CYLINDER)
    assert lint(moving(missing), "IN024") == []


# --- the same shape at two poses ------------------------------------------------------------

PLATE = box(0.1, 0.2, 0.3)  # three different edges: only half turns about its axes keep it


def _one(lint, body: str, **kw):
    findings = lint(moving(body), "IN024", **kw)
    assert len(findings) == 1, [f.message for f in findings]
    return findings[0]


def test_a_box_turned_88_degrees_over_its_twin_fires(lint):
    """
    The issue's first example: their bounding boxes overlap almost entirely (the old test was
    quiet). The corner (0.05, 0.1, 0.15) turned by 88° about z lands at (0.05 cos 88° - 0.1 sin
    88°, 0.05 sin 88° + 0.1 cos 88°) = (-0.098, 0.053): outside the twin's |x| ≤ 0.05 by 0.048.
    """
    turn = math.radians(88)
    finding = _one(lint, visual(PLATE, rpy=f"0 0 {turn!r}") + collision(PLATE))
    assert finding.message == (
        "link `arm`: visual box (0.1 × 0.2 × 0.3 m) turned 88° from its collision twin"
    )
    assert "identical collision shape" in finding.detail
    assert finding.expected["angle_deg"] == pytest.approx(88.0)
    corners = [(x, y) for x in (-0.05, 0.05) for y in (-0.1, 0.1)]
    turned = [
        (x * math.cos(turn) - y * math.sin(turn), x * math.sin(turn) + y * math.cos(turn))
        for x, y in corners
    ]
    farthest = max(math.hypot(max(abs(x) - 0.05, 0.0), max(abs(y) - 0.1, 0.0)) for x, y in turned)
    assert finding.expected["distance"] == pytest.approx(farthest, rel=1e-9)
    assert finding.severity == Severity.WARNING  # no <inertial> to tell which is right
    assert "not decidable" in finding.help


def test_a_sphere_lifted_by_its_radius_fires(lint):
    """The issue's second example: 50 % overlap by volume, and centroids one radius apart."""
    ball = sphere(0.05)
    finding = _one(lint, visual(ball, xyz="0 0 0.05") + collision(ball))
    assert "moved 50 mm from its collision twin" in finding.message
    assert "moved 50 mm (0, 0, 50 mm)" in finding.detail
    assert "turned" not in finding.message  # a sphere turned is the same sphere
    assert finding.expected["distance"] == pytest.approx(0.05)
    assert finding.expected["angle_deg"] is None


@pytest.mark.parametrize(
    ("shape", "rpy_visual", "rpy_collision"),
    [
        # a sphere turned any way
        (sphere(0.05), "0.3 1.1 -2.0", None),
        # a cylinder turned about its own axis, and flipped end to end (about x, about y)
        (CYLINDER, "0 0 0.7", None),
        (CYLINDER, f"{math.pi!r} 0 0", None),
        (CYLINDER, "0 3.14159 0", "0 0 1.2"),
        (cylinder(0.02, 0.3).replace("cylinder", "capsule"), f"{math.pi!r} 0 0.4", None),
        # a box turned a quarter about the axis whose two other edges are equal
        (box(0.1, 0.1, 0.3), "0 0 1.5708", None),
        (box(0.1, 0.3, 0.1), "0 1.5707963267948966 0", "0 0 0"),
        # half a turn about each of its axes, written as π to various precisions
        (PLATE, "3.14159265 0 0", None),
        (PLATE, "0 3.1416 0", None),
        (PLATE, "0 0 3.14", None),
        (PLATE, "3.14159 0 3.14159", "0 3.1415927 0"),
        # π/2 written as 1.5708 on one side and 1.57079632679 on the other: rounding
        (PLATE, "0 0 1.5708", "0 0 1.57079632679"),
        (PLATE, "0 1.57 0", "0 1.5707963267948966 0"),
    ],
)
def test_symmetric_turns_and_rounding_are_quiet(lint, shape, rpy_visual, rpy_collision):
    body = visual(shape, rpy=rpy_visual) + collision(shape, rpy=rpy_collision)
    assert lint(moving(body), "IN024") == []


def test_a_box_written_with_its_edges_in_another_order_is_the_same_box(lint):
    """
    A camera body written 0.09 × 0.025 × 0.02505 turned by (π/2, 0, π/2) is the collision's
    0.02505 × 0.09 × 0.025 unturned: quiet; moved 15 mm along x it is not.
    """
    turned = visual(box(0.09, 0.025, 0.02505), rpy="1.570796326795 0 1.570796326795")
    assert lint(moving(turned + collision(box(0.02505, 0.09, 0.025))), "IN024") == []
    moved = visual(
        box(0.09, 0.025, 0.02505), xyz="0.0149 0 0", rpy="1.570796326795 0 1.570796326795"
    )
    finding = _one(lint, moved + collision(box(0.02505, 0.09, 0.025)))
    assert "moved 14.9 mm" in finding.message and "turned" not in finding.message
    assert finding.expected["distance"] == pytest.approx(0.0149)


@pytest.mark.parametrize(
    ("rpy", "degrees"),
    [
        ("0 0 1.5", 90 - math.degrees(1.5)),  # a square box a quarter turn off by 4.06°
        ("0 0 0.79", 90 - math.degrees(0.79)),  # 45.26°: 44.74° from a quarter turn
    ],
)
def test_a_turn_a_symmetry_does_not_undo_fires_with_the_residual_angle(lint, rpy, degrees):
    """1.5 is not π/2 rounded (two significant digits are read as meant): 4° is beyond."""
    square = box(0.1, 0.1, 0.3)
    finding = _one(lint, visual(square, rpy=rpy) + collision(square))
    assert finding.expected["angle_deg"] == pytest.approx(degrees, rel=1e-9)


def test_a_cylinder_tilted_fires_with_the_angle_between_its_axes(lint):
    finding = _one(lint, visual(CYLINDER, rpy="0.2 0 0") + collision(CYLINDER, rpy="0 0 1.0"))
    # turning about z keeps the axis; the roll of 0.2 rad tilts it by 0.2 rad
    assert finding.expected["angle_deg"] == pytest.approx(math.degrees(0.2), rel=1e-9)


def test_the_tolerance_follows_the_written_digits(lint):
    """
    On a 0.3 m box 0.3 mm (0.1 %) is noise. Beyond it: 1 mm from 0 fires; 0.049 next to 0.05
    fires (two significant digits are read as meant); 0.124 next to 0.1235 is quiet (three
    digits: 0.1235 rounded to its last, 1e-3); 0.12 next to 0.1235 fires (3.5 mm, two digits).
    """
    assert len(lint(moving(visual(PLATE, xyz="0.001 0 0") + collision(PLATE)), "IN024")) == 1
    assert lint(moving(visual(PLATE, xyz="0.0002 0 0") + collision(PLATE)), "IN024") == []
    for written, fires in (("0.049", True), ("0.124", False), ("0.12", True)):
        reference = "0.05" if written == "0.049" else "0.1235"
        body = visual(PLATE, xyz=f"{written} 0 0") + collision(PLATE, xyz=f"{reference} 0 0")
        assert len(lint(moving(body), "IN024")) == fires, written


@pytest.mark.parametrize(
    ("value", "unit"),
    [
        (1.5708, 1e-4),
        (1.57, 1e-2),
        (3.14, 1e-2),
        (0.785, 1e-3),
        (-0.7854, 1e-4),
        (0.0523, 1e-4),
        (0.00012, 0.0),  # two: 1.2e-4 exactly
        (0.000123, 1e-6),
        (1.0, 0.0),
        (0.0, 0.0),
        (0.05, 0.0),  # one or two significant digits: meant exactly
        (1.5, 0.0),
        (0.79, 0.0),
        (1e-05, 0.0),
        (math.pi, 10.0**-15),
    ],
)
def test_written_unit(value, unit):
    assert written_unit(value) == pytest.approx(unit, rel=1e-12)


def test_identical_wheels_pair_with_their_own_twin(lint):
    """Two identical wheels, listed in another order among the collisions: quiet."""
    wheel = cylinder(0.05, 0.02)
    body = (
        visual(wheel, xyz="0 0.2 0", rpy="1.5708 0 0")
        + visual(wheel, xyz="0 -0.2 0", rpy="1.5708 0 0")
        + collision(wheel, xyz="0 -0.2 0", rpy="-1.5708 0 0")
        + collision(wheel, xyz="0 0.2 0", rpy="1.5708 0 0")
    )
    assert lint(moving(body), "IN024") == []


def test_a_visual_without_a_free_twin_falls_back_to_the_bounding_boxes(lint):
    """Three spheres drawn, two of them collided: the third is no misplaced twin of either."""
    ball = sphere(0.05)
    body = (
        visual(ball)
        + visual(ball, xyz="0 0 0.1")
        + visual(ball, xyz="0 0 0.2")
        + collision(ball)
        + collision(ball, xyz="0 0 0.1")
    )
    assert lint(moving(body), "IN024") == []


def test_the_inertial_tells_which_one_is_likely_right(lint):
    """
    A sphere of 1 kg, r = 5 cm lifted by its radius: with the centre of mass at the visual's
    centre the collision is the misplaced one (what the engines collide and, in PyBullet,
    integrate): an error at the <collision>; at the collision's, a warning at the <visual>.
    """
    ball = sphere(0.05)
    moment = 0.4 * 1.0 * 0.05**2
    shapes = visual(ball, xyz="0 0 0.05") + collision(ball)
    at_visual = _one(lint, inertial(1.0, moment, xyz="0 0 0.05") + shapes)
    assert at_visual.severity == Severity.ERROR
    assert at_visual.expected["likely_right"] == "visual"
    assert "the visual is likely right" in at_visual.help
    at_collision = _one(lint, inertial(1.0, moment) + shapes)
    assert at_collision.severity == Severity.WARNING
    assert at_collision.expected["likely_right"] == "collision"
    assert at_collision.column < at_visual.column  # the <visual> comes first on the line


def test_the_inertia_tensor_tells_which_turn_is_right(lint):
    """The rule document's arm: the tensor (least moment along x) matches the visual along x."""
    mass, radius, length = 0.3, 0.02, 0.3
    along = 0.5 * mass * radius**2
    across = mass * (3 * radius**2 + length**2) / 12
    body = (
        inertial(mass, along, across, across) + visual(CYLINDER, rpy=ALONG_X) + collision(CYLINDER)
    )
    finding = _one(lint, body)
    assert finding.expected["likely_right"] == "visual"
    assert finding.severity == Severity.ERROR


def test_several_shapes_leave_the_guess_alone(lint):
    ball = sphere(0.05)
    body = (
        inertial(1.0, 0.001, xyz="0 0 0.05")
        + visual(ball, xyz="0 0 0.05")
        + visual(box(0.3, 0.3, 0.01))
        + collision(ball)
        + collision(box(0.3, 0.3, 0.01))
    )
    finding = _one(lint, body)
    assert finding.expected["likely_right"] is None


# --- meshes: the same file at the same scale ------------------------------------------------


def _prism(sides: int, radius: float, length: float) -> np.ndarray:
    """A regular prism along z centred on its frame, its triangles wound outwards."""
    angles = 2 * np.pi * np.arange(sides) / sides
    ring = np.column_stack((radius * np.cos(angles), radius * np.sin(angles)))
    low = np.column_stack((ring, np.full(sides, -length / 2)))
    high = np.column_stack((ring, np.full(sides, length / 2)))
    triangles = []
    for i in range(sides):
        j = (i + 1) % sides
        triangles += [(low[i], low[j], high[j]), (low[i], high[j], high[i])]
        triangles += [((0, 0, -length / 2), low[j], low[i]), ((0, 0, length / 2), high[i], high[j])]
    return np.array(triangles, dtype=np.float64)


def _mesh_robot(tmp_path, triangles, visual_origin, collision_origin, scales=(None, None)):
    """The link's body: one mesh file drawn and collided at the origins given."""
    write(tmp_path / "part.stl", binary_stl(triangles))
    return visual(mesh("part.stl", scales[0]), **visual_origin) + collision(
        mesh("part.stl", scales[1]), **collision_origin
    )


def test_a_mesh_at_its_own_pose_twice_is_quiet_and_moved_fires(lint, tmp_path):
    part = box_triangles((0.1, 0.1, 0.2), low=(0, 0, 0))  # corner at its origin
    same = _mesh_robot(tmp_path, part, {"xyz": "0 0 0.0125"}, {"xyz": "0 0 0.0125"})
    assert lint(moving(same), "IN024") == []
    moved = _mesh_robot(tmp_path, part, {"xyz": "0 0 0.0867"}, {})
    finding = _one(lint, moved)
    assert (
        finding.message
        == "link `arm`: visual mesh `part.stl` moved 86.7 mm from its collision twin"
    )
    assert "moved 86.7 mm (0, 0, 86.7 mm)" in finding.detail


def test_a_mesh_turned_by_one_of_its_symmetries_is_quiet(lint, tmp_path):
    """
    A centred 0.1 × 0.1 × 0.2 box mesh turned a quarter about z: its vertices land on
    vertices. A 64-sided prism turned by 0.3 rad about its axis: its vertices land between
    vertices, within r (1 - cos(π/64)) = 6e-5 m of the surface, under 0.1 % of its 0.1 m size.
    """
    part = box_triangles((0.1, 0.1, 0.2), low=(-0.05, -0.05, -0.1))
    assert lint(moving(_mesh_robot(tmp_path, part, {"rpy": "0 0 1.5708"}, {})), "IN024") == []
    prism = _prism(64, 0.05, 0.1)
    assert lint(moving(_mesh_robot(tmp_path, prism, {"rpy": "0 0 0.3"}, {})), "IN024") == []
    assert lint(moving(_mesh_robot(tmp_path, prism, {"rpy": "3.14159265 0 0"}, {})), "IN024") == []


def test_a_mesh_turned_otherwise_fires(lint, tmp_path):
    """
    The box mesh turned 45° about z pokes its corners 0.05 (√2 - 1) = 21 mm beyond its twin;
    the prism tipped a quarter turn is no prism along z. Both centroids stay at the origin.
    """
    part = box_triangles((0.1, 0.1, 0.2), low=(-0.05, -0.05, -0.1))
    finding = _one(lint, _mesh_robot(tmp_path, part, {"rpy": "0 0 0.7853981633974483"}, {}))
    assert "turned 45°" in finding.message and "moved" not in finding.message
    assert finding.expected["distance"] > 0.01
    prism = _prism(64, 0.05, 0.3)
    finding = _one(lint, _mesh_robot(tmp_path, prism, {"rpy": "1.5707963267948966 0 0"}, {}))
    assert "turned 90°" in finding.message


def test_a_mesh_at_another_scale_is_another_shape(lint, tmp_path):
    """The same file at two scales: the bounding-box test, which passes a 10 % larger hull."""
    part = box_triangles((0.1, 0.1, 0.2), low=(-0.05, -0.05, -0.1))
    body = _mesh_robot(tmp_path, part, {"xyz": "0 0 0.001"}, {}, scales=(None, "1.1 1.1 1.1"))
    assert lint(moving(body), "IN024") == []


def test_an_unreadable_mesh_is_judged_by_its_centroids(tmp_path):
    """When the triangles cannot be read again, different centroids still mean different places."""
    from inertia_kit.analysis.geometry import evaluate_shape
    from inertia_kit.description import model

    path = write(
        tmp_path / "part.stl", binary_stl(box_triangles((0.1, 0.1, 0.2), (-0.05, -0.05, -0.1)))
    )
    part = mesh_solid(path)

    def solid(xyz, rpy):
        origin = model.Origin(xyz=xyz, rpy=rpy)
        geometry = model.Mesh("part.stl", str(path), (1.0, 1.0, 1.0), model.Source("r"))
        shape = model.Shape("visual", None, origin, geometry, model.Source("r"))
        return evaluate_shape(shape, lambda path, scale: part)

    moved = solid((0.0, 0.0, 0.05), (0.0, 0.0, 0.0))
    turned = solid((0.0, 0.0, 0.0), (0.0, 0.0, 1.0))
    still = solid((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    [pair] = pair_shapes((moved,), (still,), read=lambda s: None)
    assert pair.misplaced and pair.distance == pytest.approx(0.05)
    [pair] = pair_shapes((turned,), (still,), read=lambda s: None)
    assert not pair.misplaced  # a centred mesh turned: nothing left to tell


def test_the_message_is_one_short_line_and_the_detail_keeps_the_basis(lint):
    """A twin moved and a geometry out of scale: what moved or differs, by how much, in the
    message; the offset vector, the verdict and the bounding boxes in the detail."""
    finding = _one(lint, visual(PLATE, xyz="0 0 0.05") + collision(PLATE))
    assert finding.message == (
        "link `arm`: visual box (0.1 × 0.2 × 0.3 m) moved 50 mm from its collision twin"
    )
    assert len(finding.message) <= 100
    assert finding.detail == (
        "the visual box (0.1 × 0.2 × 0.3 m) is moved 50 mm (0, 0, 50 mm) from its identical "
        "collision shape: the same shape at two poses is no simplification"
    )
    finding = _one(lint, visual(box(0.1, 0.1, 0.1)) + collision(box(100, 100, 100)))
    assert len(finding.message) <= 100
    assert finding.detail.startswith(
        "its collision geometry is 1000 times the size of its visual geometry (100 m against "
        "0.1 m across)"
    )
    assert finding.detail.endswith(
        "collision 100 × 100 × 100 m at (0, 0, 0), visual 0.1 × 0.1 × 0.1 m at (0, 0, 0)"
    )


def test_a_long_message_names_the_only_shape_of_its_kind_by_its_type(lint, tmp_path):
    """example-robot-data's `RightSakeBaseFingerLink1`: its one visual mesh, turned and moved,
    would make a message of 120 characters with its file name, which the detail keeps."""
    triangles = box_triangles((0.1, 0.1, 0.2), low=(-0.05, -0.05, -0.1))  # centred
    write(tmp_path / "sake_finger_knuckle.stl", binary_stl(triangles))
    name = "RightSakeBaseFingerLink1"
    body = visual(mesh("sake_finger_knuckle.stl"), xyz="0 0 0.0309", rpy="0 0 1.5707963") + (
        collision(mesh("sake_finger_knuckle.stl"))
    )
    (finding,) = lint(moving(body, name=name), "IN024")
    assert finding.message == (
        f"link `{name}`: visual mesh turned 90°, moved 30.9 mm from its collision twin"
    )
    assert "the visual mesh `sake_finger_knuckle.stl` is turned 90° and moved" in finding.detail
