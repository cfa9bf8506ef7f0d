"""IN073 pybullet-verdict: findings from the PyBullet model (engines.pybullet), options."""

from __future__ import annotations

import pytest
from kit.urdf import box, collision, inertial, link, robot


def run(lint, body, **options):
    return lint(
        robot(body),
        select="IN073",
        engines=("pybullet",),
        options={"IN073": options} if options else {},
    )


BOX = link("a", inertial(6, 0.1, 0.2, 0.3), collision(box(0.6, 0.4, 0.2)))


def test_declared_tensor_equal_to_the_computed_one_gives_nothing(lint):
    # 6/12 (0.16+0.04) = 0.1, 6/12 (0.36+0.04) = 0.2, 6/12 (0.36+0.16) = 0.26: within 2×
    assert run(lint, BOX) == []


def test_tensor_far_from_the_bounding_box_is_reported(lint):
    (finding,) = run(
        lint, BOX.replace('izz="0.3"', 'izz="0.29"').replace('iyy="0.2"', 'iyy="0.02"')
    )
    assert finding.link == "a" and finding.expected["inertia_diagonal"] == pytest.approx(
        [0.1, 0.2, 0.26]
    )
    assert finding.message == "link `a`: PyBullet recomputes its inertia: 10× the declared one"
    assert len(finding.message) <= 100
    # 0.29 > 0.1 + 0.02: with URDF_USE_INERTIA_FROM_FILE, PyBullet would zero it
    assert finding.detail == (
        "Unless loaded with URDF_USE_INERTIA_FROM_FILE, PyBullet replaces the inertia of link "
        "`a` by (0.1, 0.2, 0.26) kg·m² (in its <inertial> axes) from the bounding box of its "
        "collision shape, 10× the declared moment about some axis; with that flag it zeroes the "
        'tensor. PyBullet says: "Bad inertia tensor properties, setting inertia to zero for '
        'link: a"'
    )


def test_link_without_inertial_is_reported_with_pybullet_message(lint):
    (finding,) = run(lint, '<link name="tool0"/>')
    assert finding.expected["engine_message"].startswith("No inertial data for link, using mass=1")
    assert finding.expected["mass"] == 1.0
    assert finding.message == "link `tool0`: PyBullet gives it 1 kg: no <inertial>"
    assert "inertia diagonal (6.667e-07, 6.667e-07, 6.667e-07) kg·m²" in finding.detail
    assert finding.detail.endswith(f'PyBullet says: "{finding.expected["engine_message"]}"')


def test_world_link_is_not_reported(lint):
    assert run(lint, '<link name="world"/>') == []


def test_with_inertia_from_file_a_bad_tensor_is_zeroed(lint):
    bad = BOX.replace('izz="0.3"', 'izz="0.5"')
    (finding,) = run(lint, bad, use_inertia_from_file=True)
    assert finding.expected["engine_message"] == (
        "Bad inertia tensor properties, setting inertia to zero for link: a"
    )
    assert (
        finding.message == "link `a`: PyBullet zeroes its inertia: the tensor fails Bullet's test"
    )
    assert "Bad inertia tensor properties" in finding.detail
    assert run(lint, BOX, use_inertia_from_file=True) == []
