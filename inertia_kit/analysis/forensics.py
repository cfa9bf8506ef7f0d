"""
Forensics: why a declared inertia tensor disagrees with its link's geometry.

Each hypothesis is a known slip that turns the right tensor into the declared one. A hypothesis
is tested by undoing the slip on the declared values and comparing the result with the
geometry's tensor (declared mass, uniform density, link frame, about the COM):

- ``IN060`` the tensor is about another point (the link origin, a joint origin, a mesh's
  origin, or a point solved for when no mass inside the geometry could have the declared
  tensor) instead of the COM: ``declared = I_com + m (|d|² E - d dᵀ)``;
- ``IN061`` the products of inertia have the opposite sign convention (``ixy = +∫xy dm``);
- ``IN062`` the tensor is written in the axes of another frame (a shape's own axes, an axis
  permutation, the geometry's principal axes) without ``<inertial><origin rpy>``;
- ``IN063`` a unit slip: the tensor in g·m², kg·mm², kg·cm², lb·in², … (or the inverse
  conversion), or the mass in grams;
- ``IN064`` the six values transcribed into the wrong attributes.

A hypothesis explains the numbers when the corrected tensor is within :data:`TOLERANCE` of the
geometry's about every axis, at least :data:`BETTER` times closer than the declared one, and
the declared one is off by :data:`MIN_MISMATCH` at least (nothing is diagnosed on a tensor that
already agrees). Simpler explanations win over ones with free parameters.

API (stable: ``inertia_kit.fill.plan`` and the IN020/IN06x rules use it)
----------------------------------------------------------------------
``diagnose_link(link: LinkAnalysis) -> Diagnosis | None``
    The diagnosis of a link's declared tensor: against its collision geometry, else its visual
    one; ``None`` when the tensor agrees with either (within :data:`MIN_MISMATCH`, like IN020)
    or nothing explains it. Cached per link. ``inertia-fill --fix invalid`` writes
    ``corrected`` for a diagnosed link.
``diagnose_basis(link, basis, loose=False) -> Diagnosis | None``
    The same against one of ``link.bases``; ``loose=True`` is IN020's "likely" note (within
    :data:`LOOSE`, no point solved for), never a correction.
``diagnose(declared, expected, *, points=(), rotations=(), axes=None, hull=None, volume=None,
geometry="geometry", tolerance=TOLERANCE, better=BETTER) -> Diagnosis | None``
    The pure test of one declared value against one geometry-derived value (both
    ``MassProperties`` in the link frame), with named reference points and frames.
``deviation(tensor, reference) -> float``
    The measure: the largest relative difference of moments about any axis.
``Diagnosis``
    ``code`` (``"IN060"`` … ``"IN064"``), ``summary`` and ``detail`` (message pieces, without
    the link name), ``help``, ``corrected`` (``MassProperties`` in the link frame, tensor in link
    axes about the COM: the declared COM, the declared mass except for a mass in grams (IN063),
    the declared values with the slip undone), ``residual`` (deviation of ``corrected`` from
    the geometry) and ``plain_residual`` (of the declared tensor), ``data`` (JSON-ready:
    ``point``/``point_name``, ``rotation``/``rpy``/``frame``, ``factor``/``unit``/
    ``mass_factor``, ``assignment``), ``basis`` (``"collision"``/``"visual"``) and
    ``expected()`` (the dict a finding carries).
"""

from __future__ import annotations

import itertools
import math
import weakref
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from inertia_kit.description import model
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.frames import matrix_rpy, rpy_matrix
from inertia_kit.physics.mass import MassProperties, shift_tensor

if TYPE_CHECKING:
    from inertia_kit.analysis.bounds import Hull
    from inertia_kit.analysis.geometry import Geometry
    from inertia_kit.analysis.links import LinkAnalysis

#: a corrected tensor explains the numbers within this deviation (2 %): CAD values are rounded to
#: 3–4 significant digits, far below it
TOLERANCE = 0.02
#: ... and only when it is this many times closer to the geometry than the declared tensor
BETTER = 10.0
#: IN020's "most likely" note: within 10 % and 3 times closer than the declared tensor
LOOSE = 0.1
LOOSE_BETTER = 3.0
#: nothing is diagnosed when the declared tensor is within 10 % of the geometry's already
MIN_MISMATCH = 0.1
#: deviations are relative to each axis's moment plus this fraction of the largest one, so that
#: the rounding of large entries does not count as a mismatch about a thin body's long axis
FLOOR = 0.05
#: a candidate within this much of the best fit wins over it when it is a simpler explanation
SLACK = 0.005
#: plausible densities, kg/m³ (IN022's defaults): a unit slip is only considered when undoing it
#: leaves one (a density 1e-9 says the mesh is in millimetres, IN031, not the tensor)
DENSITIES = (50.0, 25000.0)
ATTRIBUTES = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
_INDEX = ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))

# (factor, unit) for a tensor written in another unit: declared = factor × the right value
_UNITS: tuple[tuple[float, str], ...] = (
    (1e3, "g·m²"),
    (1e4, "kg·cm²"),
    (1e6, "kg·mm²"),
    (1e7, "g·cm²"),
    (1e9, "g·mm²"),
    (1.0 / 2.9263965e-4, "lb·in²"),
    (1.0 / 4.2140110e-2, "lb·ft²"),
)
_GRAMS = 1e3


@dataclass(frozen=True, eq=False)
class Diagnosis:
    """
    A known slip that explains a declared tensor (see the module docstring).

    ``summary`` is one clause ("the declared inertia is the tensor about the link origin (0, 0,
    0), not about the COM (0, 0, 0.2)"), ``detail`` the numbers that show it; a message is
    ``f"link `{name}`: {summary}: {detail}"``.
    """

    code: str
    summary: str
    detail: str
    help: str
    corrected: MassProperties
    residual: float
    plain_residual: float
    data: dict[str, Any] = field(default_factory=dict)
    basis: str | None = None

    def expected(self) -> dict[str, Any]:
        """The corrected values and the hypothesis, JSON-ready, for a finding's ``expected``."""
        clean = self.corrected.cleaned()
        tensor = clean.inertia
        values = {
            name: float(tensor[i, j]) for name, (i, j) in zip(ATTRIBUTES, _INDEX, strict=True)
        }
        return {
            "mass": clean.mass,
            "xyz": [float(v) for v in clean.com],
            **values,
            "hypothesis": self.summary,
            **self.data,
            "basis": self.basis,
            "residual": self.residual,
            "plain_residual": self.plain_residual,
        }


@dataclass(frozen=True, eq=False)
class _Candidate:
    code: str
    rank: int  # lower: fewer free parameters, preferred among near-equal fits
    corrected: MassProperties
    residual: float
    data: dict[str, Any]
    label: str = ""
    extra: Any = None


# --- measure -------------------------------------------------------------------------------------


def _symmetric(tensor: ArrayLike) -> NDArray[np.float64]:
    t = np.asarray(tensor, dtype=np.float64)
    return 0.5 * (t + t.swapaxes(-1, -2))


class _Metric:
    """:func:`deviation` from one reference tensor, vectorised over candidate tensors."""

    def __init__(self, reference: ArrayLike):
        self.reference = _symmetric(reference)
        floor = FLOOR * float(np.linalg.eigvalsh(self.reference).max())
        self.inverse = np.linalg.inv(np.linalg.cholesky(self.reference + floor * np.eye(3)))

    def __call__(self, tensors: ArrayLike) -> NDArray[np.float64]:
        difference = _symmetric(tensors) - self.reference
        scaled = self.inverse @ difference @ self.inverse.T
        # eigvalsh: symmetric input; the extreme eigenvalues are the extreme ratios over axes
        return np.abs(np.linalg.eigvalsh(scaled)).max(axis=-1)


def deviation(tensor: ArrayLike, reference: ArrayLike) -> float:
    """
    How far ``tensor`` is from ``reference`` (both (3, 3) kg·m², same axes): the largest
    ``|nᵀ (T - R) n| / (nᵀ R n + FLOOR λmax(R))`` over unit axes ``n``.

    0 when equal, 1 for a tensor twice the reference, ~1e6 for one in kg·mm². ``reference`` must
    be positive definite; ``tensor`` may be anything symmetric (a transposed one often is not
    positive definite).
    """
    return float(_Metric(reference)(tensor))


# --- hypotheses ----------------------------------------------------------------------------------


def _round(value: float) -> bool:
    """A value with one significant digit (1, 0.001, 5e-4): how placeholders are written."""
    if not value > 0:
        return False
    mantissa = value / 10.0 ** math.floor(math.log10(value))
    return abs(mantissa - round(mantissa)) <= 1e-9 * mantissa


def _unit_slips(
    declared: MassProperties, expected: MassProperties, volume: float | None
) -> list[_Candidate]:
    """IN063: the tensor in another unit, or the mass in grams (judged by the density)."""
    moments = np.linalg.eigvalsh(_symmetric(declared.inertia))
    if moments[-1] - moments[0] <= 1e-9 * moments[-1] and _round(float(moments[-1])):
        # ixx = iyy = izz = 1 on a sphere or a cube is a placeholder (IN013); that a power of
        # ten relates it to the geometry's tensor is a coincidence of round numbers
        return []
    mass_factors = [1.0]
    if volume is not None and volume > 0:
        low, high = DENSITIES
        density = declared.mass / volume
        if density > high and low <= density / _GRAMS <= high:
            mass_factors = [_GRAMS]
        elif not low <= density <= high:
            return []  # the geometry's scale is in doubt (IN022, IN031): no unit to blame
    found = []
    for mass_factor in mass_factors:
        mass = declared.mass / mass_factor
        reference = expected.inertia / mass_factor
        options = [(1.0, "kg·m²")] if mass_factor != 1.0 else []
        options += [(f, u) for f, u in _UNITS] + [(1.0 / f, u) for f, u in _UNITS]
        metric = _Metric(reference)
        for factor, unit in options:
            inertia = declared.inertia / factor
            corrected = MassProperties(mass, declared.com, inertia)
            data = {"factor": factor, "unit": unit, "mass_factor": mass_factor}
            found.append(_Candidate("IN063", 0, corrected, float(metric(inertia)), data))
    return found


def _flip_products(written: NDArray[np.float64]) -> NDArray[np.float64]:
    return 2.0 * np.diag(np.diag(written)) - written


def _sign_flip(
    declared: MassProperties, axes: NDArray[np.float64], metric: _Metric
) -> list[_Candidate]:
    """IN061: ``ixy``, ``ixz``, ``iyz`` written with ``+∫xy dm``."""
    written = axes.T @ declared.inertia @ axes
    products = np.abs(written[np.triu_indices(3, 1)])
    if not products.max() > 1e-9 * np.abs(np.diag(written)).max():
        return []  # no products: flipping them changes nothing
    inertia = axes @ _flip_products(written) @ axes.T
    corrected = MassProperties(declared.mass, declared.com, inertia)
    return [_Candidate("IN061", 1, corrected, float(metric(inertia)), {})]


def _about_point(
    declared: MassProperties, point: NDArray[np.float64], rank: int, label: str, metric: _Metric
) -> _Candidate:
    inertia = declared.inertia - shift_tensor(declared.mass, declared.com - point)
    corrected = MassProperties(declared.mass, declared.com, inertia)
    data = {"point": [float(v) for v in point], "point_name": label or None}
    return _Candidate("IN060", rank, corrected, float(metric(inertia)), data, label, point)


def _symmetric_about(tensor: NDArray[np.float64], axis: NDArray[np.float64]) -> bool:
    """Whether ``axis`` is a principal axis about which the body is round (equal moments across)."""
    scale = float(np.trace(tensor))
    if np.linalg.norm(tensor @ axis - (axis @ tensor @ axis) * axis) > TOLERANCE * scale:
        return False
    across = np.linalg.eigvalsh(tensor - np.outer(axis, axis) * (axis @ tensor @ axis))
    # the block across the axis has eigenvalues 0 (along it) and the two moments across it
    return bool(abs(across[2] - across[1]) <= TOLERANCE * scale)


def _other_points(
    declared: MassProperties,
    expected: MassProperties,
    points: Sequence[tuple[str, ArrayLike]],
    hull: Hull | None,
    metric: _Metric,
) -> list[_Candidate]:
    """IN060: the tensor about a named point, or about a point solved for."""
    size = math.sqrt(max(float(np.linalg.eigvalsh(expected.inertia).max()), 0.0) / declared.mass)
    found = []
    for label, xyz in points:
        point = np.asarray(xyz, dtype=np.float64)
        if np.linalg.norm(declared.com - point) > 1e-6 * size:
            found.append(_about_point(declared, point, 2, label, metric))
    if hull is None:
        return found
    # declared - I = m (|d|² E - d dᵀ) means the second moment of the difference is m d dᵀ
    difference = (declared.inertia - expected.inertia) / declared.mass
    values, vectors = np.linalg.eigh(0.5 * np.trace(difference) * np.eye(3) - difference)
    if not values[-1] > 0:
        return found
    offset = math.sqrt(values[-1]) * vectors[:, -1]
    # A point solved for is only believed when no mass inside the geometry could give the
    # declared tensor about its COM: the declared second moment along d exceeds the most any
    # distribution in the hull has (Bhatia–Davis). Inside that bound, an excess such as (δ, δ, 0)
    # on a cylinder is as well explained by mass at its ends as by a shifted reference point.
    direction = offset / np.linalg.norm(offset)
    if _symmetric_about(expected.inertia, direction):
        # about a point on a symmetry axis the excess is (δ, δ, 0): any too large value written
        # with the body's symmetry fits it exactly, so the fit proves nothing
        return found
    second = float(direction @ declared.second_moment @ direction) / declared.mass
    if not second > (1.0 + TOLERANCE) * float(hull.spread(declared.com, direction[None, :])[0]):
        return found
    # the sign of d is free: the point nearer the link origin
    point = min((declared.com - offset, declared.com + offset), key=lambda p: float(p @ p))
    found.append(_about_point(declared, point, 6, "", metric))
    return found


_PERMUTATIONS = tuple(
    matrix
    for order in itertools.permutations(range(3))
    for signs in itertools.product((1.0, -1.0), repeat=3)
    if np.linalg.det(matrix := np.eye(3)[list(order)] * np.array(signs)[:, None]) > 0
    and not np.array_equal(matrix, np.eye(3))
)


def _other_axes(
    declared: MassProperties,
    expected: MassProperties,
    rotations: Sequence[tuple[str, ArrayLike]],
    metric: _Metric,
) -> list[_Candidate]:
    """
    IN062: the tensor written in the axes of another frame. A rotation ``A`` (columns: the axes
    the values were written in, in link coordinates) turns them into link axes: ``A T Aᵀ``.
    """
    found = []
    named = [(label, np.asarray(r, dtype=np.float64), 3) for label, r in rotations]
    named += [("", p, 4) for p in _PERMUTATIONS]
    for label, rotation, rank in named:
        inertia = rotation @ declared.inertia @ rotation.T
        corrected = MassProperties(declared.mass, declared.com, inertia)
        found.append(
            _Candidate("IN062", rank, corrected, float(metric(inertia)), {}, label, rotation)
        )
    # the principal axes: declared values written in the geometry's principal frame (a diagonal
    # tensor from a CAD report without its rotation)
    moments, declared_axes = np.linalg.eigh(_symmetric(declared.inertia))
    _, geometry_axes = np.linalg.eigh(_symmetric(expected.inertia))
    rotation = geometry_axes @ declared_axes.T
    if np.linalg.det(rotation) < 0:
        rotation = geometry_axes @ np.diag([1.0, 1.0, -1.0]) @ declared_axes.T
    inertia = geometry_axes @ np.diag(moments) @ geometry_axes.T
    corrected = MassProperties(declared.mass, declared.com, inertia)
    found.append(_Candidate("IN062", 7, corrected, float(metric(inertia)), {}, "", rotation))
    return found


def _transposed(
    declared: MassProperties, axes: NDArray[np.float64], metric: _Metric, tolerance: float
) -> list[_Candidate]:
    """IN064: the six written values in other attributes (permutations that are not rotations)."""
    written = axes.T @ declared.inertia @ axes
    values = np.array([written[i, j] for i, j in _INDEX])
    orders = np.array(list(itertools.permutations(range(6))))
    candidates = values[orders]  # (720, 6)
    _, unique = np.unique(np.round(candidates, 15), axis=0, return_index=True)
    orders, candidates = orders[unique], candidates[unique]
    keep = ~np.all(candidates == values, axis=1)
    orders, candidates = orders[keep], candidates[keep]
    if not len(orders):
        return []
    tensors = np.empty((len(orders), 3, 3))
    for k, (i, j) in enumerate(_INDEX):
        tensors[:, i, j] = tensors[:, j, i] = candidates[:, k]
    # a permutation with the declared eigenvalues is a rotation in disguise: IN062's
    own = np.linalg.eigvalsh(written)
    scale = np.abs(own).max()
    rotation_like = np.abs(np.linalg.eigvalsh(tensors) - own).max(axis=1) <= 1e-9 * scale
    in_link = axes @ tensors @ axes.T
    residuals = metric(in_link)
    found = []
    for order, tensor, residual, skip in zip(
        orders, in_link, residuals, rotation_like, strict=True
    ):
        if skip or residual > tolerance:
            continue
        moved = sum(1 for k in range(6) if values[order[k]] != values[k])
        corrected = MassProperties(declared.mass, declared.com, tensor)
        # fewer moved values first: the simplest transcription slip that explains the numbers
        found.append(_Candidate("IN064", 5, corrected, float(residual), {}, "", (moved, order)))
    return found


# --- choosing and wording ------------------------------------------------------------------------


def _choose(candidates: list[_Candidate], tolerance: float) -> _Candidate | None:
    fits = [c for c in candidates if c.residual <= tolerance]
    if not fits:
        return None
    best = min(c.residual for c in fits)
    near = [c for c in fits if c.residual <= best + SLACK]

    def key(c: _Candidate) -> tuple:
        moved = c.extra[0] if c.code == "IN064" else 0
        return (c.rank, moved, c.residual)

    return min(near, key=key)


def _vector(v: ArrayLike, digits: int = 4) -> str:
    return "(" + ", ".join(fmt(x, digits) for x in np.asarray(v, dtype=np.float64)) + ")"


def _axis_text(axis: NDArray[np.float64]) -> str:
    a = np.abs(axis)
    index = int(np.argmax(a))
    if a[index] >= 1.0 - 1e-3:
        return "xyz"[index]
    if axis[index] < 0:
        axis = -axis
    return _vector(axis, 3)


def _distinct_axis(tensor: NDArray[np.float64]) -> tuple[str, NDArray[np.float64]] | None:
    """The principal axis whose moment stands apart from the other two (a rod's, a disc's)."""
    moments, axes = np.linalg.eigh(_symmetric(tensor))
    low, high = moments[1] - moments[0], moments[2] - moments[1]
    if max(low, high) <= 1e-6 * moments[2]:
        return None  # isotropic
    return ("least", axes[:, 0]) if low > high else ("greatest", axes[:, 2])


def _entries(tensor: NDArray[np.float64], names: Sequence[str] | None = None) -> str:
    """``ixx 0.0002, iyy 0.0076, izz 0.0076``: the named entries, else the moments and any
    non-zero product."""
    lookup = dict(zip(ATTRIBUTES, _INDEX, strict=True))
    if names is None:
        scale = np.abs(np.diag(tensor)).max()
        names = [n for n, (i, j) in lookup.items() if i == j or abs(tensor[i, j]) > 1e-9 * scale]
    return ", ".join(f"{n} {fmt(tensor[lookup[n]], 5)}" for n in names)


def _percent(residual: float) -> str:
    return f"{fmt(max(residual * 100, 0.01), 2)} %"


def _word(
    chosen: _Candidate,
    declared: MassProperties,
    expected: MassProperties,
    axes: NDArray[np.float64],
    geometry: str,
) -> tuple[str, str, str, dict[str, Any]]:
    """(summary, detail, help, data) of a chosen candidate."""
    corrected = chosen.corrected.inertia
    within = f"within {_percent(chosen.residual)}"
    if chosen.code == "IN060":
        point = chosen.extra
        offset = declared.com - point
        term = shift_tensor(declared.mass, offset)
        i = int(np.argmax(np.diag(term)))
        name = ATTRIBUTES[(0, 3, 5)[i]]
        distance = math.sqrt(max(float(offset @ offset - offset[i] ** 2), 0.0))
        where = chosen.label or "the point"
        summary = (
            f"the declared inertia is the tensor about {where} {_vector(point)}, not about the "
            f"COM {_vector(declared.com)}"
        )
        detail = (
            f"{name} {fmt(declared.inertia[i, i], 5)} = {fmt(corrected[i, i], 5)} + "
            f"{fmt(declared.mass, 5)} kg × ({fmt(distance, 4)} m)²; about the COM it is "
            f"{fmt(corrected[i, i], 5)}, and the {geometry} gives {fmt(expected.inertia[i, i], 5)}"
        )
        help = (
            "write the tensor about the centre of mass: subtract the parallel-axis term "
            f"m (|d|² E - d dᵀ) with d = {_vector(offset)} m ({_entries(corrected)})"
        )
        return summary, detail, help, chosen.data
    if chosen.code == "IN061":
        written = axes.T @ declared.inertia @ axes
        right = axes.T @ expected.inertia @ axes
        scale = np.abs(np.diag(written)).max()
        names = [
            n
            for n, (i, j) in zip(ATTRIBUTES, _INDEX, strict=True)
            if i != j and max(abs(written[i, j]), abs(right[i, j])) > 1e-9 * scale
        ]
        summary = (
            "the products of inertia have the opposite sign: written as +∫xy dm (or copied "
            "from a mirror-image part), where URDF's convention is ixy = -∫xy dm"
        )
        detail = (
            f"written {_entries(written, names)}; the {geometry} gives {_entries(right, names)} "
            f"(negated, they match {within})"
        )
        return summary, detail, "negate ixy, ixz and iyz", {}
    if chosen.code == "IN062":
        rotation = chosen.extra
        inertial_axes = rotation @ axes
        rpy = matrix_rpy(inertial_axes)
        rpy_text = " ".join(fmt(v, 5) for v in rpy)
        distinct = _distinct_axis(expected.inertia)
        where = ""
        if distinct is not None:
            kind, axis = distinct
            # the axis the declared values put there: the geometry's, turned back
            assumed = rotation.T @ axis
            where = (
                f"; it puts the axis of {kind} inertia along {_axis_text(assumed)}, the "
                f"{geometry} has it along {_axis_text(axis)}"
            )
        frame = f": {chosen.label}" if chosen.label else ""
        summary = f"the declared inertia is written for other axes{frame}{where}"
        detail = (
            f"declared {_entries(declared.inertia)}; in the link axes it is "
            f"{_entries(corrected)}, the geometry's {within}"
        )
        help = (
            f'set <inertial><origin rpy="{rpy_text}"/> or write the tensor in the link axes '
            f"({_entries(corrected)})"
        )
        data = {
            "rotation": [[float(v) for v in row] for row in rotation],
            "rpy": [float(v) for v in rpy],
            "frame": chosen.label or None,
        }
        return summary, detail, help, data
    if chosen.code == "IN063":
        factor, unit, mass_factor = (chosen.data[k] for k in ("factor", "unit", "mass_factor"))
        i = int(np.argmax(np.diag(declared.inertia)))
        name = ATTRIBUTES[(0, 3, 5)[i]]
        parts = []
        if mass_factor != 1.0:
            parts.append(f"the mass {fmt(declared.mass, 5)} is in grams")
        if factor > 1.0:
            parts.append(f"the tensor is in {unit}, not kg·m²")
        elif factor < 1.0:
            parts.append(f"the tensor was divided by {fmt(1 / factor, 5)} as if it were in {unit}")
        summary = "a unit slip: " + " and ".join(parts)
        detail = (
            f"{name} {fmt(declared.inertia[i, i], 5)} is {fmt(factor * mass_factor, 5)} times "
            f"the {fmt(expected.inertia[i, i], 4)} the {geometry} gives; converted it is "
            f"{fmt(corrected[i, i], 4)} (all six match {within})"
        )
        todo = []
        if mass_factor != 1.0:
            todo.append(f"write the mass in kg ({fmt(chosen.corrected.mass, 5)})")
        if factor != 1.0:
            todo.append(f"divide the tensor by {fmt(factor, 5)} ({_entries(corrected)})")
        return summary, detail, " and ".join(todo), chosen.data
    # IN064
    _, order = chosen.extra
    written = axes.T @ declared.inertia @ axes
    values = [written[i, j] for i, j in _INDEX]
    assignment = {ATTRIBUTES[k]: ATTRIBUTES[int(order[k])] for k in range(6) if order[k] != k}
    changed = [k for k in range(6) if values[int(order[k])] != values[k]]
    pairs = {frozenset((k, int(order[k]))) for k in changed}
    if len(changed) == 2 and len(pairs) == 1:
        a, b = (ATTRIBUTES[k] for k in changed)
        how = f"{a} and {b} are swapped"
    else:
        how = ", ".join(
            f"{ATTRIBUTES[int(order[k])]}'s value is in {ATTRIBUTES[k]}" for k in changed
        )
    summary = f"the six inertia values are in the wrong attributes: {how}"
    right = corrected if not np.any(axes != np.eye(3)) else axes.T @ corrected @ axes
    detail = (
        f"written {', '.join(f'{ATTRIBUTES[k]} {fmt(values[k], 4)}' for k in changed)}; "
        f"reassigned, {_entries(right, [ATTRIBUTES[k] for k in changed])} match the {geometry} "
        f"{within}"
    )
    help = f"write {_entries(right)}"
    return summary, detail, help, {"assignment": assignment}


# --- entry points --------------------------------------------------------------------------------


def diagnose(
    declared: MassProperties,
    expected: MassProperties,
    *,
    points: Sequence[tuple[str, ArrayLike]] = (),
    rotations: Sequence[tuple[str, ArrayLike]] = (),
    axes: ArrayLike | None = None,
    hull: Hull | None = None,
    volume: float | None = None,
    geometry: str = "geometry",
    tolerance: float = TOLERANCE,
    better: float = BETTER,
) -> Diagnosis | None:
    """
    The slip that explains ``declared`` against ``expected``, or ``None``.

    Parameters
    ----------
    declared : MassProperties
      The declared values, link frame (tensor in link axes, about the declared COM).
    expected : MassProperties
      The geometry's values for the declared mass, link frame, about the geometry's COM.
    points : sequence of (str, (3,) float)
      Named reference points in the link frame, m (``("the link origin", (0, 0, 0))``): IN060
      prefers them to a point solved for.
    rotations : sequence of (str, (3, 3) float)
      Named frames whose axes the tensor may have been written in (columns: their axes in link
      coordinates), e.g. a shape's ``<origin rpy>``: IN062 prefers them.
    axes : (3, 3) float, optional
      The rotation of ``<inertial><origin rpy>``: the axes the six values are written in (IN061
      and IN064 work on the written values). Default: the link axes.
    hull : Hull, optional
      A convex set containing the geometry: a point is only solved for when no distribution
      inside it has the declared tensor. Without one, only named points are tried.
    volume : float, optional
      The geometry's volume, m³: unit slips are judged by the density it gives.
    geometry : str
      How messages name the geometry (``collision cylinder (r = 0.05 m, l = 0.3 m)``).
    tolerance, better : float
      A hypothesis explains the numbers when the corrected tensor deviates from the geometry's
      by at most ``tolerance`` and ``better`` times less than the declared one.
    """
    if not (declared.mass > 0 and math.isfinite(declared.mass)):
        return None
    if not (np.isfinite(declared.inertia).all() and np.isfinite(declared.com).all()):
        return None
    try:
        metric = _Metric(expected.inertia)
    except np.linalg.LinAlgError:
        return None  # the geometry's tensor is not positive definite: nothing to compare with
    plain = float(metric(declared.inertia))
    if plain < MIN_MISMATCH:
        return None
    frame = np.eye(3) if axes is None else np.asarray(axes, dtype=np.float64)
    candidates = (
        _unit_slips(declared, expected, volume)
        + _sign_flip(declared, frame, metric)
        + _other_points(declared, expected, points, hull, metric)
        + _other_axes(declared, expected, rotations, metric)
        + _transposed(declared, frame, metric, tolerance)
    )
    chosen = _choose(candidates, tolerance)
    if chosen is None or chosen.residual * better > plain:
        return None
    summary, detail, help, data = _word(chosen, declared, expected, frame, geometry)
    return Diagnosis(
        chosen.code, summary, detail, help, chosen.corrected, chosen.residual, plain, data
    )


def _origin_rotation(origin: model.Origin) -> NDArray[np.float64] | None:
    rpy = origin.rpy
    if not isinstance(rpy, tuple) or not all(isinstance(v, float) for v in rpy):
        return None
    return rpy_matrix(rpy)


def _snapped(rotation: NDArray[np.float64]) -> NDArray[np.float64]:
    """An axis permutation when ``rotation`` is one up to a rounded pi (``rpy="0 1.5708 0"``)."""
    rounded = np.round(rotation)
    if np.abs(rotation - rounded).max() <= 1e-4 and np.allclose(rounded @ rounded.T, np.eye(3)):
        return rounded
    return rotation


def _rpy_text(rpy: tuple) -> str:
    return " ".join(fmt(v, 5) for v in rpy)


def _named_frames(link: LinkAnalysis) -> tuple[list, list]:
    """Reference points (link origin, child joints, mesh origins) and shape frames of a link."""
    points: list[tuple[str, ArrayLike]] = [("the link origin", (0.0, 0.0, 0.0))]
    for joint in link.children:
        xyz = joint.origin.xyz
        if isinstance(xyz, tuple) and all(isinstance(v, float) for v in xyz):
            points.append((f"the origin of joint `{joint.name}`", xyz))
    rotations: list[tuple[str, ArrayLike]] = []
    from inertia_kit.analysis.describe import TABLE, describe_geometry

    for shape in (*link.link.collisions, *link.link.visuals):
        what = f"the {shape.kind} {describe_geometry(shape.geometry, TABLE).split(' ')[0]}"
        xyz = shape.origin.xyz
        mesh = isinstance(shape.geometry, model.Mesh) and isinstance(xyz, tuple)
        if mesh and all(isinstance(v, float) for v in xyz) and any(xyz):  # type: ignore[union-attr]
            points.append((f"the origin of {what} `{shape.geometry.filename}`", xyz))
        rotation = _origin_rotation(shape.origin)
        if rotation is not None and not np.allclose(rotation, np.eye(3)):
            rpy = _rpy_text(shape.origin.rpy)  # type: ignore[arg-type]
            rotations.append((f'{what}\'s own axes (<origin rpy="{rpy}">)', _snapped(rotation)))
    return points, rotations


_CACHE: weakref.WeakKeyDictionary[LinkAnalysis, dict[tuple, Diagnosis | None]] = (
    weakref.WeakKeyDictionary()
)


def diagnose_basis(link: LinkAnalysis, basis: Geometry, loose: bool = False) -> Diagnosis | None:
    """
    The diagnosis of a link's declared tensor against one of its :attr:`LinkAnalysis.bases`
    (``basis`` set), whether or not it agrees with the other; cached per link and basis.

    ``loose``: what the tensor most likely is when it is not explained within
    :data:`TOLERANCE`: a match within :data:`LOOSE` (a real part is not the uniform solid of
    its collision shapes), only by named points, rotations, signs, units and transpositions (no
    point solved for). IN020 names it in its message; nothing is corrected from it.
    """
    cache = _CACHE.setdefault(link, {})
    key = (basis.kind, loose)
    if key not in cache:
        cache[key] = _diagnose_basis(link, basis, loose)
    return cache[key]


def _diagnose_basis(link: LinkAnalysis, basis: Geometry, loose: bool) -> Diagnosis | None:
    declared = link.declared
    if declared is None or not declared.mass > 0:
        return None
    expected = basis.at_mass(declared.mass)
    if expected is None:
        return None
    inertial = link.link.inertial
    axes = None if inertial is None else _origin_rotation(inertial.origin)
    points, rotations = _named_frames(link)
    diagnosis = diagnose(
        declared,
        expected,
        points=points,
        rotations=rotations,
        axes=axes,
        hull=None if loose else basis.hull,
        volume=basis.volume,
        geometry=basis.describe(),
        tolerance=LOOSE if loose else TOLERANCE,
        better=LOOSE_BETTER if loose else BETTER,
    )
    return None if diagnosis is None else replace(diagnosis, basis=basis.kind)


def diagnose_link(link: LinkAnalysis) -> Diagnosis | None:
    """
    The diagnosis of a link's declared tensor (see the module docstring), or ``None``: no
    declared value, no usable geometry, a tensor that agrees with the collision or the visual
    geometry (within :data:`MIN_MISMATCH`), or nothing that explains it. The collision
    geometry's diagnosis is preferred.
    """
    declared = link.declared
    if declared is None or not declared.mass > 0:
        return None
    found = []
    for basis in link.bases:
        expected = basis.at_mass(declared.mass)
        if expected is None:
            return None
        try:
            if deviation(declared.inertia, expected.inertia) < MIN_MISMATCH:
                return None  # agrees with one basis: nothing to explain
        except np.linalg.LinAlgError:
            return None
        diagnosis = diagnose_basis(link, basis)
        if diagnosis is not None:
            found.append(diagnosis)
    return found[0] if found else None
