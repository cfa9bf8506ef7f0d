"""engines.articulated: hinge inertias of the articulated-body algorithm, by closed forms."""

from __future__ import annotations

import numpy as np
import pytest

from inertia_kit.engines.articulated import Body, hinges, shift, spatial_inertia

Z = np.array([0.0, 0.0, 1.0])
X = np.array([1.0, 0.0, 0.0])
ORIGIN = np.zeros(3)


def rod(mass=1.0, com=(0.0, 0.0, 0.0), moments=(0.01, 0.01, 0.01)):
    return spatial_inertia(mass, np.array(com), np.diag(moments))


def body(name, parent, motion="revolute", axis=Z, origin=ORIGIN, inertia=None):
    return Body(name, parent, motion, axis, np.asarray(origin, float), inertia)


def test_spatial_inertia_about_the_origin_is_the_parallel_axis_theorem():
    m = spatial_inertia(2.0, np.array([0.0, 0.3, 0.0]), np.diag([0.1, 0.2, 0.3]))
    assert m[:3, :3] == pytest.approx(np.diag([0.1 + 2 * 0.09, 0.2, 0.3 + 2 * 0.09]))
    assert m[3:, 3:] == pytest.approx(2 * np.eye(3))
    assert np.allclose(m, m.T)


def test_shift_of_a_rigid_inertia_is_the_inertia_about_the_new_point():
    central = np.diag([0.1, 0.2, 0.3])
    at_com = spatial_inertia(2.0, np.zeros(3), central)
    offset = np.array([0.1, -0.2, 0.4])
    # about B, with the body's origin (its COM) at `offset` from B
    assert shift(at_com, offset) == pytest.approx(spatial_inertia(2.0, offset, central))


def test_hinge_of_a_body_about_its_axis():
    (hinge,) = hinges([body("a", None, inertia=rod())])
    assert not hinge.singular and hinge.smallest == pytest.approx(1.0)


@pytest.mark.parametrize(
    ("motion", "inertia", "singular"),
    [
        ("revolute", rod(0.0, moments=(0, 0, 0)), True),
        ("revolute", rod(1.0, moments=(0, 0, 0)), True),  # a point mass on the axis
        ("revolute", rod(1.0, com=(0.1, 0, 0), moments=(0, 0, 0)), False),
        ("prismatic", rod(1.0, moments=(0, 0, 0)), False),
        ("planar", rod(1.0, moments=(0, 0, 0)), True),
        ("free", rod(1.0, moments=(0, 0, 0)), True),
        ("free", rod(1.0), False),
        ("free", rod(1e-9, moments=(1e-20, 1e-20, 1e-20)), False),  # small, not singular
    ],
)
def test_one_body(motion, inertia, singular):
    (hinge,) = hinges([body("a", None, motion, inertia=inertia)])
    assert hinge.singular is singular


def test_massless_link_resolved_by_its_outboard_body_unless_on_the_same_axis():
    for axis, singular in ((X, False), (Z, True)):
        found = hinges(
            [
                body("a", None, inertia=np.zeros((6, 6))),
                body("b", "a", axis=axis, inertia=rod()),
            ]
        )
        assert [(h.body, h.singular) for h in found] == [("b", False), ("a", singular)]


def test_offset_outboard_joint_leaves_inertia_about_the_first_axis():
    found = hinges(
        [
            body("a", None, inertia=np.zeros((6, 6))),
            body("b", "a", origin=(0.2, 0, 0), inertia=rod()),
        ]
    )
    # b spins freely about its own axis but its mass still swings about a's: m·0.2²
    assert not found[1].singular


def test_welded_bodies_are_one_rigid_body():
    found = hinges(
        [
            body("a", None, inertia=np.zeros((6, 6))),
            body("tool", "a", "fixed", origin=(0.0, 0.0, 0.1), inertia=rod(moments=(0, 0, 0))),
        ]
    )
    assert [(h.body, h.singular) for h in found] == [("a", True)]  # the point is on a's axis


def test_order_is_deepest_first_then_depth_first():
    massless = np.zeros((6, 6))
    found = hinges(
        [
            body("a1", None, inertia=massless),
            body("b1", None, inertia=rod()),
            body("b2", "b1", inertia=massless),
            body("c", "b2", "fixed", inertia=massless),
        ]
    )
    assert [h.body for h in found] == ["b2", "a1", "b1"]


def test_a_body_past_double_precision_gives_no_hinge_value_and_no_exception():
    """Found by hypothesis: a 3.4e292 kg base made the floating joint's articulated inertia NaN,
    and the pseudo-inverse raised LinAlgError (an internal error in `--engine all`)."""
    import warnings

    unusable = np.full((6, 6), np.nan)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        found = hinges(
            [
                body("base", None, "free", inertia=unusable),
                body("arm", "base", inertia=rod()),
                body("tip", "arm", inertia=unusable),
            ]
        )
    # NaN from the tip reaches the arm and the base: nothing resists any of them
    assert [(hinge.body, hinge.smallest) for hinge in found] == [
        ("tip", 0.0),
        ("arm", 0.0),
        ("base", 0.0),
    ]


@pytest.mark.parametrize("tiny", [1e-300, 5e-324, 1e-160])
def test_a_moment_whose_square_underflows_is_judged_and_raises_nothing(tiny):
    """Issue 19: a free body whose izz is 1e-300 made each motion's scale 1e-300, their product
    0, the scaled hinge inertia inf, and LAPACK raised 'Eigenvalues did not converge' (an
    internal error in `--engine drake`). Scaled row by row, its hinge is judged: one rigid
    body resists each motion in proportion to itself (1), however small."""
    (hinge,) = hinges([body("arm", None, "free", inertia=rod(1.0, moments=(0.01, 0.01, tiny)))])
    assert hinge.smallest == pytest.approx(1.0, rel=1e-3) and not hinge.singular


@pytest.mark.parametrize("huge", [1e154, 1e300])
def test_a_scaled_hinge_past_double_precision_gives_no_claim(huge):
    """A hinge inertia whose scaled form leaves double precision says nothing (NaN, not
    singular) rather than raising."""
    (hinge,) = hinges([body("arm", None, "free", inertia=rod(huge, moments=(huge, 1.0, 1.0)))])
    assert not hinge.singular
