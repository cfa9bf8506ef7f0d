"""analysis.forensics.transposed (IN064): the six values in the wrong attributes."""

from __future__ import annotations

import numpy as np
import pytest
from forensic_cases import BOX, EYE, MASS, box_case, box_tensor, case_of, props
from hypothesis import given
from hypothesis import strategies as st

from inertia_kit.analysis.forensics import transposed
from inertia_kit.analysis.forensics.diagnosis import diagnose
from inertia_kit.analysis.forensics.transposed import ORDERS, distinct_orders
from inertia_kit.physics.frames import rpy_matrix
from inertia_kit.physics.tensor_names import INDEX, TENSOR


def values_to_tensor(ixx, ixy, ixz, iyy, iyz, izz):
    return np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])


def test_two_products_swapped():
    turned = rpy_matrix([0.0, 0.0, np.pi / 6])
    right = box_tensor(12.0, 0.4, 0.3, 0.2, turned)
    ixx, iyy, izz, ixy = right[0, 0], right[1, 1], right[2, 2], right[0, 1]
    declared = values_to_tensor(ixx, 0.0, ixy, iyy, 0.0, izz)
    found = diagnose(props(12.0, declared), props(12.0, right), volume=0.024)
    assert found is not None and found.code == "IN064"
    assert "ixy and ixz are swapped" in found.wording.summary
    assert found.wording.data["assignment"] == {"ixy": "ixz", "ixz": "ixy"}
    np.testing.assert_allclose(found.corrected.inertia, right)


def test_values_listed_moments_first_read_in_urdf_order():
    """MuJoCo's fullinertia order (Ixx Iyy Izz Ixy Ixz Iyz) pasted into ixx ixy ixz iyy iyz izz."""
    turned = rpy_matrix([0.4, 0.3, 0.5])
    right = box_tensor(MASS, *BOX, turned)
    listed = [right[0, 0], right[1, 1], right[2, 2], right[0, 1], right[0, 2], right[1, 2]]
    declared = values_to_tensor(*listed)  # not even positive definite
    assert np.linalg.eigvalsh(declared)[0] < 0
    found = box_case(declared, rotation=turned)
    assert found is not None and found.code == "IN064"
    np.testing.assert_allclose(found.corrected.inertia, right)


# values with ties: exact repeats, zeros of either sign, and values that differ only below the
# 15th decimal (one value once rounded)
_BASES = st.sampled_from([0.0, -0.0, 1e-3, -2.5e-4, 0.0123, 1.0, 7.0e-6])
_VALUES = st.lists(
    st.one_of(
        _BASES,
        st.builds(lambda b, k: b + k * 1e-17, _BASES, st.integers(-3, 3)),
        st.floats(-1.0, 1.0, allow_nan=False, width=64),
    ),
    min_size=6,
    max_size=6,
)


@given(_VALUES)
def test_distinct_orders_are_those_of_unique_on_the_rounded_rows(values):
    values = np.array(values)
    expected = np.unique(np.round(values[ORDERS], 15), axis=0, return_index=True)[1]
    np.testing.assert_array_equal(distinct_orders(values), expected)


def test_distinct_orders_of_a_diagonal_tensor():
    """Three moments and three zero products (of either sign): 6!/3! distinct reassignments."""
    found = distinct_orders(np.array([1.0, 0.0, -0.0, 2.0, 0.0, 3.0]))
    assert len(found) == 120
    assert ORDERS[found[0]].tolist() == [1, 2, 4, 0, 3, 5]  # the zeros first, then 1, 2, 3


def _search_one_by_one(case, tolerance):
    """The search as first written: every reassignment built, scored and tested."""
    written = case.written
    values = np.array([written[INDEX[name]] for name in TENSOR])
    candidates = values[ORDERS]
    _, unique = np.unique(np.round(candidates, 15), axis=0, return_index=True)
    own = np.linalg.eigvalsh(written)
    found = []
    for order, row in zip(ORDERS[unique], candidates[unique], strict=True):
        if np.all(row == values):
            continue
        tensor = values_to_tensor(*row)
        if np.abs(np.linalg.eigvalsh(tensor) - own).max() <= 1e-9 * np.abs(own).max():
            continue
        in_link = case.axes @ tensor @ case.axes.T
        residual = float(case.metric(in_link))
        if residual <= tolerance:
            found.append((tuple(int(k) for k in order), residual, in_link))
    return found


@pytest.mark.parametrize("seed", range(8))
@pytest.mark.parametrize("tolerance", [0.02, 0.1, np.inf])
def test_search_finds_what_scoring_each_reassignment_alone_finds(seed, tolerance):
    turned = rpy_matrix(np.random.default_rng(seed).uniform(-3, 3, 3))
    right = box_tensor(MASS, *BOX, turned if seed % 2 else EYE)  # odd seeds: with products
    values = [right[INDEX[name]] for name in TENSOR]
    swapped = values_to_tensor(*np.array(values)[ORDERS[seed * 89 + 1]])
    axes = rpy_matrix([0.0, 0.0, 0.3]) if seed % 4 == 3 else EYE
    case = case_of(props(MASS, axes @ swapped @ axes.T), props(MASS, right), axes)
    found = transposed.search(case, tolerance)
    expected = _search_one_by_one(case, tolerance)
    assert [(c.order, c.residual) for c in found] == [(o, r) for o, r, _ in expected]
    for candidate, (_, _, in_link) in zip(found, expected, strict=True):
        assert np.array_equal(candidate.corrected.inertia, in_link)
