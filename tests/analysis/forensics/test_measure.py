"""analysis.forensics.measure: the deviation between two tensors."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from inertia_kit.analysis.forensics.measure import Metric, deviation


def test_deviation_is_relative_per_axis_with_a_floor():
    tensor = np.diag([1.0, 2.0, 3.0])
    assert deviation(tensor, tensor) == 0.0
    # twice the tensor: (I) / (I + 5 % of the largest) about the largest axis
    assert deviation(2 * tensor, tensor) == pytest.approx(3.0 / (3.0 + 0.15))
    # a rounding error of a large entry counts against the floor, not a thin axis's moment
    thin = np.diag([1.0, 1.0, 0.001])
    assert deviation(thin + np.diag([0, 0, 0.001]), thin) < 0.05


_ENTRY = st.floats(-10.0, 10.0, allow_nan=False, width=64)
_MATRIX = st.lists(_ENTRY, min_size=9, max_size=9).map(lambda v: np.reshape(v, (3, 3)))


@given(_MATRIX, st.lists(_MATRIX, min_size=1, max_size=30))
def test_one_call_on_stacked_tensors_gives_each_deviation_to_the_bit(root, tensors):
    """The searches score their candidates in one call: each result is the single call's."""
    reference = root @ root.T + 1e-3 * np.eye(3)  # positive definite
    stacked = Metric(reference)(np.array(tensors))
    assert stacked.shape == (len(tensors),)
    for tensor, value in zip(tensors, stacked, strict=True):
        assert value == deviation(tensor, reference)


@given(_MATRIX, st.lists(_MATRIX, min_size=1, max_size=30), st.floats(1e-12, 1e12))
def test_lower_bound_is_at_most_each_deviation_as_computed(root, tensors, unit):
    """The searches skip the candidates whose bound is above the tolerance: it must never be
    above the deviation itself (less the ~1e-13 of rounding that BOUND_MARGIN covers)."""
    reference = (root @ root.T + 1e-3 * np.eye(3)) * unit
    metric = Metric(reference)
    stacked = np.array(tensors) * unit
    bounds = metric.lower_bound(stacked)
    assert np.all(bounds <= metric(stacked) * (1 + 1e-12))


def test_lower_bound_is_the_ratio_about_the_link_axes():
    reference = np.diag([1.0, 2.0, 4.0])
    # about z: 2 / (4 + 5 % of 4)
    assert Metric(reference).lower_bound(np.diag([1.0, 2.0, 6.0])[None]) == [2.0 / 4.2]
    # diagonal tensors: the bound is the deviation
    tensor = np.diag([1.5, 2.0, 3.0])
    assert Metric(reference).lower_bound(tensor[None])[0] == pytest.approx(
        deviation(tensor, reference)
    )


def test_lower_bound_skips_nothing_where_the_deviation_could_overflow():
    metric = Metric(np.eye(3))
    assert metric.lower_bound(np.diag([1e301, 1.0, 1.0])[None]).tolist() == [0.0]
    assert metric.lower_bound(np.diag([np.nan, 1.0, 1.0])[None]).tolist() == [0.0]


_TOLERANCES = st.sampled_from([0.02, 0.1, float(np.expm1(0.92))])


_MOMENT = st.floats(1e-3, 10.0)


@given(st.lists(_MOMENT, min_size=3, max_size=3), st.floats(0.9, 1.2), _TOLERANCES, _MATRIX)
def test_no_tensor_within_the_tolerance_has_an_entry_beyond_the_reach(
    moments, stretch, tolerance, turn
):
    """The searches that keep the declared magnitudes are skipped past ``reach``: a tensor with a
    larger entry deviates beyond the tolerance, so the skip drops no candidate the search would
    keep. Here the reference's largest moment is stretched about the bound (either side), in
    its own axes, where an entry is that moment; and the same, both turned (entries smaller)."""
    reference = np.diag(moments)
    largest = max(moments)
    stretched = np.diag(
        [m * (1.0 + tolerance * 1.05) * stretch if m == largest else m for m in moments]
    )
    rotation = np.linalg.qr(turn + 4.0 * np.eye(3))[0]  # orthonormal
    for axes in (np.eye(3), rotation):
        metric = Metric(axes @ reference @ axes.T)
        tensor = axes @ stretched @ axes.T
        if np.abs(tensor).max() > metric.reach(tolerance):
            assert metric(tensor[None])[0] > tolerance


def test_reach_of_a_sphere():
    """Within 2 % of the unit tensor (floor 5 %), no moment exceeds 1 + 0.02 * 1.05."""
    metric = Metric(np.eye(3))
    assert metric.reach(0.02) == pytest.approx(1.021, rel=1e-5)
    assert metric(np.diag([1.0, 1.0, 1.0215])[None])[0] > 0.02
