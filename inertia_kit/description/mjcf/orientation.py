"""
MJCF's orientation forms (``quat``, ``axisangle``, ``xyaxes``, ``zaxis``, ``euler``) as the
rotation matrix MuJoCo's compiler makes of them (``mjuu_frame2quat`` and friends in
``user_util.cc``), under the ``<compiler angle eulerseq>`` in force.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

#: the attributes that give an element's orientation; MuJoCo refuses more than one
FORMS = ("quat", "axisangle", "xyaxes", "zaxis", "euler")


class OrientationError(ValueError):
    """An orientation MuJoCo refuses (a zero quaternion, a zero axis, a bad ``eulerseq``)."""


def quat_matrix(quat: Sequence[float]) -> NDArray[np.float64]:
    """The rotation of a quaternion ``(w, x, y, z)``, normalised first as MuJoCo does."""
    q = np.asarray(quat, dtype=np.float64)
    norm = float(np.linalg.norm(q))
    if not norm > 1e-10:  # mjMINVAL
        raise OrientationError("a quaternion of zero length")
    w, x, y, z = q / norm
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def _axis_quat(axis: Sequence[float], angle: float) -> NDArray[np.float64]:
    a = np.asarray(axis, dtype=np.float64)
    norm = float(np.linalg.norm(a))
    if not norm > 1e-10:
        raise OrientationError("a rotation axis of zero length")
    return np.array([math.cos(angle / 2), *(a / norm * math.sin(angle / 2))])


def _multiply(p: NDArray[np.float64], q: NDArray[np.float64]) -> NDArray[np.float64]:
    pw, px, py, pz = p
    qw, qx, qy, qz = q
    return np.array(
        [
            pw * qw - px * qx - py * qy - pz * qz,
            pw * qx + px * qw + py * qz - pz * qy,
            pw * qy - px * qz + py * qw + pz * qx,
            pw * qz + px * qy - py * qx + pz * qw,
        ]
    )


def rotation(form: str, values: Sequence[float], *, degrees: bool, eulerseq: str = "xyz"):
    """
    The rotation matrix of one orientation attribute.

    Parameters
    ----------
    form : str
      One of :data:`FORMS`.
    values : sequence of float
      The attribute's numbers (4 for ``quat`` and ``axisangle``, 6 for ``xyaxes``, 3 else).
    degrees : bool
      ``<compiler angle="degree">`` (MJCF's default): the angles of ``axisangle`` and
      ``euler`` are in degrees.
    eulerseq : str
      ``<compiler eulerseq>``: three of ``xyzXYZ``; lower case rotates about the moving axes
      (intrinsic), upper case about the fixed ones.

    Raises
    ------
    OrientationError
      For a wrong count of numbers or an orientation MuJoCo refuses.
    """
    counts = {"quat": 4, "axisangle": 4, "xyaxes": 6, "zaxis": 3, "euler": 3}
    if len(values) != counts[form]:
        raise OrientationError(f"{form} takes {counts[form]} numbers, got {len(values)}")
    unit = math.pi / 180 if degrees else 1.0
    if form == "quat":
        return quat_matrix(values)
    if form == "axisangle":
        return quat_matrix(_axis_quat(values[:3], values[3] * unit))
    if form == "xyaxes":
        x = np.asarray(values[:3], dtype=np.float64)
        y = np.asarray(values[3:], dtype=np.float64)
        if not np.linalg.norm(x) > 1e-10:
            raise OrientationError("xyaxes: an x axis of zero length")
        x = x / np.linalg.norm(x)
        y = y - x * float(x @ y)
        if not np.linalg.norm(y) > 1e-10:
            raise OrientationError("xyaxes: a y axis parallel to x")
        y = y / np.linalg.norm(y)
        return np.column_stack([x, y, np.cross(x, y)])
    if form == "zaxis":
        z = np.asarray(values, dtype=np.float64)
        if not np.linalg.norm(z) > 1e-10:
            raise OrientationError("zaxis: a vector of zero length")
        z = z / np.linalg.norm(z)
        axis = np.cross([0.0, 0.0, 1.0], z)
        s = float(np.linalg.norm(axis))
        axis = np.array([1.0, 0.0, 0.0]) if s < 1e-10 else axis / s
        angle = math.atan2(s, z[2])
        return quat_matrix([math.cos(angle / 2), *(axis * math.sin(angle / 2))])
    if len(eulerseq) != 3 or any(c not in "xyzXYZ" for c in eulerseq):
        raise OrientationError(f"eulerseq must be three of xyzXYZ, got {eulerseq!r}")
    q = np.array([1.0, 0.0, 0.0, 0.0])
    for letter, angle in zip(eulerseq, values, strict=True):
        axis = np.zeros(3)
        axis["xyz".index(letter.lower())] = 1.0
        step = _axis_quat(axis, angle * unit)
        q = _multiply(q, step) if letter.islower() else _multiply(step, q)
    return quat_matrix(q)


def matrix_quat(matrix: NDArray[np.float64]) -> NDArray[np.float64]:
    """The unit quaternion (w, x, y, z), w ≥ 0, of a rotation matrix (Shepperd's method)."""
    m = matrix
    trace = np.trace(m)
    if trace > max(m[0, 0], m[1, 1], m[2, 2]):
        w = np.sqrt(1.0 + trace) / 2
        q = np.array(
            [
                w,
                (m[2, 1] - m[1, 2]) / (4 * w),
                (m[0, 2] - m[2, 0]) / (4 * w),
                (m[1, 0] - m[0, 1]) / (4 * w),
            ]
        )
    else:
        i = int(np.argmax(np.diag(m)))
        j, k = (i + 1) % 3, (i + 2) % 3
        r = np.sqrt(1.0 + m[i, i] - m[j, j] - m[k, k])
        q = np.empty(4)
        q[1 + i] = r / 2
        q[1 + j] = (m[j, i] + m[i, j]) / (2 * r)
        q[1 + k] = (m[k, i] + m[i, k]) / (2 * r)
        q[0] = (m[k, j] - m[j, k]) / (2 * r)
    q /= np.linalg.norm(q)
    return -q if q[0] < 0 else q
