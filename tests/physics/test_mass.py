"""MassProperties against closed forms and invariants: rotation, parallel axis, additivity."""

import numpy as np
import pytest
from kit.physics import from_second_moment

from inertia_kit.physics.frames import rpy_matrix, transform
from inertia_kit.physics.mass import MassProperties, shift_tensor
from inertia_kit.physics.primitives import box, cylinder, sphere

RNG = np.random.default_rng(20261121)


def random_rotation() -> np.ndarray:
    q, r = np.linalg.qr(RNG.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


def random_body() -> MassProperties:
    size = RNG.uniform(0.1, 2.0, 3)
    return box(size, mass=RNG.uniform(0.5, 10)).transformed(
        pose(random_rotation(), RNG.normal(size=3))
    )


def pose(rotation, translation) -> np.ndarray:
    m = np.eye(4)
    m[:3, :3] = rotation
    m[:3, 3] = translation
    return m


def test_mrm_link_01_about_com_and_about_its_base():
    # seed "mrm" arm: cylinder r = 0.35 m, l = 0.4 m at 1024 kg/m³; the CAD export gives the
    # tensor about the centre of the cylinder's base, 0.2 m below its COM
    link = cylinder(0.35, 0.4, density=1024)
    assert link.mass == pytest.approx(157.633, abs=5e-4)
    assert link.inertia[2, 2] == pytest.approx(9.655, abs=5e-4)
    assert link.inertia[0, 0] == pytest.approx(6.929, abs=5e-4)
    about_base = link.inertia_about((0, 0, -0.2))
    assert about_base[0, 0] == pytest.approx(13.235, abs=5e-4)
    assert about_base[1, 1] == pytest.approx(13.235, abs=5e-4)
    assert about_base[2, 2] == pytest.approx(9.655, abs=5e-4)


def test_mrm_base_box():
    base = box((1, 1, 1), density=1024)
    assert base.mass == 1024
    np.testing.assert_allclose(np.diag(base.inertia), 1024 / 6, rtol=1e-12)
    assert base.inertia[0, 0] == pytest.approx(170.667, abs=5e-4)


def test_rotation_leaves_principal_moments_unchanged():
    body = box((0.3, 0.5, 1.1), mass=2.0)
    for _ in range(20):
        rotated = body.transformed(pose(random_rotation(), RNG.normal(size=3)))
        np.testing.assert_allclose(rotated.principal_moments, body.principal_moments, rtol=1e-12)
        assert rotated.mass == body.mass


def test_rotation_by_urdf_rpy_is_r_i_rt():
    body = cylinder(0.02, 0.3, mass=1.0)
    # the seed simple arm: a z-axis cylinder turned along x by pitch pi/2
    along_x = body.placed(xyz=(0.15, 0, 0), rpy=(0, np.pi / 2, 0))
    np.testing.assert_allclose(
        np.diag(along_x.inertia), np.diag(body.inertia)[[2, 1, 0]], atol=1e-15
    )
    np.testing.assert_allclose(along_x.com, (0.15, 0, 0), atol=1e-15)


def test_box_about_its_corner_matches_closed_form():
    # a box x×y×z about a corner, in its edge axes: ixx = m(y² + z²)/3, ixy = -m x y / 4
    x, y, z, m = 0.2, 0.5, 0.9, 3.0
    corner = box((x, y, z), mass=m).inertia_about((-x / 2, -y / 2, -z / 2))
    expected = np.array(
        [
            [m * (y * y + z * z) / 3, -m * x * y / 4, -m * x * z / 4],
            [-m * x * y / 4, m * (x * x + z * z) / 3, -m * y * z / 4],
            [-m * x * z / 4, -m * y * z / 4, m * (x * x + y * y) / 3],
        ]
    )
    np.testing.assert_allclose(corner, expected, rtol=1e-12)


def test_ixy_sign_convention_for_a_body_leaning_along_plus_x_plus_y():
    # DESIGN.md: ixy = -∫xy dm, so point masses on the line y = x give a negative ixy
    pair = MassProperties(1.0, (1, 1, 0)) + MassProperties(1.0, (-1, -1, 0))
    assert pair.inertia[0, 1] < 0
    assert pair.inertia[0, 1] == pytest.approx(-2.0)


def test_parallel_axis_theorem():
    body = random_body()
    point = RNG.normal(size=3)
    d = body.com - point
    expected = body.inertia + body.mass * (d @ d * np.eye(3) - np.outer(d, d))
    np.testing.assert_allclose(body.inertia_about(point), expected, rtol=1e-12)
    np.testing.assert_allclose(body.inertia_about(body.com), body.inertia, rtol=1e-12)


def test_box_split_in_two_and_recombined_equals_the_whole():
    whole = box((1.0, 0.4, 0.2), density=2700)
    left = box((0.3, 0.4, 0.2), density=2700).placed(xyz=(-0.35, 0, 0))
    right = box((0.7, 0.4, 0.2), density=2700).placed(xyz=(0.15, 0, 0))
    assert (left + right).isclose(whole, rtol=1e-12)
    assert sum([left, right]).isclose(whole, rtol=1e-12)


def test_eight_octants_recombine_to_a_rotated_box():
    size = np.array([0.6, 0.4, 0.2])
    rotation = random_rotation()
    octants = [
        box(size / 2, density=7850).transformed(pose(rotation, rotation @ (np.array(s) * size / 4)))
        for s in np.ndindex(2, 2, 2)
        for s in [tuple(2 * np.array(s) - 1)]
    ]
    whole = box(size, density=7850).transformed(pose(rotation, np.zeros(3)))
    assert sum(octants).isclose(whole, rtol=1e-12)


def test_subtraction_undoes_addition():
    a, b = random_body(), random_body()
    assert ((a + b) - b).isclose(a, rtol=1e-9)


def test_subtracting_everything_is_an_error():
    a = random_body()
    with pytest.raises(ValueError, match="cannot remove"):
        a - a.with_mass(a.mass * 2)


def test_transforms_compose():
    body = random_body()
    t1 = transform(RNG.normal(size=3), RNG.normal(size=3))
    t2 = transform(RNG.normal(size=3), RNG.normal(size=3))
    assert body.transformed(t1).transformed(t2).isclose(body.transformed(t2 @ t1), rtol=1e-12)


def test_inertia_at_a_frame_is_about_its_origin_in_its_axes():
    body = random_body()
    rotation, origin = random_rotation(), RNG.normal(size=3)
    frame = pose(rotation, origin)
    # the same body expressed in that frame, then taken about the frame's origin
    inverse = np.linalg.inv(frame)
    expected = body.transformed(inverse).inertia_about((0, 0, 0))
    np.testing.assert_allclose(body.inertia_at(frame), expected, rtol=1e-10, atol=1e-12)


def test_with_mass_scales_the_tensor():
    body = cylinder(0.05, 0.3, density=1000)
    measured = body.with_mass(2.0)
    np.testing.assert_allclose(measured.inertia, cylinder(0.05, 0.3, mass=2.0).inertia, rtol=1e-12)
    np.testing.assert_array_equal(measured.com, body.com)


def test_principal_axes_diagonalise_and_are_right_handed():
    body = random_body()
    axes = body.principal_axes
    assert np.linalg.det(axes) == pytest.approx(1.0)
    np.testing.assert_allclose(
        axes.T @ body.inertia @ axes,
        np.diag(body.principal_moments),
        atol=1e-12 * body.principal_moments.max(),
    )


def test_radii_of_gyration():
    body = sphere(0.5, mass=3.0)
    np.testing.assert_allclose(body.radii_of_gyration, np.sqrt(0.4) * 0.5, rtol=1e-12)


def test_from_urdf_rotates_the_written_axes():
    declared = MassProperties.from_urdf(
        2.0, 0.1, 0, 0, 0.2, 0, 0.3, xyz=(1, 2, 3), rpy=(0, 0, np.pi / 2)
    )
    np.testing.assert_allclose(declared.com, (1, 2, 3))
    np.testing.assert_allclose(np.diag(declared.inertia), (0.2, 0.1, 0.3), atol=1e-15)
    r = rpy_matrix((0.3, -0.2, 1.1))
    rotated = MassProperties.from_urdf(1.0, 1, 0.1, 0.05, 2, -0.02, 2.5, rpy=(0.3, -0.2, 1.1))
    tensor = np.array([[1, 0.1, 0.05], [0.1, 2, -0.02], [0.05, -0.02, 2.5]])
    np.testing.assert_allclose(rotated.inertia, r @ tensor @ r.T)


def test_values_are_immutable():
    body = box((1, 1, 1), mass=1)
    with pytest.raises(ValueError):
        body.com[0] = 1.0
    with pytest.raises(AttributeError):
        body.mass = 2.0  # type: ignore[misc]


def test_shape_errors_quote_the_shape():
    with pytest.raises(ValueError, match=r"inertia must be \(3, 3\), got shape \(2, 2\)"):
        MassProperties(1.0, (0, 0, 0), np.eye(2))
    with pytest.raises(ValueError, match=r"com must be \(3,\)"):
        MassProperties(1.0, (0, 0), np.eye(3))


def test_second_moment_round_trip():
    body = random_body()
    assert from_second_moment(body.mass, body.com, body.second_moment).isclose(body, rtol=1e-12)


def test_shift_tensor_of_a_point_mass():
    np.testing.assert_allclose(shift_tensor(2.0, (0, 0, 3)), np.diag([18.0, 18.0, 0.0]))


class TestValidity:
    def test_a_primitive_is_valid(self):
        assert cylinder(0.1, 0.2, mass=1).validity().ok
        assert str(box((1, 2, 3), mass=1).validity()) == "valid"

    def test_a_thin_disk_sits_on_the_triangle_inequality_and_passes(self):
        # A + B = C exactly for a flat disk; rounding must not make it fail
        r, m = 0.3, 1.7
        disk = MassProperties(m, (0, 0, 0), np.diag([m * r * r / 4, m * r * r / 4, m * r * r / 2]))
        assert disk.transformed(pose(random_rotation(), np.zeros(3))).validity().ok

    def test_non_finite(self):
        v = MassProperties(1.0, (0, 0, 0), np.diag([1, np.nan, 1])).validity()
        assert v.kinds() == {"non-finite"}
        assert "inertia" in str(v)

    def test_non_positive_mass(self):
        v = MassProperties(0.0, (0, 0, 0), np.eye(3)).validity()
        assert "non-positive-mass" in v.kinds()

    def test_zero_tensor_is_not_positive_definite(self):
        v = MassProperties(1.0, (0, 0, 0), np.zeros((3, 3))).validity()
        assert v.kinds() == {"not-positive-definite"}

    def test_negative_product_making_it_indefinite(self):
        v = MassProperties.from_urdf(1.0, 1, 2, 0, 1, 0, 1).validity()
        assert v.kinds() == {"not-positive-definite"}
        assert "not all positive" in str(v)

    def test_triangle_inequality_says_why(self):
        v = MassProperties(1.0, (0, 0, 0), np.diag([0.1, 0.2, 0.5])).validity()
        assert v.kinds() == {"triangle-inequality"}
        assert "0.1 + 0.2 = 0.3 < 0.5" in str(v)

    def test_triangle_inequality_tolerance(self):
        barely = MassProperties(1.0, (0, 0, 0), np.diag([0.1, 0.2, 0.30003]))
        assert not barely.validity().ok
        assert barely.validity(rtol=1e-3).ok

    def test_asymmetric(self):
        tensor = np.eye(3)
        tensor[0, 1] = 0.1
        assert "asymmetric" in MassProperties(1.0, (0, 0, 0), tensor).validity().kinds()
