"""The geometric bounds and comparisons of analysis.py, against closed forms and invariants."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from inertia_kit.analysis.links import (
    RIM_SIDES,
    Hull,
    analyse,
    axis_name,
    compare_tensors,
    moment_excess,
)
from inertia_kit.description.loader import load
from inertia_kit.physics.frames import rpy_matrix, transform
from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.unions import Part

RIM = 1.0 / math.cos(math.pi / RIM_SIDES)  # how far the cylinder hull's corners overshoot


def robot(tmp_path: Path, links: str, joints: str = "") -> object:
    path = tmp_path / "r.urdf"
    path.write_text(f'<robot name="r">{links}{joints}</robot>')
    return analyse(load(path))


# --- Hull -------------------------------------------------------------------------------------


def test_box_hull_support_and_farthest():
    size = np.array([0.4, 0.2, 0.1])
    hull = Hull.of_part(Part.box(size, transform((1.0, 0.0, 0.0))))
    assert hull.support(np.eye(3)) == pytest.approx([1.2, 0.1, 0.05])
    assert hull.support(-np.eye(3)) == pytest.approx([-0.8, 0.1, 0.05])
    assert hull.farthest((1.0, 0.0, 0.0)) == pytest.approx(np.linalg.norm(size / 2))
    np.testing.assert_allclose(hull.bounds, [[0.8, -0.1, -0.05], [1.2, 0.1, 0.05]])


def test_rotated_box_hull_is_exact_not_its_bounding_box():
    # a 1 × 0.1 × 0.1 box turned 45° about z reaches (0.5 + 0.05)/√2 along x, not 0.55
    hull = Hull.of_part(Part.box((1.0, 0.1, 0.1), transform(rpy=(0, 0, math.pi / 4))))
    assert hull.support([[1.0, 0.0, 0.0]])[0] == pytest.approx(0.55 / math.sqrt(2))


def test_sphere_and_capsule_hulls_are_balls():
    sphere = Hull.of_part(Part.sphere(0.3, transform((0.0, 0.0, 1.0))))
    assert sphere.farthest((0.0, 0.0, 0.0)) == pytest.approx(1.3)
    assert sphere.support([[0.0, 0.0, -1.0]])[0] == pytest.approx(-0.7)
    capsule = Hull.of_part(Part.capsule(0.1, 0.4, transform(rpy=(0, math.pi / 2, 0))))
    assert capsule.support(np.eye(3)) == pytest.approx([0.3, 0.1, 0.1])
    assert capsule.farthest_from_axes((0, 0, 0), [[1.0, 0.0, 0.0]])[0] == pytest.approx(0.1)


def test_cylinder_hull_contains_the_rim_and_overshoots_by_the_polygon_only():
    radius, length = 0.05, 0.3
    hull = Hull.of_part(Part.cylinder(radius, length))
    reach = hull.farthest_from_axes((0, 0, 0), [[0.0, 0.0, 1.0]])[0]
    assert radius <= reach <= radius * RIM + 1e-15
    # any direction in the xy-plane: between the circle and the circumscribed polygon
    angles = np.linspace(0, 2 * np.pi, 97)
    directions = np.column_stack((np.cos(angles), np.sin(angles), np.zeros_like(angles)))
    support = hull.support(directions)
    assert (support >= radius - 1e-15).all() and (support <= radius * RIM + 1e-15).all()
    assert hull.support([[0.0, 0.0, 1.0]])[0] == pytest.approx(length / 2)


def test_moment_bound_of_a_centred_box_is_the_corner_distance():
    a, b, c = 0.2, 0.1, 0.05  # half sizes
    hull = Hull.of_part(Part.box((2 * a, 2 * b, 2 * c)))
    bound = hull.moment_bound((0, 0, 0), np.eye(3))
    np.testing.assert_allclose(bound, [b * b + c * c, a * a + c * c, a * a + b * b])


def test_moment_bound_shrinks_with_an_off_centre_com_bhatia_davis():
    a, b, c, d = 0.2, 0.1, 0.05, 0.15  # COM d along x from the centre
    hull = Hull.of_part(Part.box((2 * a, 2 * b, 2 * c)))
    bound = hull.moment_bound((d, 0, 0), np.eye(3))
    # about y: second moments along x ≤ (a - d)(a + d), along z ≤ c²
    assert bound[1] == pytest.approx((a - d) * (a + d) + c * c)
    assert bound[1] < (a + d) ** 2 + c * c  # tighter than the distance to the far corner


@pytest.mark.parametrize("seed", range(5))
def test_moment_bound_holds_for_random_distributions_inside(seed):
    """No distribution inside the geometry has more than the bound about its own COM."""
    rng = np.random.default_rng(seed)
    pose = transform(rng.uniform(-1, 1, 3), rng.uniform(-np.pi, np.pi, 3))
    radius, length = 0.1, 0.5
    hull = Hull.of_part(Part.cylinder(radius, length, pose))
    count = int(rng.integers(2, 6))
    # point masses on the cylinder's rims: the extreme distributions
    angle = rng.uniform(0, 2 * np.pi, count)
    local = np.column_stack(
        (radius * np.cos(angle), radius * np.sin(angle), rng.choice([-0.5, 0.5], count) * length)
    )
    points = local @ pose[:3, :3].T + pose[:3, 3]
    masses = rng.uniform(0.1, 1.0, count)
    body = sum(MassProperties(m, p) for m, p in zip(masses, points, strict=True))
    frames = [np.eye(3), body.principal_axes, rpy_matrix(rng.uniform(-3, 3, 3))]
    for frame in frames:
        bound = body.mass * hull.moment_bound(body.com, frame)
        moments = np.einsum("ji,jk,ki->i", frame, body.inertia, frame)
        assert (moments <= bound * (1 + 1e-12) + 1e-15).all()


def test_distance_outside_is_a_lower_bound_and_zero_inside():
    hull = Hull.of_part(Part.box((1.0, 1.0, 1.0)))
    assert hull.distance_outside((0.2, -0.3, 0.4)) == 0.0
    assert hull.distance_outside((0.8, 0.0, 0.0)) == pytest.approx(0.3)
    true = math.dist((0.8, 0.8, 0.8), (0.5, 0.5, 0.5))
    assert 0.9 * true <= hull.distance_outside((0.8, 0.8, 0.8)) <= true + 1e-12


def test_union_of_hulls_keeps_every_ball():
    left = Hull.of_part(Part.sphere(0.1, transform((-1.0, 0.0, 0.0))))
    right = Hull.of_part(Part.box((0.2, 0.2, 0.2), transform((1.0, 0.0, 0.0))))
    both = Hull.union([left, right])
    assert both.support([[1.0, 0, 0], [-1.0, 0, 0]]) == pytest.approx([1.1, 1.1])
    # the segment between them is inside the convex hull of the union
    assert both.distance_outside((0.0, 0.0, 0.0)) == 0.0


def test_hull_rejects_bad_shapes():
    with pytest.raises(ValueError, match=r"\(k, 3\)"):
        Hull(np.zeros((3, 2)))
    with pytest.raises(ValueError, match="radii"):
        Hull(np.zeros((2, 3)), np.zeros(3))


# --- tensor comparison --------------------------------------------------------------------------


def test_compare_tensors_of_a_scaled_tensor_gives_the_scale_on_every_axis():
    tensor = np.diag([1.0, 2.0, 3.0])
    result = compare_tensors(2.5 * tensor, tensor)
    assert result is not None
    np.testing.assert_allclose(result.ratios, [2.5, 2.5, 2.5])
    assert result.factor == pytest.approx(2.5)


def test_compare_tensors_sees_a_tensor_written_for_the_wrong_axes():
    """Same eigenvalues, other axes: a cylinder's tensor for z used on a cylinder along x."""
    mass, radius, length = 1.0, 0.02, 0.3
    along_z = np.diag([mass * (3 * radius**2 + length**2) / 12] * 2 + [mass * radius**2 / 2])
    rotation = rpy_matrix((0.0, math.pi / 2, 0.0))
    along_x = rotation @ along_z @ rotation.T
    result = compare_tensors(along_z, along_x)
    assert result is not None
    transverse, axial = along_z[0, 0], along_z[2, 2]
    np.testing.assert_allclose(
        sorted(result.ratios), sorted([axial / transverse, 1.0, transverse / axial])
    )
    worst = result.axes[result.worst]
    assert axis_name(worst) in ("x", "z")
    # the sorted principal moments alone would not notice
    np.testing.assert_allclose(np.linalg.eigvalsh(along_z), np.linalg.eigvalsh(along_x), rtol=1e-12)


def test_compare_tensors_is_invariant_under_a_common_rotation():
    rng = np.random.default_rng(7)
    a = np.diag([1.0, 2.0, 2.5])
    b = np.diag([1.5, 1.0, 2.0])
    rotation = rpy_matrix(rng.uniform(-3, 3, 3))
    plain = compare_tensors(a, b)
    turned = compare_tensors(rotation @ a @ rotation.T, rotation @ b @ rotation.T)
    assert plain is not None and turned is not None
    np.testing.assert_allclose(plain.ratios, turned.ratios, rtol=1e-10)


def test_compare_tensors_refuses_what_is_not_positive_definite():
    assert compare_tensors(np.diag([1.0, 1.0, -1.0]), np.eye(3)) is None
    assert compare_tensors(np.eye(3), np.zeros((3, 3))) is None
    assert compare_tensors(np.full((3, 3), np.nan), np.eye(3)) is None


def test_axis_name():
    assert axis_name((0.0, -1.0, 0.0)) == "y"
    assert axis_name((0.6, 0.8, 0.0)) is None


# --- moment excess ------------------------------------------------------------------------------


def test_moment_excess_reports_the_link_axis_beyond_the_bound():
    hull = Hull.of_part(Part.cylinder(0.05, 0.05))
    declared = MassProperties(1.0, np.zeros(3), np.diag([1.0, 1.0, 1.0]))
    excess = moment_excess(declared, hull)
    assert excess is not None and excess.ratio > 100
    assert axis_name(excess.axis) is not None
    # about a transverse axis the farthest points are the rim corners: r² + (l/2)²
    if axis_name(excess.axis) in "xy":
        assert excess.r_max == pytest.approx(math.hypot(0.05 * RIM, 0.025), rel=1e-9)


def test_moment_excess_of_the_uniform_tensor_is_within_the_bound():
    part = Part.box((0.4, 0.2, 0.1))
    uniform = part.mass_properties(mass=3.0)
    excess = moment_excess(uniform, Hull.of_part(part))
    assert excess is not None
    # a uniform box has a third of the corner bound about each axis: (b² + c²)/3 vs b² + c²
    assert excess.ratio == pytest.approx(1 / 3)


# --- solids, geometry and links ---------------------------------------------------------------


def test_solid_contains_for_primitives_and_meshes(tmp_path):
    analysis = robot(
        tmp_path,
        """<link name="a">
          <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
          <collision><origin xyz="1 0 0" rpy="0 1.5707963 0"/>
            <geometry><cylinder radius="0.1" length="0.4"/></geometry></collision>
          <collision><origin xyz="0 1 0"/><geometry><sphere radius="0.1"/></geometry></collision>
          <collision><origin xyz="0 0 1"/>
            <geometry><capsule radius="0.1" length="0.2"/></geometry></collision>
        </link>""",
    )
    box, cylinder, sphere, capsule = analysis.links[0].collision.solids
    assert box.contains((0.09, -0.09, 0.09)) and not box.contains((0.11, 0, 0))
    assert cylinder.contains((1.19, 0.0, 0.0)) and not cylinder.contains((1.0, 0.0, 0.11))
    assert sphere.contains((0.0, 1.0, 0.099)) and not sphere.contains((0.08, 1.08, 0.0))
    assert capsule.contains((0.0, 0.0, 1.19)) and not capsule.contains((0.09, 0.0, 1.19))
    assert box.contains((0.105, 0, 0), tol=0.01)


def test_link_bases_envelope_and_missing_meshes(tmp_path):
    analysis = robot(
        tmp_path,
        """<link name="a">
          <visual><geometry><box size="1 1 1"/></geometry></visual>
          <collision><geometry><sphere radius="0.1"/></geometry></collision>
        </link>
        <link name="b">
          <visual><geometry><mesh filename="missing.stl"/></geometry></visual>
          <collision><geometry><sphere radius="0.1"/></geometry></collision>
        </link>""",
    )
    a, b = analysis.links
    assert [g.kind for g in a.bases] == ["collision", "visual"]
    assert a.envelope is not None
    assert a.envelope.support([[1.0, 0.0, 0.0]])[0] == pytest.approx(0.5)
    assert [g.kind for g in b.bases] == ["collision"]
    assert b.envelope is None  # a partial envelope would understate what is possible


def test_mass_share_of_a_fixed_joint_group(tmp_path):
    analysis = robot(
        tmp_path,
        """<link name="base"/>
        <link name="arm"><inertial><mass value="3"/>
          <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
        <link name="tool"><inertial><mass value="1"/>
          <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>""",
        """<joint name="j" type="continuous"><parent link="base"/><child link="arm"/></joint>
        <joint name="f" type="fixed"><parent link="arm"/><child link="tool"/></joint>""",
    )
    assert analysis.by_name["arm"].mass_share == pytest.approx(0.75)
    assert analysis.by_name["tool"].mass_share == pytest.approx(0.25)
    assert analysis.by_name["base"].mass_share == 1.0
