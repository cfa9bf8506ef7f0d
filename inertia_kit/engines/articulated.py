"""
The articulated-body hinge inertias of a tree of rigid bodies at rest: what the tip-to-base pass
of Featherstone's articulated-body algorithm (ABA) factors at each moving joint, and whether it is
positive definite.

An engine that runs the ABA (Drake's ``MultibodyPlant`` does, for forward dynamics) stops when a
hinge inertia ``D = Hᵀ P H`` is not positive definite: the joint moves a subtree that has no
inertia along one of the joint's motions (a massless link, a point mass on a revolute axis, a
massless link between two revolute joints about the same axis).

Everything is expressed in world axes at the zero configuration; each body's spatial inertia and
articulated inertia are about its own origin, spatial vectors ordered ``[ω; v]``. Pure numpy: the
engine model (``engines/drake.py``) builds the bodies from its own reading of the file.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

# a hinge inertia, each motion scaled by its composite (rigid-subtree) inertia, whose smallest
# eigenvalue is at most this is singular: the exact value is 0 and what is left is floating-point
# rounding (~1e-16). Not more: iCub's neck (example-robot-data) has two joint axes parallel to
# 3.7e-6 rad (rpy written 1.5708 for π/2), a hinge inertia of 1.4e-11, and Drake runs it
SINGULAR = 1e-12

MOTIONS = ("fixed", "revolute", "prismatic", "planar", "free")


@dataclass(frozen=True)
class Body:
    """
    One rigid body of the tree.

    Attributes
    ----------
    name : str
    parent : str or None
      The inboard body; ``None`` for a body attached to the world.
    motion : str
      How the joint from ``parent`` (or the world) lets the body move: one of :data:`MOTIONS`.
    axis : (3,) float
      The joint axis in world axes, unit (``revolute``, ``prismatic``: the axis; ``planar``:
      the plane's normal; unused otherwise).
    origin : (3,) float
      The body's origin in the world at rest, m (on the joint axis).
    inertia : (6, 6) float
      Spatial inertia about ``origin`` in world axes, ``[ω; v]`` order.
    """

    name: str
    parent: str | None
    motion: str
    axis: NDArray[np.float64]
    origin: NDArray[np.float64]
    inertia: NDArray[np.float64]


@dataclass(frozen=True)
class Hinge:
    """
    The hinge inertia of one moving joint.

    ``smallest`` is the smallest eigenvalue of the hinge inertia with each motion scaled by its
    composite inertia (1 when the rest of the subtree is rigid, 0 when nothing resists the
    motion); ``depth`` is the body's level in the tree (1 for a body on the world), ``order`` its
    position depth first, children in the order given.
    """

    body: str
    smallest: float
    depth: int
    order: int

    @property
    def singular(self) -> bool:
        return self.smallest <= SINGULAR


def skew(p: NDArray[np.float64]) -> NDArray[np.float64]:
    """(3, 3) matrix of ``p ×``."""
    x, y, z = p
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def spatial_inertia(
    mass: float, com: NDArray[np.float64], central: NDArray[np.float64]
) -> NDArray[np.float64]:
    """
    (6, 6) spatial inertia about the origin of a body of ``mass`` kg whose centre of mass is at
    ``com`` (m) with ``central`` (3, 3) the tensor about it, all in the same axes.
    """
    c = skew(np.asarray(com, dtype=np.float64))
    about_origin = central + mass * (c.T @ c)
    return np.block([[about_origin, mass * c], [-mass * c, mass * np.eye(3)]])


def shift(articulated: NDArray[np.float64], offset: NDArray[np.float64]) -> NDArray[np.float64]:
    """
    A (6, 6) inertia about a point moved to a point ``offset`` behind it: the inertia about ``B``
    of one given about ``C``, with ``offset`` the vector from ``B`` to ``C``.
    """
    transmit = np.eye(6)
    transmit[3:, :3] = -skew(offset)  # v_C = v_B + ω × p_BC
    return transmit.T @ articulated @ transmit


def hinge_matrix(motion: str, axis: NDArray[np.float64]) -> NDArray[np.float64]:
    """(6, n) hinge matrix: the body's spatial velocity for each joint speed."""
    if motion == "revolute":
        return np.concatenate([axis, np.zeros(3)])[:, None]
    if motion == "prismatic":
        return np.concatenate([np.zeros(3), axis])[:, None]
    if motion == "planar":
        # any two in-plane directions: positive definiteness does not depend on the basis
        helper = np.eye(3)[int(np.argmin(np.abs(axis)))]
        first = np.cross(axis, helper)
        first /= np.linalg.norm(first)
        second = np.cross(axis, first)
        columns = [np.r_[np.zeros(3), first], np.r_[np.zeros(3), second], np.r_[axis, np.zeros(3)]]
        return np.array(columns).T
    if motion == "free":
        return np.eye(6)
    return np.zeros((6, 0))


def hinges(bodies: Iterable[Body]) -> list[Hinge]:
    """
    The hinge inertia of every moving joint of a forest, tip to base (deepest first, then depth
    first order): the order in which the ABA factors them and an engine reports the first.

    Bodies whose parent is not in ``bodies`` are attached to the world; a parent cycle is cut
    where it closes.
    """
    by_name: dict[str, Body] = {}
    for body in bodies:
        by_name.setdefault(body.name, body)
    children: dict[str | None, list[Body]] = {}
    for body in by_name.values():
        parent = body.parent if body.parent in by_name else None
        children.setdefault(parent, []).append(body)

    # depth first from the world, children in the order given; each body once
    ordered: list[tuple[Body, int]] = []
    seen: set[str] = set()
    stack = [(body, 1) for body in reversed(children.get(None, []))]
    while stack:
        body, depth = stack.pop()
        if body.name in seen:
            continue
        seen.add(body.name)
        ordered.append((body, depth))
        stack.extend((child, depth + 1) for child in reversed(children.get(body.name, [])))

    articulated: dict[str, NDArray[np.float64]] = {}
    composite: dict[str, NDArray[np.float64]] = {}
    found: list[Hinge] = []
    for order in range(len(ordered) - 1, -1, -1):
        body, depth = ordered[order]
        p = body.inertia.copy()
        k = body.inertia.copy()
        for child in children.get(body.name, []):
            if child.name not in articulated:
                continue
            offset = child.origin - body.origin
            p += shift(articulated[child.name], offset)
            k += shift(composite[child.name], offset)
        h = hinge_matrix(body.motion, body.axis)
        if h.shape[1]:
            d = h.T @ p @ h
            scale = np.diag(h.T @ k @ h)
            if (scale > 0).all() and np.isfinite(d).all():
                found.append(Hinge(body.name, _smallest_scaled(d, scale), depth, order))
            else:
                found.append(Hinge(body.name, 0.0, depth, order))
            u = p @ h
            # the motions nothing resists are left free: the pseudo-inverse drops them
            p = p - u @ _pseudo_inverse(d) @ u.T
        articulated[body.name] = p
        composite[body.name] = k
    found.sort(key=lambda hinge: (-hinge.depth, hinge.order))
    return found


def _smallest_scaled(d: NDArray[np.float64], scale: NDArray[np.float64]) -> float:
    """
    The smallest eigenvalue of ``d`` with each motion scaled by ``scale`` (positive): each row
    and column divided by the root of its own scale, not by the root of a product, which
    underflows to 0 for a 1e-300 kg·m² moment. NaN (no claim) where the scaled matrix leaves
    double precision or its eigenvalues do not converge.
    """
    root = np.sqrt(scale)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        normed = d / root[:, None] / root[None, :]
    if not np.isfinite(normed).all():
        return math.nan
    try:
        return float(np.linalg.eigvalsh(0.5 * (normed + normed.T))[0])
    except np.linalg.LinAlgError:
        return math.nan


def _pseudo_inverse(d: NDArray[np.float64]) -> NDArray[np.float64]:
    """
    ``d``'s pseudo-inverse; NaN where it has none: values past double precision (a 1e292 kg
    body: the decomposition does not converge) give no number, as they give none in an engine,
    and the hinges above then compare as nothing resisting them.
    """
    if np.isfinite(d).all():
        try:
            return np.linalg.pinv(d, rcond=SINGULAR, hermitian=True)
        except np.linalg.LinAlgError:
            pass
    return np.full(d.shape[::-1], np.nan)
