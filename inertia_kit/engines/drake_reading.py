"""
How Drake's URDF parser reads what it reads, and the words it says about it (Drake 1.51.1, the
PyPI wheel; ``tests/engines/test_drake_matrix.py`` checks every message against the real
``pydrake``).

- Numbers: ``ConvertToVector`` reads an attribute with ``std::istringstream >> double`` until a
  read fails: ``2kg`` is 2, ``0x10`` is 0, ``1,5`` is 1; ``nan``, ``inf``, ``1e999`` and ``1e``
  read nothing. A scalar must give exactly one number, a vector exactly three.
- Inertia: ``RotationalInertia::CouldBePhysicallyValid`` (principal moments ≥ −ε and
  A + B + ε ≥ C, ε = 16·2⁻⁵²·max(1, trace/2)) and its report, matrix and principal moments
  written as ``fmt`` writes doubles.
"""

from __future__ import annotations

import math
import re

import numpy as np
from numpy.typing import NDArray

VERSION = "1.51.1"

_SPACE = " \t\n\v\f\r"
_MANTISSA = re.compile(r"[+-]?[0-9]*(?:\.[0-9]*)?")
_EXPONENT = re.compile(r"[eE][+-]?[0-9]*")
_DIGIT = re.compile(r"[0-9]")

EPSILON = float(np.finfo(np.float64).eps)


def read_numbers(text: str) -> list[float]:
    """
    The numbers ``std::istringstream >> double`` reads from ``text`` one after the other (the
    classic locale), stopping at the first read that fails: libstdc++ gathers a sign, digits, one
    decimal point and, after a digit, an exponent, and fails when ``strtod`` does not take all of
    it or overflows (an underflow reads as 0 or a subnormal).
    """
    values: list[float] = []
    position, end = 0, len(text)
    while True:
        while position < end and text[position] in _SPACE:
            position += 1
        stop = _MANTISSA.match(text, position).end()  # type: ignore[union-attr]
        if _DIGIT.search(text, position, stop):
            exponent = _EXPONENT.match(text, stop)
            if exponent:
                stop = exponent.end()
        try:
            value = float(text[position:stop])
        except ValueError:
            return values
        if math.isinf(value):
            return values
        values.append(value)
        position = stop


def scalar_error(attribute: str, text: str) -> str:
    """``ParseScalarAttribute``'s error for a value that is not exactly one number."""
    return f"Expected single value for attribute '{attribute}' got '{text}'"


def vector_error(attribute: str, text: str) -> str:
    """``ParseVectorAttribute``'s error for a value that is not exactly three numbers."""
    return f"Expected 3 values for attribute {attribute} got {text}"


def fmt_double(value: float) -> str:
    """A double as ``fmt::format("{}")`` writes it: the shortest round trip, no ``.0``."""
    text = repr(float(value))
    return text[:-2] if text.endswith(".0") else text


def fmt_eigen_row(values) -> str:
    """A row vector as Drake's ``fmt_eigen`` writes it: each right-aligned to the widest."""
    texts = [fmt_double(v) for v in values]
    width = max(len(t) for t in texts)
    return " ".join(t.rjust(width) for t in texts)


def principal_moments(tensor: NDArray[np.float64]) -> NDArray[np.float64]:
    """
    ``CalcPrincipalMomentsOfInertia``: the sorted diagonal when every product is within
    4ε·trace/2 of 0, else the eigenvalues (ascending).
    """
    tolerance = 4 * EPSILON * 0.5 * abs(_trace(tensor))
    products = (tensor[1, 0], tensor[2, 0], tensor[2, 1])
    if all(abs(p) <= tolerance for p in products):
        return np.sort(np.diag(tensor))
    return np.linalg.eigvalsh(tensor)


def _trace(tensor: NDArray[np.float64]) -> float:
    """The trace in Python floats: inf past double precision, as C++ sums it, and no warning."""
    return float(tensor[0, 0]) + float(tensor[1, 1]) + float(tensor[2, 2])


def could_be_physically_valid(tensor: NDArray[np.float64]) -> bool:
    """``RotationalInertia::CouldBePhysicallyValid`` for a (3, 3) tensor."""
    if not np.isfinite(tensor).all():
        return False
    epsilon = 16 * EPSILON * max(1.0, 0.5 * abs(_trace(tensor)))
    # Python floats: a sum past 1.8e308 is inf, as in Drake's C++, without numpy's warning
    a, b, c = (float(m) for m in principal_moments(tensor))
    near_positive = a + epsilon >= 0 and b + epsilon >= 0 and c + epsilon >= 0
    return bool(near_positive and a + b + epsilon >= c and b + c + epsilon >= a)


def invalid_inertia_message(tensor: NDArray[np.float64]) -> str:
    """
    The exception ``MakeFromMomentsAndProductsOfInertia`` throws for a tensor that fails
    :func:`could_be_physically_valid`, as ``ParseSpatialInertia`` logs it (line breaks kept).
    """
    texts = [[fmt_double(tensor[i, j]) for j in range(3)] for i in range(3)]
    width = max(len(t) for row in texts for t in row)
    matrix = "".join("[" + "  ".join(t.rjust(width) for t in row) + "]\n" for row in texts)
    if not np.isfinite(tensor).all():
        report = "\nNon-finite moment or product of inertia detected in RotationalInertia."
    else:
        moments = principal_moments(tensor)
        report = "\nThe associated principal moments of inertia:\n" + "  ".join(
            fmt_double(m) for m in moments
        )
        if (moments < 0).any():
            report += "\nare invalid since at least one is negative."
        else:
            report += "\ndo not satisfy the triangle inequality."
    return (
        "While parsing inertia matrix: MakeFromMomentsAndProductsOfInertia(): The rotational "
        f"inertia\n{matrix}did not pass the test CouldBePhysicallyValid().{report}"
    )


# ``DRAKE_THROW_UNLESS(mass > 0)`` in UnitInertia::SetFromRotationalInertia, as the wheel prints
# it (the path and line are the build's: they change from one Drake release to the next)
NON_POSITIVE_MASS = (
    "While re-expressing as central inertia: Failure at bazel-out/k8-opt/bin/external/drake+/"
    "multibody/tree/_virtual_includes/unit_inertia/drake/multibody/tree/unit_inertia.h:104 in "
    "SetFromRotationalInertia(): condition 'mass > 0' failed."
)

# the Joint constructor and Joint::set_velocity_limits, as the wheel prints them
JOINT_LIMITS = (
    "Failure at bazel-out/k8-opt/bin/external/drake+/multibody/tree/_virtual_includes/"
    "multibody_tree_core/drake/multibody/tree/joint.h:159 in Joint(): condition "
    "'(pos_lower_limits.array() <= pos_upper_limits.array()).all()' failed."
)
VELOCITY_LIMITS = (
    "Failure at bazel-out/k8-opt/bin/external/drake+/multibody/tree/_virtual_includes/"
    "multibody_tree_core/drake/multibody/tree/joint.h:435 in set_velocity_limits(): condition "
    "'(lower_limits.array() <= upper_limits.array()).all()' failed."
)
FRICTION = (
    "A joint has specified a non-zero value for the 'friction' attribute of a joint/dynamics "
    "tag. MultibodyPlant does not currently support non-zero joint friction."
)

# SpatialInertia::SolidSphereWithDensity, when the stand-in sphere's radius underflows to 0
ZERO_RADIUS = "SolidSphereWithDensity(): radius is not positive and finite: 0."

# shape_specification.cc: DRAKE_THROW_UNLESS(std::isfinite(x) && x > 0, x), by shape and
# dimension, with the source line the wheel prints
_SHAPE_CHECKS = {
    ("Box", "width"): 110,
    ("Box", "depth"): 111,
    ("Box", "height"): 112,
    ("Capsule", "radius"): 129,
    ("Capsule", "length"): 130,
    ("Cylinder", "radius"): 194,
    ("Cylinder", "length"): 195,
    ("Sphere", "radius"): 309,
}


def shape_error(shape: str, dimension: str, value: float) -> str:
    """The ``geometry::<Shape>`` constructor's failure for a dimension out of range."""
    line = _SHAPE_CHECKS[(shape, dimension)]
    relation = ">=" if shape == "Sphere" else ">"
    return (
        f"Failure at external/drake+/geometry/shape_specification.cc:{line} in {shape}(): "
        f"condition 'std::isfinite({dimension}) && {dimension} {relation} 0' failed. "
        f"{dimension} = {_debug_double(value)}."
    )


def _debug_double(value: float) -> str:
    """A double as DRAKE_THROW_UNLESS prints it: like Python's ``repr`` (``0.0``, ``-1.0``)."""
    return repr(float(value))


def singular_hinge(inboard: str, outboard: str, rotates: bool, translates: bool) -> str:
    """``BodyNode::CalcArticulatedBodyHingeInertiaMatrixFactorization``'s error."""
    text = (
        "An internal mass matrix associated with the joint that connects body "
        f"{inboard} to body {outboard} is not positive-definite."
    )
    if rotates:
        text += (
            f" Since the joint allows rotation, ensure body {outboard} (combined with other "
            "outboard bodies) has reasonable non-zero moments of inertia about the joint "
            "rotation axes."
        )
    if translates:
        text += (
            f" Since the joint allows translation, ensure body {outboard} (combined with other "
            "outboard bodies) has a reasonable non-zero mass."
        )
    return text


def flatten(message: str) -> str:
    """
    A multi-line message on one line: every run of white space one space, none after ``[``
    (a matrix row ``[   0  0.01]`` reads ``[0 0.01]``).
    """
    return re.sub(r"\[ ", "[", " ".join(message.split()))
