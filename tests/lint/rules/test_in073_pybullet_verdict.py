"""IN073 pybullet-verdict: predictions, and the installed pybullet as the judge."""

from __future__ import annotations

import numpy as np
import pytest
from kit import REPO
from kit.urdf import LIMIT, box, collision, inertial, link, robot

from inertia_kit.analysis.links import analyse
from inertia_kit.description.loader import load
from inertia_kit.lint.rules.in073_pybullet_verdict import bad_tensor, predicted_inertia

MESH = REPO / "examples/pan_tilt_description/meshes/pan.stl"
INERTIA = '<inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/>'

# (name, <inertial><origin> attributes, collision elements)
CASES = [
    ("box", "", '<collision><geometry><box size="0.2 0.4 0.6"/></geometry></collision>'),
    (
        "offset box",
        "",
        '<collision><origin xyz="0 0 0.1"/><geometry><box size="0.2 0.4 0.6"/></geometry>'
        "</collision>",
    ),
    (
        "rotated box",
        "",
        '<collision><origin rpy="0 0 0.5"/><geometry><box size="0.2 0.4 0.6"/></geometry>'
        "</collision>",
    ),
    (
        "box in rotated inertial axes",
        'rpy="0 0 1.5707963267948966"',
        '<collision><geometry><box size="0.2 0.4 0.6"/></geometry></collision>',
    ),
    (
        "sphere at the COM",
        'xyz="0.1 0 0"',
        '<collision><origin xyz="0.1 0 0"/><geometry><sphere radius="0.1"/></geometry></collision>',
    ),
    (
        "offset sphere",
        "",
        '<collision><origin xyz="0.1 0 0"/><geometry><sphere radius="0.1"/></geometry></collision>',
    ),
    (
        "cylinder",
        "",
        '<collision><geometry><cylinder radius="0.1" length="0.5"/></geometry></collision>',
    ),
    (
        "rotated cylinder",
        "",
        '<collision><origin rpy="0.3 0 0"/><geometry><cylinder radius="0.1" length="0.5"/>'
        "</geometry></collision>",
    ),
    (
        "two shapes",
        "",
        '<collision><origin xyz="0 0 0.5"/><geometry><box size="0.1 0.1 0.1"/></geometry>'
        '</collision><collision><geometry><sphere radius="0.2"/></geometry></collision>',
    ),
    ("no collision", "", ""),
    ("mesh", "", f'<collision><geometry><mesh filename="{MESH}"/></geometry></collision>'),
    (
        "scaled offset mesh",
        "",
        f'<collision><origin xyz="0.01 0 0"/><geometry><mesh filename="{MESH}" '
        'scale="0.001 0.001 0.001"/></geometry></collision>',
    ),
]


def urdf(origin: str, collisions: str, mass: float = 2.0) -> str:
    return f"""<robot name="r"><link name="world"/>
  <joint name="j" type="revolute"><parent link="world"/><child link="l"/><axis xyz="0 0 1"/>
    {LIMIT}</joint>
  <link name="l"><inertial><origin {origin}/><mass value="{mass}"/>{INERTIA}</inertial>
    {collisions}</link></robot>"""


@pytest.mark.parametrize(("name", "origin", "collisions"), CASES, ids=[c[0] for c in CASES])
def test_prediction_matches_pybullet(tmp_path, name, origin, collisions):
    pybullet = pytest.importorskip("pybullet")
    path = tmp_path / "robot.urdf"
    path.write_text(urdf(origin, collisions))
    predicted = predicted_inertia(analyse(load(path)).by_name["l"], 2.0)
    client = pybullet.connect(pybullet.DIRECT)
    try:
        body = pybullet.loadURDF(str(path), physicsClientId=client)
        measured = pybullet.getDynamicsInfo(body, 0, physicsClientId=client)[2]
        from_file = pybullet.loadURDF(
            str(path), flags=pybullet.URDF_USE_INERTIA_FROM_FILE, physicsClientId=client
        )
        kept = pybullet.getDynamicsInfo(from_file, 0, physicsClientId=client)[2]
    finally:
        pybullet.disconnect(client)
    # pybullet computes in float64 but some shapes store float32 vertices
    np.testing.assert_allclose(measured, predicted, rtol=1e-5)
    np.testing.assert_allclose(kept, [0.1, 0.1, 0.1], rtol=1e-12)


def test_link_without_inertial_gets_one_kilogram(tmp_path):
    pybullet = pytest.importorskip("pybullet")
    path = tmp_path / "robot.urdf"
    path.write_text(
        urdf("", "").replace(
            '<link name="l"><inertial><origin /><mass value="2.0"/>' + INERTIA + "</inertial>",
            '<link name="l"><collision><geometry><box size="0.1 0.2 0.3"/></geometry></collision>',
        )
    )
    predicted = predicted_inertia(analyse(load(path)).by_name["l"], 1.0)
    client = pybullet.connect(pybullet.DIRECT)
    try:
        info = pybullet.getDynamicsInfo(
            pybullet.loadURDF(str(path), physicsClientId=client), 0, physicsClientId=client
        )
    finally:
        pybullet.disconnect(client)
    assert info[0] == 1.0
    np.testing.assert_allclose(info[2], predicted, rtol=1e-9)


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
    assert "URDF_USE_INERTIA_FROM_FILE" in finding.message


def test_link_without_inertial_is_reported_with_pybullet_message(lint):
    (finding,) = run(lint, '<link name="tool0"/>')
    assert finding.expected["engine_message"].startswith("No inertial data for link, using mass=1")
    assert finding.expected["mass"] == 1.0


def test_world_link_is_not_reported(lint):
    assert run(lint, '<link name="world"/>') == []


def test_with_inertia_from_file_a_bad_tensor_is_zeroed(lint):
    bad = BOX.replace('izz="0.3"', 'izz="0.5"')
    (finding,) = run(lint, bad, use_inertia_from_file=True)
    assert finding.expected["engine_message"] == (
        "Bad inertia tensor properties, setting inertia to zero for link: a"
    )
    assert run(lint, BOX, use_inertia_from_file=True) == []


def test_bad_tensor_uses_pybullet_test():
    assert bad_tensor(np.diag([0.1, 0.2, 0.31]))
    assert not bad_tensor(np.diag([0.1, 0.2, 0.3]))
    assert bad_tensor(np.diag([-0.1, 0.2, 0.2]))
