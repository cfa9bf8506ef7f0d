"""Rigid frames as URDF writes them: ``xyz`` + ``rpy`` <-> 4×4 homogeneous transforms."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

_EYE3 = np.eye(3)
_LAST_ROW = np.array([0.0, 0.0, 0.0, 1.0])


def as_vector3(value: ArrayLike, name: str) -> NDArray[np.float64]:
    """Coerce ``value`` to a finite (3,) float64 array, or raise ``ValueError`` naming it."""
    vector = np.asarray(value, dtype=np.float64)
    if vector.shape != (3,):
        raise ValueError(f"{name} must be (3,), got shape {vector.shape}")
    return vector


def rpy_matrix(rpy: ArrayLike) -> NDArray[np.float64]:
    """
    Rotation matrix of URDF roll-pitch-yaw angles.

    URDF applies roll about x, then pitch about y, then yaw about z, all about the fixed
    parent axes, so ``R = Rz(yaw) @ Ry(pitch) @ Rx(roll)``.

    Parameters
    ----------
    rpy : (3,) float
      Roll, pitch, yaw in radians.

    Returns
    -------
    rotation : (3, 3) float
      Columns are the rotated frame's axes expressed in the parent frame.
    """
    angles = as_vector3(rpy, "rpy")
    if not angles.any() and not np.signbit(angles).any():
        return _UNTURNED.copy()  # most origins: the formula's result at +0, signed zeros too
    return _rotation(*angles)


def _rotation(roll: float, pitch: float, yaw: float) -> NDArray[np.float64]:
    cr, sr = np.cos(roll), np.sin(roll)
    cp, sp = np.cos(pitch), np.sin(pitch)
    cy, sy = np.cos(yaw), np.sin(yaw)
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


_UNTURNED = _rotation(np.float64(0.0), np.float64(0.0), np.float64(0.0))


def matrix_rpy(rotation: ArrayLike) -> NDArray[np.float64]:
    """
    Roll-pitch-yaw angles of a rotation matrix (the inverse of :func:`rpy_matrix`).

    Parameters
    ----------
    rotation : (3, 3) float
      A proper rotation matrix.

    Returns
    -------
    rpy : (3,) float
      Radians; pitch in [-pi/2, pi/2]. At gimbal lock roll is set to 0.
    """
    r = np.asarray(rotation, dtype=np.float64)
    if r.shape != (3, 3):
        raise ValueError(f"rotation must be (3, 3), got shape {r.shape}")
    pitch = np.arctan2(-r[2, 0], np.hypot(r[0, 0], r[1, 0]))
    if np.hypot(r[0, 0], r[1, 0]) < 1e-12:
        # gimbal lock: only roll ± yaw is defined, put it all in yaw
        return np.array([0.0, pitch, np.arctan2(-r[0, 1], r[1, 1])])
    return np.array([np.arctan2(r[2, 1], r[2, 2]), pitch, np.arctan2(r[1, 0], r[0, 0])])


def transform(xyz: ArrayLike = (0.0, 0.0, 0.0), rpy: ArrayLike = (0.0, 0.0, 0.0)) -> NDArray:
    """
    4×4 homogeneous transform of a URDF ``<origin xyz rpy>``.

    Returns
    -------
    matrix : (4, 4) float
      Maps coordinates in the child frame to the parent frame.
    """
    matrix = np.eye(4)
    matrix[:3, :3] = rpy_matrix(rpy)
    matrix[:3, 3] = as_vector3(xyz, "xyz")
    return matrix


def as_transform(matrix: ArrayLike) -> NDArray[np.float64]:
    """Coerce to a (4, 4) rigid transform, checking that its rotation part is orthonormal."""
    m = np.asarray(matrix, dtype=np.float64)
    if m.shape != (4, 4):
        raise ValueError(f"transform must be (4, 4), got shape {m.shape}")
    rotation = m[:3, :3]
    # plain max/abs, not np.allclose: this runs for every placed shape and allclose is ~10x slower
    orthonormal = float(np.abs(rotation @ rotation.T - _EYE3).max()) <= 1e-9
    (a, b, c), (d, e, f), (g, h, i) = rotation.tolist()
    if not orthonormal or a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g) < 0:
        raise ValueError(
            "transform's rotation part must be a proper rotation (orthonormal, det +1)"
        )
    if float(np.abs(m[3] - _LAST_ROW).max()) > 1e-12:
        raise ValueError(f"transform's last row must be (0, 0, 0, 1), got {m[3]}")
    return m


def inverse(matrix: ArrayLike) -> NDArray[np.float64]:
    """Inverse of a rigid transform, without a general matrix inversion."""
    m = as_transform(matrix)
    out = np.eye(4)
    out[:3, :3] = m[:3, :3].T
    out[:3, 3] = -m[:3, :3].T @ m[:3, 3]
    return out


def transformed_points(points: NDArray[np.float64], matrix: ArrayLike) -> NDArray[np.float64]:
    """(n, 3) points under a (4, 4) transform, element by element: not a matrix product, since
    BLAS may round the same point differently at different rows, and the closure check of a
    mesh compares vertices by their exact bits."""
    matrix = np.asarray(matrix, dtype=np.float64)
    if np.array_equal(matrix, np.eye(4)):
        return points
    out = points[:, 0:1] * matrix[:3, 0]
    out += points[:, 1:2] * matrix[:3, 1]
    out += points[:, 2:3] * matrix[:3, 2]
    out += matrix[:3, 3]
    return out
