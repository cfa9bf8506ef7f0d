"""analysis.tensors: comparing tensors about every axis, naming axes, zero moments."""

from __future__ import annotations

import math

import numpy as np
import pytest

from inertia_kit.analysis.tensors import (
    ZERO_ATOL,
    axis_name,
    compare_tensors,
    moments_text,
    positive_definite,
    zero_tolerance,
)
from inertia_kit.physics.frames import rpy_matrix, transform
from inertia_kit.physics.mass import MassProperties


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


# --- zero moments -------------------------------------------------------------------------------


def test_zero_tolerance_is_relative_with_an_absolute_floor():
    assert zero_tolerance(np.array([0.0, 1.0, 2.0])) == pytest.approx(2e-9)
    assert zero_tolerance(np.zeros(3)) == ZERO_ATOL


def test_positive_definite_sees_eigenvalue_noise_as_zero():
    rod = MassProperties(1.0, np.zeros(3), np.diag([1.0, 1.0, 0.0]))
    turned = rod.transformed(transform(rpy=(0.3, 0.2, 0.1)))
    assert abs(turned.principal_moments[0]) < 1e-15  # noise, not an exact zero
    assert not positive_definite(turned)
    assert not positive_definite(None)
    assert positive_definite(MassProperties(1.0, np.zeros(3), np.eye(3)))
    assert moments_text(turned.principal_moments) == "(0, 1, 1) kg·m²"
