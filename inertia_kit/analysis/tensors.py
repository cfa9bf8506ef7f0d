"""
Inertia tensors judged on their own and against each other: when a principal moment is zero
(:func:`zero_tolerance`), how one tensor compares with another about every axis
(:func:`compare_tensors`), and which link axis a direction is (:func:`axis_name`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from inertia_kit.physics.formatting import vector_text
from inertia_kit.physics.mass import MassProperties

# a principal moment within this fraction of the largest one (or below ZERO_ATOL) is zero:
# eigenvalues of a singular tensor come out as ±1e-17·C, not as 0
ZERO_RTOL = 1e-9
ZERO_ATOL = 1e-18  # kg·m²: 1 mg at 1 µm


def zero_tolerance(principal: NDArray[np.float64]) -> float:
    """Below this a principal moment of ``principal`` (3,) kg·m² is zero, kg·m²."""
    return max(ZERO_RTOL * float(np.abs(principal).max()), ZERO_ATOL)


def positive_definite(body: MassProperties | None) -> bool:
    """Whether every principal moment of ``body`` is above :func:`zero_tolerance`."""
    if body is None:
        return False
    principal = body.principal_moments
    return bool(principal[0] > zero_tolerance(principal))


def moments_text(principal: NDArray[np.float64]) -> str:
    """``(0, 0.0521, 0.09895) kg·m²``: eigenvalue noise of a zero moment shown as 0."""
    tol = zero_tolerance(principal)
    return vector_text(0.0 if abs(v) <= tol else v for v in principal) + " kg·m²"


@dataclass(frozen=True)
class TensorComparison:
    """
    How a declared inertia tensor compares with an expected one, axis by axis, in link axes.

    ``ratios[i]`` is the generalised eigenvalue ``λ`` of ``I_declared v = λ I_expected v``: the
    ratio of the two moments about ``axes[i]``. They are the stationary values of
    ``nᵀ I_declared n / nᵀ I_expected n`` over all axes ``n``, so the largest and smallest are
    the largest and smallest ratio of moments about any axis: a tensor written for the wrong
    axes (same eigenvalues) shows up, and so does a wrong value about an axis of symmetry.

    Attributes
    ----------
    ratios : (3,) float
      Ascending.
    axes : (3, 3) float
      Unit axes (rows), link frame.
    """

    ratios: NDArray[np.float64]
    axes: NDArray[np.float64]

    @property
    def worst(self) -> int:
        """Index of the ratio farthest from 1 (by factor)."""
        return int(np.argmax(np.abs(np.log(self.ratios))))

    @property
    def factor(self) -> float:
        """The largest factor between the two moments about any axis (≥ 1)."""
        return float(np.exp(np.abs(np.log(self.ratios)).max()))


def compare_tensors(declared: ArrayLike, expected: ArrayLike) -> TensorComparison | None:
    """
    Compare two inertia tensors (3, 3) kg·m² in the same axes through generalised eigenvalues.

    Returns ``None`` unless both are symmetric positive definite (the expected one must be; a
    declared one that is not is another rule's finding).
    """
    a = np.asarray(declared, dtype=np.float64)
    b = np.asarray(expected, dtype=np.float64)
    if (
        a.shape != (3, 3)
        or b.shape != (3, 3)
        or not (np.isfinite(a).all() and np.isfinite(b).all())
    ):
        return None
    a, b = 0.5 * (a + a.T), 0.5 * (b + b.T)
    try:
        lower = np.linalg.cholesky(b)
        np.linalg.cholesky(a)
    except np.linalg.LinAlgError:
        return None
    inverse = np.linalg.inv(lower)
    # eigh: symmetric input; L⁻¹ A L⁻ᵀ has the generalised eigenvalues of (A, B = L Lᵀ)
    ratios, vectors = np.linalg.eigh(inverse @ a @ inverse.T)
    axes = (inverse.T @ vectors).T
    axes /= np.linalg.norm(axes, axis=1, keepdims=True)
    if not (ratios > 0).all():
        return None
    return TensorComparison(ratios, axes)


def axis_name(axis: ArrayLike, tol: float = 1e-3) -> str | None:
    """``x``, ``y`` or ``z`` when the unit ``axis`` (3,) is (anti)parallel to a link axis."""
    a = np.abs(np.asarray(axis, dtype=np.float64))
    index = int(np.argmax(a))
    return "xyz"[index] if a[index] >= 1.0 - tol else None
