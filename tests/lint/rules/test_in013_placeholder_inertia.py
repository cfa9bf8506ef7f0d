"""IN013 placeholder-inertia: isotropic tensors on anisotropic shapes, and copied tensors."""

from __future__ import annotations

import math

import numpy as np
import pytest
from kit.moments import box_moments
from kit.urdf import (
    box,
    collision,
    inertial,
    joint,
    link,
    moving,
    robot,
    sphere,
    visual,
)

from inertia_kit.analysis.tensors import compare_tensors
from inertia_kit.physics.formatting import fmt


def on_base(**bodies: str) -> str:
    """Each link (``name=body``) on a revolute joint of its own from a massless base."""
    parts = [link("base")]
    for name, body in bodies.items():
        parts += [joint("base", name), link(name, body)]
    return robot(*parts)


def in013(lint, text, **options):
    kw = {"options": {"IN013": options}} if options else {}
    return [f for f in lint(text, "IN013", **kw) if f.code == "IN013"]


def test_isotropic_tensor_on_a_long_box(lint):
    (finding,) = in013(lint, moving(inertial(1.8, 0.0045) + collision(box(0.1, 0.1, 0.18))))
    ixx, iyy, izz = box_moments(1.8, (0.1, 0.1, 0.18))
    assert finding.message == (
        "link `arm`: ixx = iyy = izz = 0.0045 kg·m² is an isotropic placeholder"
    )
    assert len(finding.message) <= 100
    assert f"1 : {fmt(iyy / izz, 3)} : {fmt(ixx / izz, 3)}" in finding.detail
    assert f"ixx = {fmt(ixx, 4)}, iyy = {fmt(iyy, 4)}, izz = {fmt(izz, 4)}" in finding.detail
    assert "its collision box (0.1 × 0.1 × 0.18 m)" in finding.detail
    assert finding.expected["mass"] == 1.8
    assert finding.expected["ixx"] == pytest.approx(ixx)
    assert finding.expected["izz"] == pytest.approx(izz)
    assert finding.severity.name == "WARNING"


@pytest.mark.parametrize(
    "geometry",
    [collision(sphere(0.05)), collision(box(0.1, 0.1, 0.1)), collision(box(0.1, 0.1, 0.14))],
    ids=["sphere", "cube", "near-cube"],
)
def test_isotropic_tensor_on_a_round_shape_is_right(lint, geometry):
    assert in013(lint, moving(inertial(1.0, 0.001) + geometry, name="ball")) == []


def test_anisotropy_option(lint):
    text = moving(inertial(1.8, 0.0045) + collision(box(0.1, 0.1, 0.18)))
    ixx, _, izz = box_moments(1.8, (0.1, 0.1, 0.18))
    assert in013(lint, text, anisotropy=ixx / izz + 0.01) == []
    assert len(in013(lint, text, anisotropy=ixx / izz - 0.01)) == 1


def test_expected_values_in_the_written_axes(lint):
    # the inertia axes turned 90° about y: the box's x and z moments swap
    body = inertial(1.8, 0.0045, rpy=f"0 {math.pi / 2} 0") + collision(box(0.1, 0.1, 0.18))
    (finding,) = in013(lint, moving(body))
    ixx, _, izz = box_moments(1.8, (0.1, 0.1, 0.18))
    assert finding.expected["ixx"] == pytest.approx(izz)
    assert finding.expected["izz"] == pytest.approx(ixx)


def test_copied_tensor_flags_the_copy_not_the_original(lint):
    moments = box_moments(2.0, (0.1, 0.1, 0.3))
    # the six values copied, the mass the hand's own (a whole block copied is IN066's)
    text = on_base(
        upper=inertial(2.0, *moments) + collision(box(0.1, 0.1, 0.3)),
        hand=inertial(1.5, *moments) + collision(box(0.06, 0.06, 0.06)),
    )
    (finding,) = in013(lint, text)
    assert finding.link == "hand" and "those of link `upper`" in finding.detail
    cube, _, _ = box_moments(1.5, (0.06, 0.06, 0.06))
    spread = max(moments) / cube
    assert finding.message == (
        f"link `hand`: `<inertia>` copied from `upper`, a different body (×{fmt(spread, 3)})"
    )
    assert len(finding.message) <= 100
    assert f"differ by a factor of {fmt(spread, 3)}" in finding.detail
    assert finding.expected["ixx"] == pytest.approx(cube)
    assert f"ixx = {fmt(cube, 4)}" in finding.detail


def test_identical_and_turned_parts_share_a_tensor(lint):
    moments = box_moments(2.0, (0.1, 0.1, 0.3))
    turned = collision(box(0.1, 0.1, 0.3), rpy="0 0 1.5707963267948966")
    text = on_base(
        left=inertial(2.0, *moments) + collision(box(0.1, 0.1, 0.3)),
        right=inertial(2.0, *moments) + turned,
        spare=inertial(2.0, *moments) + collision(box(0.1, 0.1, 0.3)),
    )
    assert in013(lint, text) == []
    assert lint(text, "IN066") == []


def test_a_slipped_mass_among_identical_parts_is_named_on_it(lint):
    # three identical parts sharing six values (twice their 2 kg box's, as CAD parts with a
    # dense motor have: within OWNER_FIT), the first with its mass tripled: at 6 kg its box
    # fits the values best, but the other two agree with each other, so the first holds
    # values that cannot fit it
    moments = box_moments(4.0, (0.1, 0.1, 0.3))
    text = on_base(
        first=inertial(6.0, *moments) + collision(box(0.1, 0.1, 0.3)),
        second=inertial(2.0, *moments, xyz=(0, 0, 0.01)) + collision(box(0.1, 0.1, 0.3)),
        third=inertial(2.0, *moments, xyz=(0, 0, 0.02)) + collision(box(0.1, 0.1, 0.3)),
    )
    (finding,) = in013(lint, text)
    assert finding.link == "first" and "those of link `second`" in finding.detail
    assert "it declares 3 times `second`'s mass on a shape alike per kilogram" in finding.detail


def test_a_pair_that_fits_alike_names_neither(lint):
    # UR5e's two wrists share a tensor (1.6 times their box's, a real part's fit); the first's
    # mass tripled leaves it at a factor of 1.9 from its geometry: both fit as real parts do,
    # neither outvotes the other, and the file cannot say which mass is wrong
    size = (0.1, 0.1, 0.2)
    moments = [1.6 * m for m in box_moments(1.2, size)]
    text = on_base(
        first=inertial(3.6, *moments) + collision(box(*size)),
        second=inertial(1.2, *moments) + collision(box(*size)),
    )
    assert in013(lint, text) == []


def test_a_centre_of_mass_carried_along_counts_for_the_owner(lint):
    # Baxter's shape: a whole block whose tensor fits one link (1.3 times its box's) but whose
    # centre of mass lies 60 % of that link's size from its centroid, and which sits at the
    # centroid of the other (a cube, its tensor 6 times off): the centre of mass and the
    # tensor point at different owners, so no link is named the copy (IN021 and IN020 judge
    # each link)
    moments = [1.3 * m for m in box_moments(2.0, (0.1, 0.1, 0.3))]
    block = inertial(2.0, *moments, xyz=(0, 0, 0.18))
    text = on_base(
        long=block + collision(box(0.1, 0.1, 0.3)),
        cube=block + collision(box(0.1, 0.1, 0.1), xyz=(0, 0, 0.18)),
    )
    assert in013(lint, text) == []
    assert lint(text, "IN066") == []


def test_a_link_whose_visual_part_fits_the_values_holds_no_copy(lint):
    # GR3's upper arm roll link: a 5 cm collision sphere stands in for the part, the values
    # are its visual box's; the same six values on a forearm box they fit within a factor of
    # 1.5 make the forearm the best fit by collision, but the upper arm's own part holds them
    upper = (0.06, 0.06, 0.3)
    moments = box_moments(2.0, upper)
    text = on_base(
        upper=inertial(2.0, *moments) + collision(sphere(0.05)) + visual(box(*upper)),
        fore=inertial(2.0, *moments, xyz=(0, 0, 0.01)) + collision(box(0.06, 0.06, 0.24)),
    )
    assert "upper" not in [f.link for f in in013(lint, text)]


def test_a_placeholder_on_every_link_keeps_the_best_fit_as_original(lint):
    # about 1 kg·m² on a 5 kg chassis and on four identical 0.25 kg motors (not isotropic:
    # the copy is judged, not the isotropy): the motors agree with each other, but the values
    # fit none of them as a real part; the chassis they fit best is the original
    chassis = inertial(5.0, 1.0, 1.0, 0.9) + collision(box(0.3, 0.2, 0.1))
    motor = inertial(0.25, 1.0, 1.0, 0.9) + collision(box(0.04, 0.04, 0.08))
    text = on_base(chassis=chassis, m1=motor, m2=motor, m3=motor, m4=motor)
    assert sorted(f.link for f in in013(lint, text)) == ["m1", "m2", "m3", "m4"]


def test_copy_factor_option(lint):
    moments = box_moments(2.0, (0.1, 0.1, 0.3))
    text = on_base(
        upper=inertial(2.0, *moments) + collision(box(0.1, 0.1, 0.3)),
        lower=inertial(2.5, *moments) + collision(box(0.1, 0.1, 0.2)),
    )
    spread = moments[0] / box_moments(2.5, (0.1, 0.1, 0.2))[0]
    assert in013(lint, text) == []  # 1.8 apart: within the default 2
    assert [f.link for f in in013(lint, text, copy_factor=spread - 0.05)] == ["lower"]


def test_placeholder_on_a_negligible_welded_frame(lint):
    body = inertial(5.0, *box_moments(5.0, (0.2, 0.2, 0.5))) + collision(box(0.2, 0.2, 0.5))
    frame = joint("torso", "cam", "fixed") + link(
        "cam", inertial(0.001, 1e-8), collision(box(0.01, 0.01, 0.1))
    )
    text = moving(body, name="torso", extra=frame)
    assert in013(lint, text) == []


def test_factor_is_the_largest_moment_ratio_about_any_axis():
    """What IN013 measures copies with: the largest ratio either way, about any axis."""
    a = [[2.0, 0, 0], [0, 1.0, 0], [0, 0, 1.0]]
    b = [[1.0, 0, 0], [0, 4.0, 0], [0, 0, 1.0]]
    comparison = compare_tensors(np.array(a), np.array(b))
    assert comparison is not None and comparison.factor == pytest.approx(4.0)


def test_a_one_digit_isotropic_value_far_from_a_round_shape_is_a_placeholder(lint):
    # ixx = iyy = izz = 1 on a 60 g ball of radius 2 cm (2/5 m r² = 9.6e-6): no part is that
    (finding,) = in013(lint, moving(inertial(0.06, 1.0) + collision(sphere(0.02)), name="foot"))
    assert "ixx = iyy = izz = 1 kg·m²" in finding.message
    assert "near-isotropic but gives 1/1.04e+05 of that" in finding.detail
    assert finding.expected["ixx"] == pytest.approx(0.4 * 0.06 * 0.02**2)
    # within the band real parts scatter in (a factor of 2.5), or a value no one makes up
    assert in013(lint, moving(inertial(0.06, 2e-5) + collision(sphere(0.02)))) == []
    assert in013(lint, moving(inertial(0.06, 0.937) + collision(sphere(0.02)))) == []
