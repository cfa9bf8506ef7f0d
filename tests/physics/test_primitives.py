"""Primitives against their closed forms (1e-12) and against independent constructions."""

import math

import numpy as np
import pytest

from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.polyhedra import integrate
from inertia_kit.physics.primitives import box, capsule, cylinder, ellipsoid, sphere

trimesh = pytest.importorskip("trimesh")


def test_box_closed_form():
    x, y, z, rho = 0.3, 0.5, 0.7, 2700.0
    body = box((x, y, z), density=rho)
    m = rho * x * y * z
    assert body.mass == pytest.approx(m, rel=1e-12)
    np.testing.assert_allclose(
        np.diag(body.inertia),
        [m * (y * y + z * z) / 12, m * (x * x + z * z) / 12, m * (x * x + y * y) / 12],
        rtol=1e-12,
    )
    np.testing.assert_array_equal(body.com, 0)


def test_cylinder_seed_formulas():
    r, length, m = 0.05, 0.3, 2.0
    body = cylinder(r, length, mass=m)
    np.testing.assert_allclose(
        np.diag(body.inertia), [m * (3 * r * r + length**2) / 12] * 2 + [m * r * r / 2], rtol=1e-12
    )
    assert cylinder(r, length, density=1000).mass == pytest.approx(
        1000 * math.pi * r * r * length, rel=1e-12
    )


def test_sphere_closed_form():
    body = sphere(0.2, density=1000)
    m = 1000 * 4 / 3 * math.pi * 0.2**3
    assert body.mass == pytest.approx(m, rel=1e-12)
    np.testing.assert_allclose(np.diag(body.inertia), 0.4 * m * 0.04, rtol=1e-12)


def test_capsule_from_two_hemispheres_moved_apart():
    # independent construction: a cylinder plus a sphere cut in two, each half moved out by
    # length/2 (parallel axis on each hemisphere, whose COM sits 3r/8 from its flat face)
    r, h, rho = 0.1, 0.4, 1000.0
    cap = capsule(r, h, density=rho)
    cyl, sph = cylinder(r, h, density=rho), sphere(r, density=rho)
    assert cap.mass == pytest.approx(cyl.mass + sph.mass, rel=1e-12)
    side = cyl.inertia[0, 0] + sph.inertia[0, 0] + sph.mass * (h * h / 4 + 3 * h * r / 8)
    np.testing.assert_allclose(
        np.diag(cap.inertia), [side, side, cyl.inertia[2, 2] + sph.inertia[2, 2]], rtol=1e-12
    )


def test_capsule_matches_a_fine_mesh():
    r, h = 0.1, 0.4
    mesh = trimesh.creation.capsule(height=h, radius=r, count=[128, 128])
    assert mesh.is_watertight
    from_mesh = integrate(mesh.triangles).moments.mass_properties(density=1.0)
    exact = capsule(r, h, density=1.0)
    np.testing.assert_allclose(from_mesh.mass, exact.mass, rtol=2e-3)
    np.testing.assert_allclose(np.diag(from_mesh.inertia), np.diag(exact.inertia), rtol=4e-3)


def test_ellipsoid_with_equal_radii_is_a_sphere():
    assert ellipsoid((0.3, 0.3, 0.3), mass=2.0).isclose(sphere(0.3, mass=2.0), rtol=1e-12)


def test_ellipsoid_matches_a_scaled_icosphere():
    radii = np.array([0.1, 0.2, 0.35])
    sphere_mesh = trimesh.creation.icosphere(subdivisions=6)
    moments = integrate(sphere_mesh.triangles).moments.scaled(radii)
    from_mesh = moments.mass_properties(density=1.0)
    exact = ellipsoid(radii, density=1.0)
    np.testing.assert_allclose(from_mesh.mass, exact.mass, rtol=1e-3)
    np.testing.assert_allclose(np.diag(from_mesh.inertia), np.diag(exact.inertia), rtol=2e-3)


@pytest.mark.parametrize(
    "make",
    [
        lambda **kw: box((1, 2, 3), **kw),
        lambda **kw: cylinder(0.1, 1, **kw),
        lambda **kw: sphere(0.1, **kw),
        lambda **kw: capsule(0.1, 1, **kw),
        lambda **kw: ellipsoid((0.1, 0.2, 0.3), **kw),
    ],
)
def test_density_or_mass_exactly_one(make):
    assert isinstance(make(mass=1.0), MassProperties)
    with pytest.raises(ValueError, match="exactly one"):
        make()
    with pytest.raises(ValueError, match="exactly one"):
        make(mass=1.0, density=1.0)
    with pytest.raises(ValueError, match="positive"):
        make(mass=-1.0)
    with pytest.raises(ValueError, match="positive"):
        make(density=float("nan"))


@pytest.mark.parametrize("bad", [0.0, -0.1, float("inf"), float("nan"), 1e51, 1e-320])
def test_bad_dimensions_are_named(bad):
    with pytest.raises(ValueError, match="radius must be a positive length in m, at most 1e50"):
        cylinder(bad, 1.0, mass=1)
    with pytest.raises(ValueError, match=r"size\[1\]"):
        box((1, bad, 1), mass=1)


@pytest.mark.parametrize(
    ("make", "message"),
    [
        # the dimensions are usable, their product is not: the volume is named, not the density
        (lambda: box((1e-200, 1e-200, 1e-200), density=1.0), "the volume underflows to zero"),
        (lambda: sphere(1e-300, mass=1.0), "the volume underflows to zero"),
        (lambda: box((1e-200,) * 3, density=1e-50), "the volume underflows"),
        (lambda: box((1e-100,) * 3, density=1e-50), "the mass, density 1e-50 kg/m³"),
        (lambda: box((1, 1, 1), density=1e308), "density must be positive, from 1e-50 to 1e50"),
        (lambda: box((1, 1, 1), density=1e-51), "density must be positive, from 1e-50 to 1e50"),
        (lambda: box((1, 1, 1), mass=5e-324), "mass must be positive, from 1e-50 to 1e50 kg"),
    ],
)
def test_out_of_range_results_blame_the_right_input(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_the_largest_usable_inputs_give_finite_values():
    """Six factors of at most 1e50 stay below 1e300: nothing overflows (physics/numbers.py)."""
    for body in (box((1e50,) * 3, density=1e50), cylinder(1e50, 1e50, density=1e50)):
        assert np.isfinite(body.inertia).all() and np.isfinite(body.principal_moments).all()
