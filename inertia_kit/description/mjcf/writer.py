"""
An MJCF ``<inertial>`` element for mass properties, written as an author of MJCF writes it:
``pos``, then the principal axes as a ``quat`` (left out when they are the body's), ``mass``
and ``diaginertia``; or, for a body whose ``<inertial>`` gives ``fullinertia``, ``pos``,
``mass`` and the six ``fullinertia`` values in the body's axes. Numbers to
:data:`~inertia_kit.description.writing.DIGITS` significant digits; a ``quat`` is
independent of the compiler's ``angle`` unit.
"""

from __future__ import annotations

import itertools

import numpy as np
from numpy.typing import NDArray

from inertia_kit.description.mjcf.orientation import matrix_quat
from inertia_kit.description.writing import DIGITS, PRODUCT_FLOOR
from inertia_kit.physics.formatting import xml_number
from inertia_kit.physics.mass import MassProperties

#: ``fullinertia``'s order (MuJoCo's): the moments, then the products
FULL_ORDER = ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))


def principal_frame(tensor: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray]:
    """
    ``(quat, moments)`` of a symmetric tensor: the rotation (w, x, y, z, w ≥ 0) whose columns
    are its principal axes, right-handed, and the moments about them; of the orders and signs
    of the axes, the one that turns least from the body's (an author's quat turns a part a
    little, not by a relabelling of its axes); a tensor already diagonal (to
    :data:`PRODUCT_FLOOR` of its largest moment) keeps the body's axes.
    """
    tensor = (np.asarray(tensor, dtype=np.float64) + np.asarray(tensor).T) / 2
    scale = float(np.abs(tensor).max()) or 1.0
    if np.abs(tensor - np.diag(np.diag(tensor))).max() <= PRODUCT_FLOOR * scale:
        return np.array([1.0, 0.0, 0.0, 0.0]), np.diag(tensor).copy()
    moments, axes = np.linalg.eigh(tensor)
    best = None
    for order in itertools.permutations(range(3)):
        turned = axes[:, order] * np.where(np.diag(axes[:, order]) < 0, -1.0, 1.0)
        if np.linalg.det(turned) < 0:
            weakest = int(np.argmin(np.abs(np.diag(turned))))
            turned[:, weakest] = -turned[:, weakest]
        if best is None or np.trace(turned) > np.trace(best[0]) + 1e-12:
            best = (turned, moments[list(order)])
    assert best is not None
    return matrix_quat(best[0]), best[1]


def _numbers(values, digits: int) -> str:
    return " ".join(xml_number(float(v), digits) for v in values)


def inertial_attributes(
    properties: MassProperties, form: str = "diaginertia", digits: int = DIGITS
) -> dict[str, str]:
    """The attributes of the ``<inertial>`` for ``properties`` (body frame, about the centre of
    mass), in the order written; ``form``: ``diaginertia`` or ``fullinertia``."""
    clean = properties.cleaned()
    attributes = {"pos": _numbers(clean.com, digits)}
    if form == "fullinertia":
        attributes["mass"] = xml_number(float(clean.mass), digits)
        attributes["fullinertia"] = _numbers([clean.inertia[i, j] for i, j in FULL_ORDER], digits)
        return attributes
    quat, moments = principal_frame(clean.inertia)
    if not np.array_equal(quat, [1.0, 0.0, 0.0, 0.0]):
        attributes["quat"] = _numbers(quat, digits)
    attributes["mass"] = xml_number(float(clean.mass), digits)
    attributes["diaginertia"] = _numbers(moments, digits)
    return attributes


def _balanced(attributes: dict[str, str]) -> bool:
    """Whether the moments as written keep the triangle inequality, which MuJoCo's compiler
    checks (a flat part's A + B = C, rounded, can fall short of it: refused)."""
    if "diaginertia" in attributes:
        moments = np.sort([float(v) for v in attributes["diaginertia"].split()])
    else:
        full = [float(v) for v in attributes["fullinertia"].split()]
        tensor = np.zeros((3, 3))
        for value, (i, j) in zip(full, FULL_ORDER, strict=True):
            tensor[i, j] = tensor[j, i] = value
        moments = np.linalg.eigvalsh(tensor)
    return bool(moments[0] + moments[1] >= moments[2])


def inertial_element(
    properties: MassProperties, form: str = "diaginertia", digits: int = DIGITS
) -> str:
    """The ``<inertial .../>`` element for ``properties``, on one line; with more digits where
    ``digits`` would break the triangle inequality that the values keep."""
    attributes = inertial_attributes(properties, form, digits)
    for more in range(digits + 1, 18):
        if _balanced(attributes):
            break
        attributes = inertial_attributes(properties, form, more)
    return "<inertial " + " ".join(f'{k}="{v}"' for k, v in attributes.items()) + "/>"
