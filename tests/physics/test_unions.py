"""Solid unions against closed forms, an independent quadrature and invariants."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest
import trimesh
from kit.physics import from_second_moment

from inertia_kit.physics import primitives
from inertia_kit.physics.frames import transform
from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.polyhedra import integrate
from inertia_kit.physics.unions import Part, capsules, union


def errors(actual: MassProperties, expected: MassProperties) -> tuple[float, float, float]:
    """Relative errors of mass, COM (per radius of gyration) and inertia (per largest entry)."""
    size = math.sqrt(expected.principal_moments.max() / expected.mass)
    return (
        abs(actual.mass - expected.mass) / expected.mass,
        float(np.abs(actual.com - expected.com).max() / size),
        float(np.abs(actual.inertia - expected.inertia).max() / np.abs(expected.inertia).max()),
    )


def assert_close(actual: MassProperties, expected: MassProperties, rtol: float) -> None:
    worst = max(errors(actual, expected))
    assert worst < rtol, f"relative error {worst:.3g} ≥ {rtol:g}: {actual} vs {expected}"


def half_ellipsoid(radii: tuple[float, float, float], density: float) -> MassProperties:
    """The half z ≥ 0 of an ellipsoid centred on the origin: COM at 3c/8, ∫x² dm = m a²/5."""
    a, b, c = radii
    mass = density * 2.0 / 3.0 * math.pi * a * b * c
    com_z = 3.0 * c / 8.0
    about_face = mass / 5.0 * np.diag([a * a, b * b, c * c])
    central = about_face - mass * np.diag([0.0, 0.0, com_z * com_z])
    return from_second_moment(mass, [0.0, 0.0, com_z], central)


def cylinder_sphere_quadrature(
    radius: float, length: float, centre: np.ndarray, sphere_radius: float, n: int
) -> MassProperties:
    """
    Unit-density union of a cylinder along z (centred on the origin) and a sphere, integrated
    independently of any mesh: z exactly along each vertical column (union of two intervals),
    the midpoint rule over a polar grid about the cylinder axis whose rings split at its rim.
    """
    outer = max(radius, math.hypot(centre[0], centre[1]) + sphere_radius)
    edges = np.concatenate([np.linspace(0, radius, n + 1), np.linspace(radius, outer, n + 1)[1:]])
    rho = 0.5 * (edges[1:] + edges[:-1])
    phi = 2 * np.pi * (np.arange(4 * n) + 0.5) / (4 * n)
    r, p = np.meshgrid(rho, phi, indexing="ij")
    x, y = r * np.cos(p), r * np.sin(p)
    area = r * np.diff(edges)[:, None] * (2 * np.pi / (4 * n))
    in_cylinder = r <= radius
    s2 = sphere_radius**2 - (x - centre[0]) ** 2 - (y - centre[1]) ** 2
    in_sphere = s2 > 0
    s = np.sqrt(np.where(in_sphere, s2, 0.0))

    def interval(low, high, present):
        high = np.where(present, np.maximum(high, low), low)
        return np.stack([high - low, (high**2 - low**2) / 2, (high**3 - low**3) / 3]) * area

    low1, high1 = np.full_like(x, -length / 2), np.full_like(x, length / 2)
    low2, high2 = centre[2] - s, centre[2] + s
    both = in_cylinder & in_sphere
    z = (
        interval(low1, high1, in_cylinder)
        + interval(low2, high2, in_sphere)
        - interval(np.maximum(low1, low2), np.minimum(high1, high2), both)
    )
    volume = z[0].sum()
    first = np.array([(x * z[0]).sum(), (y * z[0]).sum(), z[1].sum()])
    xz, yz = (x * z[1]).sum(), (y * z[1]).sum()
    second = np.array(
        [
            [(x * x * z[0]).sum(), (x * y * z[0]).sum(), xz],
            [(x * y * z[0]).sum(), (y * y * z[0]).sum(), yz],
            [xz, yz, z[2].sum()],
        ]
    )
    com = first / volume
    return from_second_moment(volume, com, second - volume * np.outer(com, com))


# --- exact cases: boxes tessellate exactly ------------------------------------------------


def test_identical_boxes_count_once():
    pose = transform([0.1, -0.2, 0.3], [0.4, -0.5, 0.6])
    result = union([Part.box([1.0, 0.4, 0.2], pose), Part.box([1.0, 0.4, 0.2], pose)], density=7.0)
    expected = primitives.box([1.0, 0.4, 0.2], density=7.0).transformed(pose)
    assert_close(result.mass_properties, expected, 1e-9)
    assert result.volume == pytest.approx(0.08, rel=1e-12)
    assert result.overlap_volume == pytest.approx(0.08, rel=1e-9)
    assert not result.exact


def test_boxes_overlapping_by_half():
    a = Part.box([1.0, 0.4, 0.2])
    b = Part.box([1.0, 0.4, 0.2], transform([0.5, 0.0, 0.0]))
    result = union([a, b], density=1000.0)
    expected = primitives.box([1.5, 0.4, 0.2], density=1000.0).placed([0.25, 0.0, 0.0])
    assert_close(result.mass_properties, expected, 1e-9)
    assert result.overlap_volume == pytest.approx(0.5 * 0.4 * 0.2, rel=1e-12)
    assert result.parts_volume == pytest.approx(2 * 0.08, rel=1e-15)
    assert result.volume == pytest.approx(1.5 * 0.4 * 0.2, rel=1e-12)


def test_three_boxes_in_a_row_overlapping_by_half():
    """Three parts meeting in pairs (the union and each part tessellated, not one
    intersection): a box 2 long, each half-overlap counted once."""
    parts = [Part.box([1.0, 0.4, 0.2], transform([0.5 * k, 0.0, 0.0])) for k in range(3)]
    result = union(parts, density=1000.0)
    expected = primitives.box([2.0, 0.4, 0.2], density=1000.0).placed([0.5, 0.0, 0.0])
    assert_close(result.mass_properties, expected, 1e-9)
    assert result.overlap_volume == pytest.approx(2 * 0.5 * 0.4 * 0.2, rel=1e-12)


def test_rotated_crossed_bars_and_rigid_motion():
    # a plus sign: two bars, one yawed 90°, sharing a central cube counted once
    bar = (1.0, 0.2, 0.2)
    x_bar, y_bar = Part.box(bar), Part.box(bar, transform(rpy=[0.0, 0.0, math.pi / 2]))
    cube = primitives.box([0.2, 0.2, 0.2], density=1.0)
    expected = (
        primitives.box(bar, density=1.0)
        + primitives.box(bar, density=1.0).placed(rpy=[0, 0, math.pi / 2])
        - cube
    )
    motion = transform([3.0, -1.0, 2.0], [0.3, -1.1, 2.5])
    moved = [x_bar.transformed(motion), y_bar.transformed(motion)]
    assert_close(union([x_bar, y_bar], density=1.0).mass_properties, expected, 1e-9)
    assert_close(union(moved, density=1.0).mass_properties, expected.transformed(motion), 1e-9)
    assert union(moved, density=1.0).overlap_volume == pytest.approx(0.008, rel=1e-9)


def test_disjoint_parts_are_the_exact_sum():
    parts = [
        Part.box([0.2, 0.1, 0.3], transform([0.0, 0.0, 0.0], [0.1, 0.2, 0.3])),
        Part.cylinder(0.05, 0.4, transform([1.0, 0.0, 0.0], [1.0, 0.0, 0.0])),
        Part.sphere(0.1, transform([0.0, 1.0, 0.0])),
        Part.capsule(0.04, 0.2, transform([0.0, 0.0, 1.0], [0.0, 0.5, 0.0])),
        Part.ellipsoid([0.1, 0.2, 0.05], transform([-1.0, 0.0, 0.0], [0.0, 0.0, 0.7])),
    ]
    result = union(parts, density=2700.0)
    expected = sum(part.mass_properties(density=2700.0) for part in parts)
    assert_close(result.mass_properties, expected, 1e-12)
    assert result.exact
    assert result.overlap_volume == 0.0
    assert result.volume == pytest.approx(sum(part.volume for part in parts), rel=1e-15)


def test_bounding_boxes_overlap_but_solids_do_not():
    # spheres 2.1 r apart on a diagonal: their boxes overlap, the spheres do not
    offset = 2.1 * 0.1 / math.sqrt(3.0) * np.ones(3)
    parts = [Part.sphere(0.1), Part.sphere(0.1, transform(offset))]
    result = union(parts, density=1.0)
    expected = primitives.sphere(0.1, density=1.0) + primitives.sphere(0.1, density=1.0).placed(
        offset
    )
    assert result.exact
    assert_close(result.mass_properties, expected, 1e-12)


def test_single_part_is_exact():
    pose = transform([0.1, 0.2, 0.3], [0.3, 0.2, 0.1])
    result = union([Part.capsule(0.05, 0.3, pose)], mass=2.0)
    assert result.exact
    assert_close(
        result.mass_properties, primitives.capsule(0.05, 0.3, mass=2.0).transformed(pose), 1e-14
    )


# --- curved parts: within 0.1 % by the specification, measured far below -----------------


def test_sphere_inside_box_is_the_box():
    result = union(
        [Part.box([1.0, 1.0, 1.0]), Part.sphere(0.3, transform([0.1, 0, 0]))], density=1.0
    )
    assert_close(result.mass_properties, primitives.box([1.0, 1.0, 1.0], density=1.0), 1e-5)
    assert result.overlap_volume == pytest.approx(primitives.sphere_volume(0.3), rel=1e-9)


def test_coaxial_cylinders_are_one_cylinder():
    pose = transform([0.5, 0.2, -0.1], [0.0, math.pi / 2, 0.3])
    parts = [
        Part.cylinder(0.1, 0.4, pose @ transform([0, 0, -0.1])),
        Part.cylinder(0.1, 0.4, pose @ transform([0, 0, 0.1])),
    ]
    result = union(parts, density=1.0)
    expected = primitives.cylinder(0.1, 0.6, density=1.0).transformed(pose)
    assert_close(result.mass_properties, expected, 1e-6)
    assert result.overlap_volume == pytest.approx(primitives.cylinder_volume(0.1, 0.2), rel=1e-9)


def test_cylinder_and_end_spheres_are_a_capsule():
    parts = [
        Part.cylinder(0.05, 0.3),
        Part.sphere(0.05, transform([0, 0, 0.15])),
        Part.sphere(0.05, transform([0, 0, -0.15])),
    ]
    result = union(parts, mass=1.5)
    assert_close(result.mass_properties, primitives.capsule(0.05, 0.3, mass=1.5), 1e-4)
    capsule_volume = math.pi * 0.05**2 * 0.3 + 4 / 3 * math.pi * 0.05**3  # cylinder + sphere
    assert result.volume == pytest.approx(capsule_volume, rel=1e-9)


def test_sphere_on_cylinder_end_adds_a_hemisphere():
    result = union(
        [Part.cylinder(0.1, 0.4), Part.sphere(0.08, transform([0, 0, 0.2]))], density=1.0
    )
    expected = primitives.cylinder(0.1, 0.4, density=1.0) + half_ellipsoid(
        (0.08, 0.08, 0.08), 1.0
    ).placed([0, 0, 0.2])
    assert_close(result.mass_properties, expected, 1e-4)
    assert result.overlap_volume == pytest.approx(primitives.sphere_volume(0.08) / 2, rel=1e-9)


def test_quadrature_reproduces_the_hemisphere_closed_form():
    estimate = cylinder_sphere_quadrature(0.1, 0.4, np.array([0, 0, 0.2]), 0.08, n=300)
    expected = primitives.cylinder(0.1, 0.4, density=1.0) + half_ellipsoid(
        (0.08, 0.08, 0.08), 1.0
    ).placed([0, 0, 0.2])
    assert_close(estimate, expected, 2e-5)


def test_sphere_off_axis_on_cylinder_matches_quadrature():
    # the sphere pokes out of the cylinder's side: a lens-shaped overlap with no closed form;
    # the quadrature is good to ~1e-5 here (checked on the hemisphere case above)
    centre = np.array([0.07, 0.02, 0.1])
    estimate = cylinder_sphere_quadrature(0.1, 0.4, centre, 0.08, n=300)
    result = union([Part.cylinder(0.1, 0.4), Part.sphere(0.08, transform(centre))], density=1.0)
    assert_close(result.mass_properties, estimate, 1e-4)
    assert not result.exact
    assert 0 < result.overlap_volume < primitives.sphere_volume(0.08)


def test_ellipsoid_half_out_of_a_box():
    # centred on the top face and yawed: the box plus the upper half-ellipsoid
    radii = (0.2, 0.3, 0.4)
    pose = transform([0.0, 0.0, 0.5], [0.0, 0.0, 0.4])
    result = union([Part.box([1.0, 1.0, 1.0]), Part.ellipsoid(radii, pose)], density=1.0)
    expected = primitives.box([1.0, 1.0, 1.0], density=1.0) + half_ellipsoid(
        radii, 1.0
    ).transformed(pose)
    assert_close(result.mass_properties, expected, 1e-4)


def test_rigid_motion_commutes_with_union():
    parts = [
        Part.cylinder(0.1, 0.4),
        Part.sphere(0.08, transform([0.07, 0.02, 0.1])),
        Part.capsule(0.03, 0.3, transform([0.0, 0.1, 0.2], [1.2, 0.0, 0.3])),
    ]
    motion = transform([1.0, -2.0, 0.5], [0.7, 0.4, -1.3])
    here = union(parts, density=1.0)
    moved = union([part.transformed(motion) for part in parts], density=1.0)
    assert_close(moved.mass_properties, here.mass_properties.transformed(motion), 1e-9)
    assert moved.overlap_volume == pytest.approx(here.overlap_volume, rel=1e-9)


@pytest.mark.parametrize(
    "part",
    [
        Part.box([0.3, 0.2, 0.1]),
        Part.cylinder(0.1, 0.4),
        Part.sphere(0.2),
        Part.capsule(0.05, 0.3),
        Part.ellipsoid([0.1, 0.2, 0.3], transform([1, 2, 3], [0.1, 0.2, 0.3])),
    ],
    ids=lambda part: part.kind,
)
@pytest.mark.parametrize("segments", [8, 13, 96])
def test_tessellations_are_closed_and_keep_the_volume(part, segments):
    vertices, faces = part.tessellation(segments)
    # closed and consistently wound: every directed edge meets its reverse exactly once
    edges = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    assert sorted(map(tuple, edges)) == sorted(map(tuple, edges[:, ::-1]))
    assert len(set(map(tuple, edges))) == len(edges)
    moments = integrate(vertices[faces]).moments
    assert moments.volume == pytest.approx(part.volume, rel=1e-12)
    assert np.allclose(moments.centroid, part.pose[:3, 3], atol=1e-12)


# --- meshes -------------------------------------------------------------------------------


def test_mesh_parts_unite_like_boxes():
    block = trimesh.creation.box(extents=[1.0, 0.4, 0.2])
    indexed = Part.mesh(block.vertices, block.faces, transform([0.5, 0, 0]))
    soup = Part.mesh(block.triangles, pose=transform([0.5, 0, 0]))
    expected = primitives.box([1.5, 0.4, 0.2], density=1.0).placed([0.25, 0.0, 0.0])
    for part in (indexed, soup):
        assert part.volume == pytest.approx(0.08, rel=1e-12)
        result = union([Part.box([1.0, 0.4, 0.2]), part], density=1.0)
        assert_close(result.mass_properties, expected, 1e-9)


def test_mesh_with_a_vertex_per_triangle_corner():
    # STL-like: every triangle has its own three vertices; equal coordinates are shared
    block = trimesh.creation.box(extents=[1.0, 0.4, 0.2])
    part = Part.mesh(block.triangles.reshape(-1, 3), np.arange(36).reshape(-1, 3))
    result = union([part, Part.box([1.0, 0.4, 0.2], transform([0.5, 0, 0]))], density=1.0)
    expected = primitives.box([1.5, 0.4, 0.2], density=1.0).placed([0.25, 0.0, 0.0])
    assert_close(result.mass_properties, expected, 1e-9)


def test_mesh_with_near_duplicate_vertices_is_merged():
    triangles = trimesh.creation.box(extents=[1.0, 1.0, 1.0]).triangles.copy()
    triangles[0, 0] += 1e-13  # one copy of a shared corner no longer matches bit for bit
    part = Part.mesh(triangles)
    assert part.volume == pytest.approx(1.0, rel=1e-9)


def test_open_mesh_is_rejected():
    block = trimesh.creation.box(extents=[1.0, 1.0, 1.0])
    with pytest.raises(ValueError, match="not a closed"):
        Part.mesh(block.vertices, block.faces[1:])


def test_inverted_mesh_is_rejected():
    block = trimesh.creation.box(extents=[1.0, 1.0, 1.0])
    with pytest.raises(ValueError, match="inside-out"):
        Part.mesh(block.vertices, block.faces[:, ::-1])


# --- density, mass and errors -------------------------------------------------------------


def test_mass_is_spread_over_the_union():
    parts = [Part.box([1.0, 0.4, 0.2]), Part.box([1.0, 0.4, 0.2], transform([0.5, 0, 0]))]
    by_mass = union(parts, mass=3.0).mass_properties
    by_density = union(parts, density=3.0 / 0.12).mass_properties
    expected = primitives.box([1.5, 0.4, 0.2], mass=3.0).placed([0.25, 0, 0])
    assert by_mass.mass == pytest.approx(3.0, rel=1e-15)
    assert_close(by_mass, expected, 1e-9)
    assert_close(by_density, expected, 1e-9)


@pytest.mark.parametrize(
    ("build", "message"),
    [
        (lambda: Part.box([1.0, 0.0, 1.0]), "size"),
        (lambda: Part.box([1.0, 1.0]), "size"),
        (lambda: Part.cylinder(-0.1, 1.0), "radius"),
        (lambda: Part.sphere(float("nan")), "radius"),
        (lambda: Part.capsule(0.1, 0.0), "length"),
        (lambda: Part.ellipsoid([0.1, 0.2, -0.3]), "radii"),
        (lambda: Part.sphere(0.1, pose=np.diag([2.0, 1.0, 1.0, 1.0])), "rotation"),
        (lambda: Part.mesh(np.zeros((4, 3)), np.array([[0, 1, 9]])), "out of range"),
        (lambda: Part.mesh(np.zeros((4, 2))), r"\(n, 3, 3\)"),
        (lambda: Part.mesh(np.zeros((0, 3, 3))), "no triangles"),
        (lambda: union([]), "no parts"),
        (lambda: union([Part.sphere(0.1)]), "exactly one"),
        (lambda: union([Part.sphere(0.1)], density=1.0, mass=1.0), "exactly one"),
        (lambda: union([Part.sphere(0.1)], density=-1.0), "density"),
        (lambda: union([Part.sphere(0.1)], density=1.0, segments=4), "segments"),
    ],
)
def test_invalid_input_raises_value_error(build, message):
    with pytest.raises(ValueError, match=message):
        build()


def test_union_takes_parts_only():
    with pytest.raises(TypeError, match="MassProperties"):
        union([primitives.sphere(0.1, density=1.0)], density=1.0)  # type: ignore[list-item]


def test_import_does_not_load_manifold3d():
    code = "import sys, inertia_kit.physics.unions; assert 'manifold3d' not in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True)


def _capsule_parts(radius, length, pose, off=0.0):
    """A cylinder and a sphere of its radius on each end cap (the second moved by ``off``)."""
    axis = pose[:3, 2]
    centre = pose[:3, 3]
    end = [np.eye(4), np.eye(4)]
    end[0][:3, 3] = centre + 0.5 * length * axis
    end[1][:3, 3] = centre - (0.5 * length + off) * axis
    return [
        Part.sphere(radius, end[0]),
        Part.cylinder(radius, length, pose),
        Part.sphere(radius, end[1]),
    ]


def test_a_cylinder_with_a_sphere_on_each_end_is_a_capsule_exactly(monkeypatch):
    import inertia_kit.physics.unions as unions

    pose = transform((0.1, -0.2, 0.3), (0.4, -0.7, 1.1))
    monkeypatch.setattr(unions, "_overlap_corrected", lambda *a: pytest.fail("tessellated"))
    result = union(_capsule_parts(0.06, 0.11, pose), density=1000.0)
    expected = primitives.capsule(0.06, 0.11, density=1000.0).transformed(pose)
    assert result.exact
    assert result.mass_properties.mass == pytest.approx(expected.mass, rel=1e-14)
    np.testing.assert_allclose(result.mass_properties.com, expected.com, rtol=1e-13)
    np.testing.assert_allclose(result.mass_properties.inertia, expected.inertia, rtol=1e-12)
    # what a plain sum counts twice: a hemisphere inside each end of the cylinder
    assert result.overlap_volume == pytest.approx(4 / 3 * math.pi * 0.06**3, rel=1e-12)


def test_a_sphere_off_the_end_cap_is_no_capsule_and_is_united_by_tessellation():
    pose = transform((0.0, 0.0, 0.0), (0.0, 0.5, 0.0))
    parts = _capsule_parts(0.05, 0.2, pose, off=0.01)
    assert [p.kind for p in capsules(tuple(parts))] == ["sphere", "cylinder", "sphere"]
    result = union(parts, density=1.0)
    assert not result.exact
    exact = primitives.capsule(0.05, 0.2, density=1.0).mass
    assert exact < result.mass_properties.mass < exact + 4 / 3 * math.pi * 0.05**3


def test_a_capsule_among_other_parts_still_unites_with_them():
    pose = np.eye(4)
    box = Part.box((0.3, 0.3, 0.05), transform((0.0, 0.0, 0.15), (0, 0, 0)))
    parts = (box, *_capsule_parts(0.05, 0.2, pose))
    assert [p.kind for p in capsules(parts)] == ["box", "capsule"]
    result = union(parts, density=1.0)
    assert not result.exact  # the box meets the capsule's upper end
    alone = primitives.capsule(0.05, 0.2, density=1.0).mass + 0.3 * 0.3 * 0.05
    assert result.mass_properties.mass < alone
