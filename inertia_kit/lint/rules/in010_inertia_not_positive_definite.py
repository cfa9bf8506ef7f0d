"""IN010 inertia-not-positive-definite: a principal moment of the declared tensor is ≤ 0."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
from inertia_kit.description import model
from inertia_kit.engines.lumping import lumped, positive_mass
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.frames import rpy_matrix
from inertia_kit.physics.mass import MassProperties

CODE = "IN010"
NAME = "inertia-not-positive-definite"
SEVERITY = Severity.ERROR
SCOPE = "robot"
SUMMARY = "a principal moment of the declared inertia tensor is zero or negative"

# a principal moment within this fraction of the largest one (or below ZERO_ATOL) is zero:
# eigenvalues of a singular tensor come out as ±1e-17·C, not as 0
ZERO_RTOL = 1e-9
ZERO_ATOL = 1e-18  # kg·m²: 1 mg at 1 µm


# --- shared with IN011/IN012 ------------------------------------------------------------------


def moments(declared: MassProperties) -> NDArray[np.float64]:
    """(3,) principal moments, ascending, kg·m²."""
    return declared.principal_moments


def zero_tolerance(principal: NDArray[np.float64]) -> float:
    return max(ZERO_RTOL * float(np.abs(principal).max()), ZERO_ATOL)


def welded_to_world(robot: RobotAnalysis, name: str) -> bool:
    """Whether a fixed-joint path joins ``name`` to a link called ``world`` (a static body)."""
    return any(member.name == "world" for member in robot.group_of(name))


def lumped_positive_definite(robot: RobotAnalysis, link: LinkAnalysis) -> bool:
    """Whether the link is welded to other links and the lumped body is positive definite."""
    if len(robot.group_of(link.name)) < 2:
        return False
    body = lumped(robot, link.name)
    if body is None:
        return False
    principal = body.principal_moments
    return bool(principal[0] > zero_tolerance(principal))


TENSOR = model.Inertial.TENSOR
_INDEX = {"ixx": (0, 0), "ixy": (0, 1), "ixz": (0, 2), "iyy": (1, 1), "iyz": (1, 2), "izz": (2, 2)}


def written_axes(
    inertial: model.Inertial | None, inertia: NDArray[np.float64]
) -> tuple[NDArray[np.float64], str]:
    """
    A link-frame tensor re-expressed in the axes the ``<inertia>`` values are written in (those
    of ``<inertial><origin rpy>``), so that its six values can replace the declared ones; with
    the words that say so (empty for rpy = 0).
    """
    rpy = (0.0, 0.0, 0.0) if inertial is None else inertial.origin.rpy
    if not isinstance(rpy, tuple) or not any(rpy):
        return inertia, ""
    rotation = rpy_matrix(rpy)
    return rotation.T @ inertia @ rotation, " in the axes of its `<inertial><origin rpy>`"


def tensor_fields(inertia: NDArray[np.float64]) -> dict[str, float]:
    """The six URDF values of a (3, 3) tensor, kg·m², JSON-ready."""
    return {name: float(inertia[_INDEX[name]]) for name in TENSOR}


def tensor_text(inertia: NDArray[np.float64], names: tuple[str, ...] = ()) -> str:
    """``ixx = 0.0163, iyy = 0.0163, izz = 0.0025`` (+ products that are not negligible)."""
    if not names:
        scale = float(np.abs(np.diag(inertia)).max())
        products = tuple(n for n in ("ixy", "ixz", "iyz") if abs(inertia[_INDEX[n]]) > 1e-6 * scale)
        names = ("ixx", "iyy", "izz", *products)
    return ", ".join(f"{n} = {fmt(inertia[_INDEX[n]], 4)}" for n in names)


def geometry_tensor(
    link: LinkAnalysis, mass: float
) -> tuple[dict[str, float], str, NDArray[np.float64]] | None:
    """
    The link geometry's tensor for ``mass`` at uniform density, in the written axes: the
    ``expected`` fields, the message text (``its collision box (…) with 2 kg gives ixx = …``
    without the mass words), and the tensor.
    """
    body = link.geometry.at_mass(mass)
    if body is None:
        return None
    inertia, axes = written_axes(link.link.inertial, body.inertia)
    return tensor_fields(inertia), f"{tensor_text(inertia)} kg·m²{axes}", inertia


def moments_text(principal: NDArray[np.float64]) -> str:
    """``(0, 0.0521, 0.09895) kg·m²``: eigenvalue noise of a zero moment shown as 0."""
    tol = zero_tolerance(principal)
    return "(" + ", ".join(fmt(0.0 if abs(v) <= tol else v, 4) for v in principal) + ") kg·m²"


# --- the rule ---------------------------------------------------------------------------------


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    for link in robot.links:
        declared = positive_mass(link)
        if declared is None:
            continue
        principal = moments(declared)
        tol = zero_tolerance(principal)
        if principal[0] > tol:
            continue
        inertial = link.link.inertial
        assert inertial is not None
        negative = principal[0] < -tol
        if not negative and (
            welded_to_world(robot, link.name) or lumped_positive_definite(robot, link)
        ):
            # a point mass (or rod, or plate) welded to a body: every engine lumps it into
            # that body, whose tensor is positive definite
            continue
        values = inertial.tensor_values()
        if all(v == 0 for v in values.values()):
            what = "all six `<inertia>` values are 0"
        elif float(np.abs(principal).max()) <= tol:
            what = f"the tensor is zero: principal moments {moments_text(principal)}"
        elif negative:
            what = (
                f"principal moments {moments_text(principal)}: "
                f"{fmt(principal[0], 4)} kg·m² is negative"
            )
        else:
            what = f"principal moments {moments_text(principal)}: the smallest is 0"
        basis = ""
        payload = None
        values_at = geometry_tensor(link, declared.mass)
        if values_at is not None:
            payload, text, _ = values_at
            basis = (
                f"; its {link.geometry.describe()} with the declared {fmt(declared.mass)} kg "
                f"gives {text}"
            )
        engines = (
            "MuJoCo refuses the model, Gazebo and Drake reject the tensor, PyBullet zeroes it"
            if negative
            else "MuJoCo refuses the model; Drake and PyBullet cannot turn a body with no "
            "rotational inertia about that axis"
        )
        yield ctx.finding(
            f"link `{link.name}`: {what}, so the tensor is not positive definite ({engines})"
            f"{basis}",
            inertial.inertia_source or inertial.source,
            link=link.name,
            expected=payload,
            help="write the tensor about the centre of mass with every principal moment > 0 "
            "(from CAD, or `inertia-fill --fix invalid` from the geometry); a massless frame "
            "belongs on a link with no <inertial> at all",
        )
