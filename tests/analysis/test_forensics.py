"""
analysis.forensics: each slip constructed from closed forms here, undone by ``diagnose``; and
the tensors no slip explains (right ones, rounded ones, real-part deviations, random ones).
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from kit.moments import box_tensor, cylinder_moments

from inertia_kit.analysis.forensics import deviation, diagnose
from inertia_kit.analysis.links import Hull
from inertia_kit.physics.frames import rpy_matrix
from inertia_kit.physics.mass import MassProperties

EYE = np.eye(3)


def box_hull(x, y, z, centre=(0.0, 0.0, 0.0), rotation=EYE):
    signs = np.array(list(itertools.product((-0.5, 0.5), repeat=3)))
    return Hull(signs * [x, y, z] @ rotation.T + np.asarray(centre))


def parallel_axis(mass, d):
    d = np.asarray(d, dtype=float)
    return mass * (d @ d * np.eye(3) - np.outer(d, d))


def rounded(tensor, digits=4):
    """Each value rounded to ``digits`` significant digits, as CAD reports print them."""
    out = np.array(tensor, dtype=float)
    for index, value in np.ndenumerate(out):
        out[index] = float(f"{value:.{digits - 1}e}") if value else 0.0
    return 0.5 * (out + out.T)


def props(mass, tensor, com=(0.0, 0.0, 0.0)):
    return MassProperties(mass, com, tensor)


# --- the measure ----------------------------------------------------------------------------------


def test_deviation_is_relative_per_axis_with_a_floor():
    tensor = np.diag([1.0, 2.0, 3.0])
    assert deviation(tensor, tensor) == 0.0
    # twice the tensor: (I) / (I + 5 % of the largest) about the largest axis
    assert deviation(2 * tensor, tensor) == pytest.approx(3.0 / (3.0 + 0.15))
    # a rounding error of a large entry counts against the floor, not a thin axis's moment
    thin = np.diag([1.0, 1.0, 0.001])
    assert deviation(thin + np.diag([0, 0, 0.001]), thin) < 0.05


# --- nothing to explain ---------------------------------------------------------------------------

BOX = (0.4, 0.2, 0.1)
MASS = 2.0
VOLUME = 0.4 * 0.2 * 0.1


def box_case(tensor, com=(0.0, 0.0, 0.0), rotation=EYE, **kw):
    """``diagnose`` against the box (turned by ``rotation``), 2 kg, its hull and volume."""
    expected = props(MASS, box_tensor(MASS, BOX, rotation))
    kw.setdefault("hull", box_hull(*BOX, rotation=rotation))
    kw.setdefault("volume", VOLUME)
    kw.setdefault("points", [("the link origin", (0.0, 0.0, 0.0))])
    return diagnose(props(MASS, tensor, com), expected, **kw)


def test_the_right_tensor_is_not_diagnosed_exact_or_rounded():
    right = box_tensor(MASS, BOX)
    assert box_case(right) is None
    assert box_case(rounded(right, 3)) is None
    turned = rpy_matrix([0.4, 0.3, 0.5])
    expected = props(MASS, box_tensor(MASS, BOX, turned))
    assert diagnose(props(MASS, rounded(expected.inertia, 3)), expected) is None


def test_real_part_deviations_are_not_diagnosed():
    right = box_tensor(MASS, BOX)
    assert box_case(2 * right) is None  # a hollow-ish part
    assert box_case(right / 3) is None  # a dense core
    assert box_case(right * np.diag([3.0, 1.0, 1.0])) is None  # one moment 3 times
    assert box_case(right * np.diag([1.0, 1.5, 1.0])) is None


def test_a_rod_with_heavy_ends_is_not_a_shifted_point():
    """
    Mass at both ends of a rod adds the same δ to both transverse moments: the signature of a
    tensor about a point on the axis. Inside the rod's Bhatia–Davis bound it is not diagnosed.
    """
    mass, radius, length = 1.0, 0.02, 0.3
    rod = np.diag(cylinder_moments(mass, radius, length))
    ends = rod + np.diag([1.0, 1.0, 0.0]) * rod[0, 0]  # transverse ×2
    hull = Hull(np.array([[0, 0, -length / 2], [0, 0, length / 2]]), np.array([radius, radius]))
    assert diagnose(props(mass, ends), props(mass, rod), hull=hull) is None


def test_a_too_large_value_across_a_round_body_is_not_solved_for():
    """
    Across a cylinder the excess of a tensor about a point on its axis is (δ, δ, 0): a wrong
    transverse value written with the body's symmetry fits it whatever it is, even beyond what any
    mass inside allows. Only a named point explains it.
    """
    mass, radius, length = 2.0, 0.05, 0.2
    rod = np.diag(cylinder_moments(mass, radius, length))
    declared = rod + np.diag([1.0, 1.0, 0.0]) * 4 * rod[0, 0]  # ×5 across
    hull = Hull(np.array([[0, 0, -length / 2], [0, 0, length / 2]]), np.array([radius, radius]))
    assert diagnose(props(mass, declared), props(mass, rod), hull=hull) is None


def test_random_tensors_are_not_explained():
    """No slip explains tensors drawn at random around the box's (0.3–3 times, any axes)."""
    rng = np.random.default_rng(20240611)
    turned = rpy_matrix([0.4, 0.3, 0.5])
    expected = props(MASS, box_tensor(MASS, BOX, turned))
    hull = box_hull(*BOX, rotation=turned)
    scale = np.trace(expected.inertia) / 3
    found = []
    for _ in range(300):
        a, b = np.exp(rng.uniform(np.log(0.3), np.log(3.0), 2)) * scale
        c = rng.uniform(abs(a - b), a + b)  # the triangle inequality holds
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        tensor = q @ np.diag([a, b, c]) @ q.T
        points = [("the link origin", rng.uniform(-0.3, 0.3, 3))]
        found.append(
            diagnose(props(MASS, tensor), expected, points=points, hull=hull, volume=VOLUME)
        )
    assert [d.summary for d in found if d is not None] == []


# --- IN060 ---------------------------------------------------------------------------------------

DRUM = (157.633, 0.35, 0.4)  # the seed mrm arm's link_01


def test_tensor_about_the_link_origin():
    mass, radius, length = DRUM
    com = np.array([0.0, 0.0, length / 2])
    right = np.diag(cylinder_moments(mass, radius, length))
    declared = right + parallel_axis(mass, com)
    found = diagnose(
        props(mass, declared, com),
        props(mass, right, com),
        points=[("the link origin", (0.0, 0.0, 0.0))],
    )
    assert found is not None and found.code == "IN060"
    assert found.data["point"] == [0.0, 0.0, 0.0]
    assert "about the link origin (0, 0, 0), not about the COM (0, 0, 0.2)" in found.summary
    np.testing.assert_allclose(found.corrected.inertia, right, rtol=0, atol=1e-12)
    np.testing.assert_allclose(found.corrected.com, com)
    assert found.corrected.mass == mass
    assert right[0, 0] == pytest.approx(6.929, abs=1e-3)


def test_rounded_values_about_the_origin_are_still_recognised():
    """The mrm values: 13.235 and 9.655 (three decimals), the corrected ixx 13.235 - m d²."""
    mass, radius, length = DRUM
    com = (0.0, 0.0, 0.2)
    declared = np.diag([13.235, 13.235, 9.655])
    found = diagnose(
        props(mass, declared, com),
        props(mass, np.diag(cylinder_moments(mass, radius, length)), com),
        points=[("the link origin", (0.0, 0.0, 0.0))],
    )
    assert found is not None and found.code == "IN060"
    assert found.corrected.inertia[0, 0] == pytest.approx(13.235 - mass * 0.2**2)
    assert found.corrected.inertia[2, 2] == 9.655
    assert found.residual < 1e-3 and found.plain_residual > 0.5


def test_a_named_joint_origin_is_preferred_and_named():
    mass, radius, length = DRUM
    com = np.array([0.0, 0.0, 0.2])
    joint = np.array([0.0, 0.0, 0.5])
    right = np.diag(cylinder_moments(mass, radius, length))
    found = diagnose(
        props(mass, right + parallel_axis(mass, com - joint), com),
        props(mass, right, com),
        points=[("the link origin", (0, 0, 0)), ("the origin of joint `j2`", joint)],
        hull=Hull(np.array([[0, 0, 0], [0, 0, length]]), np.array([radius, radius])),
    )
    assert found is not None and found.code == "IN060"
    assert "about the origin of joint `j2` (0, 0, 0.5)" in found.summary


def test_a_point_outside_what_any_mass_allows_is_solved_for():
    """A CAD part origin at a corner of the box: the tensor about it, no named point."""
    corner = np.array(BOX) / 2
    declared = box_tensor(MASS, BOX) + parallel_axis(MASS, corner)
    found = box_case(declared, points=[])
    assert found is not None and found.code == "IN060"
    point = np.array(found.data["point"])
    assert np.allclose(point, corner) or np.allclose(point, -corner)
    assert found.data["point_name"] is None
    np.testing.assert_allclose(found.corrected.inertia, box_tensor(MASS, BOX), atol=1e-12)
    # without a hull nothing is solved for
    assert box_case(declared, points=[], hull=None) is None


# --- IN061 ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("rpy", [(0.4, 0.3, 0.5), (0.0, 0.0, 0.5236)])
def test_flipped_products(rpy):
    """All three products, or one (then it is also a half turn, but the sign slip is named)."""
    turned = rpy_matrix(rpy)
    right = box_tensor(MASS, BOX, turned)
    flipped = 2 * np.diag(np.diag(right)) - right
    found = box_case(flipped, rotation=turned)
    assert found is not None and found.code == "IN061"
    np.testing.assert_allclose(found.corrected.inertia, right, atol=1e-12)


def test_flipped_products_in_the_axes_of_inertial_rpy():
    """The written values are in the axes of <inertial><origin rpy>: their products flip."""
    axes = rpy_matrix([0.0, 0.0, 0.3])
    turned = rpy_matrix([0.4, 0.3, 0.5])
    right = box_tensor(MASS, BOX, turned)
    written = axes.T @ right @ axes
    declared = axes @ (2 * np.diag(np.diag(written)) - written) @ axes.T
    found = box_case(declared, rotation=turned, axes=axes)
    assert found is not None and found.code == "IN061"
    np.testing.assert_allclose(found.corrected.inertia, right, atol=1e-12)


# --- IN062 ---------------------------------------------------------------------------------------


def test_cylinder_formula_for_z_on_a_rod_along_x():
    mass, radius, length = 1.0, 0.02, 0.3
    along_z = np.diag(cylinder_moments(mass, radius, length))
    turn = rpy_matrix([0.0, np.pi / 2, 0.0])
    along_x = turn @ along_z @ turn.T
    label = "the collision cylinder's own axes"
    found = diagnose(props(mass, along_z), props(mass, along_x), rotations=[(label, turn)])
    assert found is not None and found.code == "IN062"
    assert label in found.summary
    assert "axis of least inertia along z" in found.summary and "along x" in found.summary
    np.testing.assert_allclose(found.corrected.inertia, along_x, atol=1e-15)
    np.testing.assert_allclose(rpy_matrix(found.data["rpy"]), turn, atol=1e-12)
    # without the shape's frame, an axis swap says the same
    found = diagnose(props(mass, along_z), props(mass, along_x))
    assert found is not None and found.code == "IN062"
    np.testing.assert_allclose(found.corrected.inertia, along_x, atol=1e-15)


def test_principal_moments_written_without_their_rotation():
    turned = rpy_matrix([0.3, 0.2, 0.1])
    principal = box_tensor(MASS, BOX)
    assert box_case(rounded(principal)) is None  # for the box as it lies, that tensor is right
    found = box_case(rounded(principal), rotation=turned)
    assert found is not None and found.code == "IN062"
    np.testing.assert_allclose(
        found.corrected.inertia, box_tensor(MASS, BOX, turned), rtol=0, atol=1e-5
    )


# --- IN063 ---------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("factor", "unit"),
    [(1e6, "kg·mm²"), (1e9, "g·mm²"), (1e4, "kg·cm²"), (1e3, "g·m²"), (1 / 2.9263965e-4, "lb·in²")],
)
def test_tensor_in_another_unit(factor, unit):
    right = box_tensor(MASS, BOX)
    found = box_case(rounded(right * factor))
    assert found is not None and found.code == "IN063"
    assert found.data["unit"] == unit and found.data["factor"] == pytest.approx(factor)
    np.testing.assert_allclose(found.corrected.inertia, right, rtol=1e-3)


def test_tensor_converted_the_wrong_way():
    right = box_tensor(MASS, BOX)
    found = box_case(right / 1e6)
    assert found is not None and found.code == "IN063"
    assert found.data["factor"] == pytest.approx(1e-6)
    np.testing.assert_allclose(found.corrected.inertia, right)


def test_mass_in_grams():
    """2000 (g) declared: 25 000 kg/m³ would be needed; the tensor is right for 2 kg."""
    right = box_tensor(MASS, BOX)
    declared = props(1000 * MASS, right)
    expected = props(1000 * MASS, box_tensor(1000 * MASS, BOX))
    found = diagnose(declared, expected, volume=VOLUME)
    assert found is not None and found.code == "IN063"
    assert found.data["mass_factor"] == 1000 and found.data["factor"] == 1.0
    assert found.corrected.mass == pytest.approx(MASS)
    np.testing.assert_allclose(found.corrected.inertia, right)
    assert "in grams" in found.summary


def test_no_unit_slip_when_the_geometry_scale_is_in_doubt_or_the_value_is_a_placeholder():
    right = box_tensor(MASS, BOX)
    # a mesh in millimetres: a density of 2.5e-6 kg/m³; the tensor is not to blame
    assert box_case(right * 1e6, volume=VOLUME * 1e9) is None
    # ixx = iyy = izz = 1 on a 1 cm sphere of 0.1 g: exactly 1e9 times 1e-9, a placeholder
    sphere = np.eye(3) * 0.4 * 1e-4 * 0.005**2
    volume = 4 / 3 * np.pi * 0.005**3
    expected = props(0.1, sphere * 1e3)
    assert diagnose(props(0.1, np.eye(3)), expected, volume=volume) is None


# --- IN064 ---------------------------------------------------------------------------------------


def values_to_tensor(ixx, ixy, ixz, iyy, iyz, izz):
    return np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])


def test_two_products_swapped():
    turned = rpy_matrix([0.0, 0.0, np.pi / 6])
    right = box_tensor(12.0, (0.4, 0.3, 0.2), turned)
    ixx, iyy, izz, ixy = right[0, 0], right[1, 1], right[2, 2], right[0, 1]
    declared = values_to_tensor(ixx, 0.0, ixy, iyy, 0.0, izz)
    found = diagnose(props(12.0, declared), props(12.0, right), volume=0.024)
    assert found is not None and found.code == "IN064"
    assert "ixy and ixz are swapped" in found.summary
    assert found.data["assignment"] == {"ixy": "ixz", "ixz": "ixy"}
    np.testing.assert_allclose(found.corrected.inertia, right)


def test_values_listed_moments_first_read_in_urdf_order():
    """MuJoCo's fullinertia order (Ixx Iyy Izz Ixy Ixz Iyz) pasted into ixx ixy ixz iyy iyz izz."""
    turned = rpy_matrix([0.4, 0.3, 0.5])
    right = box_tensor(MASS, BOX, turned)
    listed = [right[0, 0], right[1, 1], right[2, 2], right[0, 1], right[0, 2], right[1, 2]]
    declared = values_to_tensor(*listed)  # not even positive definite
    assert np.linalg.eigvalsh(declared)[0] < 0
    found = box_case(declared, rotation=turned)
    assert found is not None and found.code == "IN064"
    np.testing.assert_allclose(found.corrected.inertia, right)
