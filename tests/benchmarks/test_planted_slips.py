"""
benchmarks/planted_slips.py: its slips are the exact physics its document says (checked against
sums over point masses, not against its own formulas), the invertible ones undo, and the current
rules see the kg·mm² slip on a textbook box.
"""

from __future__ import annotations

import dataclasses
import sys

import numpy as np
import pytest
from kit import REPO, write
from kit.urdf import box, box_inertial, collision, moving

sys.path.insert(0, str(REPO / "benchmarks"))
import planted_slips as ps

from inertia_kit.description.loader import load
from inertia_kit.physics.frames import rpy_matrix

RNG = np.random.default_rng(20)


def _points(n=7):
    """Point masses (kg) at positions (m, link frame): a body whose tensors are plain sums."""
    return RNG.uniform(0.1, 2.0, n), RNG.normal([0.05, -0.2, 0.3], 0.1, (n, 3))


def _about(masses, positions, point):
    """The tensor of the point masses about ``point``, link axes: sum m (|r|² E - r rᵀ)."""
    r = positions - point
    return sum(m * (v @ v * np.eye(3) - np.outer(v, v)) for m, v in zip(masses, r, strict=True))


@pytest.mark.parametrize("rpy", [(0.0, 0.0, 0.0), (0.3, -0.7, 1.2)])
def test_about_origin_is_the_tensor_about_the_link_origin(rpy):
    masses, positions = _points()
    com = masses @ positions / masses.sum()
    rotation = rpy_matrix(rpy)
    written = rotation.T @ _about(masses, positions, com) @ rotation  # in the <origin rpy> axes
    values = ps.Values(masses.sum(), com, np.array(rpy), written)
    slipped = ps.about_origin(values)
    about_origin = rotation @ slipped.tensor @ rotation.T
    assert np.allclose(about_origin, _about(masses, positions, np.zeros(3)), rtol=1e-12, atol=0)
    assert slipped.mass == values.mass and np.array_equal(slipped.xyz, values.xyz)


def _values():
    masses, positions = _points()
    com = masses @ positions / masses.sum()
    return ps.Values(masses.sum(), com, np.array([0.1, 0.2, 0.3]), _about(masses, positions, com))


UNDO = {
    "about-origin": lambda v: ps.about_origin(v, sign=-1.0),
    "signs": ps.signs,
    "other-axes": lambda v: ps.other_axes(v, ps.RX90.T),
    "kg-mm2": lambda v: v.replace(tensor=v.tensor / 1e6),
    "swap-ixx-iyy": ps.swap_ixx_iyy,
    "mass-x3": lambda v: v.replace(mass=v.mass / 3),
    "grams": lambda v: v.replace(mass=v.mass / 1000),
    "com-mirrored": ps.com_mirrored,
    "com-flip": ps.com_flip,
    "com-swap": ps.com_swap,
}


@pytest.mark.parametrize("kind", sorted(UNDO))
def test_undoing_an_invertible_slip_gives_the_original(kind):
    values = _values()
    slipped = ps.SLIPS[kind](values)
    assert not ps._same(values, slipped)
    back = UNDO[kind](slipped)
    for a, b in ((back.tensor, values.tensor), (back.xyz, values.xyz)):
        assert np.allclose(a, b, rtol=1e-12, atol=1e-15)
    assert back.mass == pytest.approx(values.mass, rel=1e-15)


def test_each_slip_changes_what_it_names():
    v = ps.Values(2.0, np.array([0.1, -0.3, 0.2]), np.zeros(3), np.diag([1.0, 2.0, 3.0]))
    assert np.array_equal(ps.com_flip(v).xyz, [0.1, 0.3, 0.2])  # the largest |value|, y
    assert np.array_equal(ps.com_swap(v).xyz, [0.1, 0.2, -0.3])  # y and z exchanged
    assert np.array_equal(ps.com_origin(v).xyz, np.zeros(3))
    assert np.array_equal(ps.identity(v).tensor, np.eye(3))
    # 90° about x: y and z exchange their moments
    assert np.allclose(ps.other_axes(v).tensor, np.diag([1.0, 3.0, 2.0]), atol=1e-15)
    assert ps.grams(v).mass == 2000.0 and ps.mass_x3(v).mass == 6.0


def test_identifiable_is_a_change_beyond_the_populations_agreement():
    v = ps.Values(2.0, np.array([0.1, 0.0, 0.0]), np.zeros(3), np.diag([1.0, 2.0, 2.5]))
    assert ps.identifiable(v, ps.mass_x3(v), size=1.0)  # I/m a third: beyond a factor 2
    assert ps.identifiable(v, ps.kg_mm2(v), size=1.0)
    assert not ps.identifiable(v, ps.signs(v), size=1.0)  # no products: nothing changes
    assert not ps.identifiable(v, ps.com_mirrored(v), size=1.0)  # moved 0.2 of 1 m
    assert ps.identifiable(v, ps.com_mirrored(v), size=0.5)  # moved 0.2 of 0.5 m


def test_the_current_rules_see_the_kg_mm2_slip_on_a_textbook_box(tmp_path):
    size = (0.3, 0.1, 0.05)
    body = box_inertial(2.0, size) + collision(box(*size))
    robot = load(write(tmp_path / "r.urdf", moving(body)))
    load_mesh = ps._loader()
    analysis, before = ps._lint(robot, load_mesh)
    assert not [f for f in before if f.link == "arm" and ps._loud(f)]
    assert ps._agrees(analysis.by_name["arm"]) == {"cad": False, "size": 0.3}
    index = [link.name for link in robot.links].index("arm")
    link = robot.links[index]
    slipped = ps.kg_mm2(ps.Values.of(link.inertial))
    links = (*robot.links[:index], ps.planted(link, slipped), *robot.links[index + 1 :])
    _, after = ps._lint(dataclasses.replace(robot, links=links), load_mesh)
    assert [f for f in after if f.link == "arm" and ps._loud(f)]


def _box_case(tmp_path, slip):
    """The textbook box with ``slip`` planted: its true values, the slipped link's analysis and
    its findings."""
    size = (0.3, 0.1, 0.05)
    body = box_inertial(2.0, size) + collision(box(*size))
    robot = load(write(tmp_path / "r.urdf", moving(body)))
    load_mesh = ps._loader()
    index = [link.name for link in robot.links].index("arm")
    link = robot.links[index]
    true = ps.Values.of(link.inertial)
    links = (*robot.links[:index], ps.planted(link, slip(true)), *robot.links[index + 1 :])
    analysis, after = ps._lint(dataclasses.replace(robot, links=links), load_mesh)
    return true, analysis.by_name["arm"], [f for f in after if f.link == "arm" and ps._loud(f)]


def test_visible_judges_the_planted_values_against_the_geometry(tmp_path):
    # a mass x3 on the exact box: the tensor is a third of the geometry's at the planted mass,
    # ln((1 + f) / (1/3 + f)) = 1.01 in log distance, beyond the band (0.92)
    _, link, _ = _box_case(tmp_path, ps.mass_x3)
    assert ps.visible("mass-x3", link, size=0.3)
    # a mass x1.5: 0.39, within what real parts scatter
    _, link, _ = _box_case(tmp_path, lambda v: v.replace(mass=v.mass * 1.5))
    assert not ps.visible("mass-x3", link, size=0.3)
    _, link, _ = _box_case(tmp_path, ps.grams)
    assert ps.visible("grams", link, size=0.3)  # by its factor
    # the box's COM at its centre: moved off it by 0.1 m, a third of its length
    _, link, _ = _box_case(tmp_path, lambda v: v.replace(xyz=np.array([0.1, 0.0, 0.0])))
    assert ps.visible("com-flip", link, size=0.3)
    assert not ps.visible("com-flip", link, size=0.5)


def test_an_equivalent_rule_names_a_slip_when_its_repair_restores_the_true_values(tmp_path):
    # ixx and iyy exchanged on a diagonal tensor is a quarter turn about z: IN062's repair
    true, _, found = _box_case(tmp_path, ps.swap_ixx_iyy)
    assert {f.code for f in found} & {"IN062", "IN064"}
    assert any(ps.restored(f, true) for f in found if f.code in ps.FORENSIC)
    # a repair that does not restore them: the true values of another mass
    assert not any(ps.restored(f, true.replace(mass=2 * true.mass)) for f in found)
    assert not any(ps.restored(f, true.replace(tensor=1.1 * true.tensor)) for f in found)


def test_changes_elsewhere_tells_new_findings_from_changed_severities_and_welded_ones():
    from inertia_kit.lint.findings import Severity

    def finding(link, code, severity, weighed=False):
        kind = dataclasses.make_dataclass("F", ["link", "code", "severity", "weighed"])
        return kind(link, code, severity, weighed)

    before = [
        finding("imu", "IN020", Severity.WARNING),
        finding("roll", "IN066", Severity.WARNING),
        finding("wheel", "IN023", Severity.ERROR),
    ]
    after = [
        finding("planted", "IN021", Severity.ERROR),  # on the planted link: not elsewhere
        finding("imu", "IN020", Severity.ERROR),  # raised
        finding("roll", "IN013", Severity.WARNING),  # the copy told by the other rule
        finding("wheel", "IN023", Severity.WARNING),  # lowered
        finding("wheel", "IN020", Severity.WARNING),  # new
        finding("twin", "IN065", Severity.WARNING),  # new
        finding(None, "IN065", Severity.WARNING),  # a pair blaming neither twin: not counted
        finding("imu", "IN013", Severity.WARNING, weighed=True),  # its body changed: welded
        finding("camera", "IN022", Severity.WARNING, weighed=True),  # not welded: new
        finding("imu", "IN042", Severity.WARNING),  # welded, but not judged by its share: new
    ]
    assert ps.changes_elsewhere(before, after, "planted", frozenset({"planted", "imu"})) == (
        ["camera:IN022", "imu:IN042", "twin:IN065", "wheel:IN020"],
        ["imu:IN020"],
        ["wheel:IN023"],
        ["imu:IN013"],
    )
