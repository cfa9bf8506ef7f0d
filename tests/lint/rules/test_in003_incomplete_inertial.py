"""IN003 incomplete-inertial: what is missing, where it is reported, what the parsers do."""

from __future__ import annotations

import pytest
from kit.moments import box_moments
from kit.urdf import box, collision

from inertia_kit.physics.formatting import fmt

HEAD = (
    '<robot name="r"><link name="base"/>'
    '<joint name="j" type="revolute"><parent link="base"/><child link="arm"/>'
    '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>\n'
    '<link name="arm">\n'
)
SIZE = (0.1, 0.2, 0.3)
BOX = collision(box(*SIZE)) + "\n"
SIX = 'ixx="0.0325" ixy="0" ixz="0" iyy="0.025" iyz="0" izz="0.0125"'


def robot(inertial: str, geometry: str = BOX) -> str:
    return HEAD + inertial + geometry + "</link></robot>"


def in003(lint, text):
    return [f for f in lint(text, "IN003") if f.code == "IN003"]


def test_complete_inertial_is_quiet(lint):
    assert in003(lint, robot(f'<inertial><mass value="3"/><inertia {SIX}/></inertial>\n')) == []


def test_missing_diagonal_value(lint):
    text = robot(
        '<inertial><mass value="3"/>\n'
        '<inertia ixx="0.0325" ixy="0" ixz="0" iyy="0.025" iyz="0"/></inertial>\n'
    )
    (finding,) = in003(lint, text)
    assert finding.message == "link `arm`: `<inertial>` has an `<inertia>` without `izz`"
    assert "PyBullet refuse the file" in finding.detail
    assert "Drake reads izz as 0" in finding.detail and "yourdfpy izz as 1.0" in finding.detail
    _, _, izz = box_moments(3.0, SIZE)
    assert f"izz = {fmt(izz, 4)}" in finding.detail
    assert finding.expected["izz"] == pytest.approx(izz)
    # reported on the <inertia> element, the most specific one
    assert finding.line == 4


def test_missing_product_pybullet_reads_zero(lint):
    text = robot(
        '<inertial><mass value="3"/>'
        '<inertia ixx="0.0325" ixz="0" iyy="0.025" iyz="0" izz="0.0125"/></inertial>\n'
    )
    (finding,) = in003(lint, text)
    assert "without `ixy`" in finding.message and "PyBullet as 0" in finding.detail
    assert "PyBullet refuse" not in finding.detail


def test_missing_mass_uses_1000_kg_per_m3(lint):
    text = robot(f"<inertial>\n<inertia {SIX}/></inertial>\n")
    (finding,) = in003(lint, text)
    assert "no `<mass>`" in finding.message and "Drake reads mass 0" in finding.detail
    mass = 1000.0 * 0.1 * 0.2 * 0.3
    _, iyy, _ = box_moments(mass, SIZE)
    assert f"holds {fmt(mass, 4)} kg" in finding.detail
    assert finding.expected["mass"] == pytest.approx(mass)
    assert finding.expected["density"] == 1000.0
    assert finding.expected["iyy"] == pytest.approx(iyy)
    assert finding.line == 3  # the <inertial> element: there is no <mass> to point at


def test_mass_without_value(lint):
    text = robot(f"<inertial>\n<mass/>\n<inertia {SIX}/></inertial>\n")
    (finding,) = in003(lint, text)
    assert "`<mass>` without `value`" in finding.message
    assert finding.line == 4


def test_missing_inertia_element(lint):
    (finding,) = in003(lint, robot('<inertial><mass value="3"/></inertial>\n'))
    assert "no `<inertia>`" in finding.message and "Drake reads a zero tensor" in finding.detail
    ixx, iyy, _ = box_moments(3.0, SIZE)
    assert f"ixx = {fmt(ixx, 4)}" in finding.detail
    assert f"iyy = {fmt(iyy, 4)}" in finding.detail


def test_everything_missing_in_one_finding(lint):
    (finding,) = in003(lint, robot("<inertial/>\n"))
    assert "no `<mass>` and no `<inertia>`" in finding.message


def test_without_geometry_no_expected_values(lint):
    (finding,) = in003(lint, robot('<inertial><mass value="3"/></inertial>', geometry=""))
    assert finding.expected is None


def test_values_in_the_written_axes(lint):
    # the inertia axes turned 90° about z: the geometry's ixx and iyy swap
    inertial = '<inertial><origin rpy="0 0 1.5707963267948966"/><mass value="3"/></inertial>\n'
    (finding,) = in003(lint, robot(inertial))
    ixx, iyy, _ = box_moments(3.0, SIZE)
    assert finding.expected["ixx"] == pytest.approx(iyy)
    assert finding.expected["iyy"] == pytest.approx(ixx)
    assert "axes of its `<inertial><origin rpy>`" in finding.detail


def test_a_value_that_is_not_a_number_is_in004s(lint):
    text = robot(f'<inertial><mass value="abc"/><inertia {SIX}/></inertial>\n')
    assert in003(lint, text) == []


def test_the_message_is_one_short_line_and_the_detail_has_the_basis(lint):
    text = robot('<inertial><mass value="3"/><inertia ixx="0.0325" ixy="0"/></inertial>\n')
    (finding,) = in003(lint, text)
    assert finding.message == (
        "link `arm`: `<inertial>` has an `<inertia>` without 4 of its 6 values"
    )
    assert len(finding.message) <= 100
    detail = finding.detail
    assert detail.startswith("the `<inertia>` has no `ixz`, `iyy`, `iyz`, `izz`; ROS (urdfdom)")
    assert "its collision box (0.1 × 0.2 × 0.3 m) with the declared 3 kg gives" in detail
