"""
Volume integrals as values: about a mass or a density, scaled (and mirrored), added, and their
centroid, against closed forms and against integrating the transformed surface.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from kit.meshes import box_triangles
from kit.moments import box_tensor
from kit.physics import assert_mass_close, random_rotation, sphere_triangles

from inertia_kit.physics.polyhedra import integrate
from inertia_kit.physics.volume_moments import VolumeMoments

RNG = np.random.default_rng(20261121)
DENSITY = 1000.0


def test_box_by_mass_and_by_density_agree():
    moments = integrate(box_triangles((0.5, 0.25, 2.0))).moments
    by_density = moments.mass_properties(density=DENSITY)
    by_mass = moments.mass_properties(mass=by_density.mass)
    assert_mass_close(by_mass, by_density)
    with pytest.raises(ValueError, match="exactly one"):
        moments.mass_properties(density=1.0, mass=1.0)


@pytest.mark.parametrize(
    "scale", [(2.0, 0.5, 3.0), (-1.0, 1.0, 1.0), (1.0, -2.0, -0.5), (-1.0, -1.0, -1.0)]
)
def test_scaled_equals_integrating_the_scaled_mesh(scale):
    triangles = sphere_triangles(3) * (1.0, 0.7, 0.4) @ random_rotation(RNG).T + (0.3, 0.1, -0.2)
    scaled = triangles * scale
    if np.prod(scale) < 0:  # a mirror turns the winding inside out
        scaled = scaled[:, ::-1]
    expected = integrate(scaled).moments.mass_properties(density=DENSITY)
    moments = integrate(triangles).moments.scaled(scale)
    assert moments.volume > 0
    assert_mass_close(moments.mass_properties(density=DENSITY), expected)


def test_millimetre_mesh_scaled_to_metres():
    size, low = (500.0, 250.0, 2000.0), (250.0, -500.0, 1000.0)
    moments = integrate(box_triangles(size, low).astype(np.float32)).moments.scaled((1e-3,) * 3)
    properties = moments.mass_properties(density=DENSITY)
    metres = np.multiply(size, 1e-3)
    mass = DENSITY * math.prod(metres)
    assert properties.mass == pytest.approx(mass, rel=1e-12)
    np.testing.assert_allclose(properties.com, (0.5, -0.375, 2.0), atol=1e-12)
    np.testing.assert_allclose(properties.inertia, box_tensor(mass, metres), atol=1e-12 * mass)


def test_scaled_rejects_zero_and_non_finite_factors():
    moments = integrate(box_triangles((0.5, 0.25, 2.0))).moments
    for scale in [(1.0, 0.0, 1.0), (1.0, np.nan, 1.0), (1.0, 1.0)]:
        with pytest.raises(ValueError, match="scale"):
            moments.scaled(scale)


def test_moments_add_up_about_a_common_point():
    low, high = box_triangles((1.0, 1.0, 1.0)), box_triangles((1.0, 1.0, 1.0), (0.0, 0.0, 1.0))
    both = integrate(low, (0.0, 0.0, 0.0)).moments + integrate(high, (3.0, 1.0, 2.0)).moments
    tall = integrate(box_triangles((1.0, 1.0, 2.0))).moments
    assert_mass_close(both.mass_properties(density=DENSITY), tall.mass_properties(density=DENSITY))


def test_volume_moments_type():
    moments = integrate(box_triangles((0.5, 0.25, 2.0))).moments
    assert isinstance(moments, VolumeMoments)
    np.testing.assert_allclose(moments.centroid, (0.25, 0.125, 1.0), atol=1e-15)
