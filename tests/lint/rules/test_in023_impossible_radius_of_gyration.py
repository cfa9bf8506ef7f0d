"""IN023 impossible-radius-of-gyration: hard bounds from closed forms computed here."""

from __future__ import annotations

import importlib.metadata
import json
import math
from collections import Counter
from pathlib import Path

import pytest
from click.testing import CliRunner
from kit.moments import box_moments, cylinder_moments
from kit.urdf import box, collision, cylinder, inertial, mesh, moving, sphere, visual

from inertia_kit.analysis.bounds import RIM_SIDES
from inertia_kit.cli.lint import lint_command
from inertia_kit.lint.findings import Severity
from inertia_kit.physics.formatting import fmt

RIM = 1.0 / math.cos(math.pi / RIM_SIDES)
CYLINDER = collision(cylinder(0.05, 0.05))


def test_unit_placeholder_on_a_small_wheel_is_impossible(lint):
    """robot1's wheels: 1 kg·m² on a 1 kg wheel of radius 5 cm."""
    findings = lint(moving(CYLINDER + inertial(1.0, 1.0, 1.0, 1.0)), "IN023")
    assert len(findings) == 1
    finding = findings[0]
    assert finding.severity == Severity.ERROR
    # worst about the axis z: at most m r² (the rim polygon overshoots r by 1/cos(π/64))
    assert finding.expected["max"] == pytest.approx((0.05 * RIM) ** 2)
    assert finding.expected["uniform"] == pytest.approx(0.05**2 / 2)
    assert finding.message == (
        f"link `arm`: izz = 1 kg·m² exceeds the {fmt(finding.expected['max'], 4)} kg·m² its "
        "geometry allows"
    )
    assert len(finding.message) <= 100
    assert "(radius of gyration 1 m)" in finding.detail
    assert "inside its collision cylinder (r = 0.05 m, l = 0.05 m) can have" in finding.detail


def test_ring_at_the_rim_is_the_limit_and_passes(lint):
    """A thin ring of radius r has izz = m r², ixx = iyy = m r²/2: possible, never flagged."""
    mass, radius = 2.0, 0.05
    ring = inertial(mass, mass * radius**2 / 2, mass * radius**2 / 2, mass * radius**2)
    assert lint(moving(CYLINDER + ring), "IN023") == []
    over = inertial(mass, mass * radius**2 / 2, mass * radius**2 / 2, 1.05 * mass * radius**2)
    findings = lint(moving(CYLINDER + over), "IN023")
    assert len(findings) == 1 and "izz" in findings[0].message
    assert findings[0].expected["max"] == pytest.approx(mass * (radius * RIM) ** 2)


def test_rtol_option(lint):
    mass, radius = 2.0, 0.05
    text = moving(CYLINDER + inertial(mass, 1e-3, 1e-3, 1.03 * mass * radius**2))
    assert len(lint(text, "IN023")) == 1
    assert lint(text, "IN023", options={"IN023": {"rtol": 0.05}}) == []


def test_dumbbell_bound_is_close_to_the_uniform_value(lint):
    """Two balls far apart: the uniform value is nearly the most possible (IN020 quiet)."""
    body = collision(sphere(0.05), xyz="0 0.25 0") + collision(sphere(0.05), xyz="0 -0.25 0")
    mass = 2.0
    uniform_x = mass * (0.25**2 + 2 * 0.05**2 / 5)  # two balls at ±0.25 about x
    bound_x = mass * (0.25 + 0.05) ** 2  # Bhatia–Davis along y; a ball's support is exact
    assert lint(moving(body + inertial(mass, uniform_x, 0.002, uniform_x)), "IN023") == []
    findings = lint(moving(body + inertial(mass, 1.5 * uniform_x, 0.002, uniform_x)), "IN023")
    assert len(findings) == 1
    assert findings[0].expected["max"] == pytest.approx(bound_x)
    assert lint(moving(body + inertial(mass, 1.5 * uniform_x, 0.002, uniform_x)), "IN020") == []


def test_rotated_cylinder_is_bounded_in_link_axes(lint):
    """Cylinder along x: about x at most m r²; a tensor written for z breaks that."""
    mass, radius, length = 1.0, 0.02, 0.3
    transverse, _, axial = cylinder_moments(mass, radius, length)
    body = collision(cylinder(radius, length), rpy="0 1.5707963267948966 0")
    findings = lint(moving(body + inertial(mass, transverse, transverse, axial)), "IN023")
    assert len(findings) == 1 and "ixx" in findings[0].message
    assert findings[0].expected["max"] == pytest.approx(mass * (radius * RIM) ** 2)
    # rotating the same values into link axes makes them right
    right = inertial(mass, transverse, transverse, axial, rpy="0 1.5707963267948966 0")
    assert lint(moving(body + right), "IN023") == []


def test_an_off_centre_com_shrinks_the_bound(lint):
    """A 1 m rod with its COM 0.45 m off centre: about y at most m (0.05 × 0.95 + 0.05²)."""
    body = collision(box(1, 0.1, 0.1))
    mass = 1.0
    _, uniform, _ = box_moments(mass, (1, 0.1, 0.1))
    findings = lint(moving(body + inertial(mass, 0.002, uniform, uniform, xyz="0.45 0 0")), "IN023")
    assert len(findings) == 1
    assert findings[0].expected["max"] == pytest.approx(mass * (0.05 * 0.95 + 0.05**2))


def test_visual_geometry_widens_the_envelope(lint):
    """A small collision sphere inside a large visual box: the box bounds what is possible."""
    body = visual(box(0.4, 0.4, 0.4)) + collision(sphere(0.05))
    mass = 1.0
    possible = mass * 0.2**2  # a ring at 0.2 m, inside the visual box
    assert lint(moving(body + inertial(mass, possible, possible, possible)), "IN023") == []


def test_missing_mesh_or_inertial_is_not_its_business(lint):
    body = visual(mesh("missing.stl")) + CYLINDER
    assert lint(moving(body + inertial(1.0, 1.0, 1.0, 1.0)), "IN023") == []
    assert lint(moving(CYLINDER), "IN023") == []


# --- severity by the firmness of the bound (analysis.firmness) ---------------------------------

# Unitree Go1's rotor (example-robot-data go1.urdf): 2.3 % over m r² of its drawn cylinder
ROTOR_RPY = "0 1.5707963267948966 0"
ROTOR = inertial(0.089, 0.000111842, 5.9647e-05, 5.9647e-05)


def test_go1_rotor_2_percent_over_a_rounded_radius_is_a_warning(lint):
    shape = cylinder(0.035, 0.02)
    (finding,) = lint(
        moving(collision(shape, rpy=ROTOR_RPY) + visual(shape, rpy=ROTOR_RPY) + ROTOR), "IN023"
    )
    assert finding.severity == Severity.WARNING
    assert finding.detail.endswith(
        "; a warning, not an error: 2.3% over is within what rounding of the written cylinder "
        "radius 0.035 m and mass 0.089 kg can explain (the bound then reaches 0.0001131 kg·m²)"
    )
    assert finding.expected["firm"] is False
    assert finding.expected["max_with_rounding"] == pytest.approx(0.0895 * (0.0355 * RIM) ** 2)
    assert "make the collision geometry as large as the part" in finding.help


def test_a_schematic_visual_only_rotor_is_a_warning(lint):
    """The issue's Go1: a rotor drawn as a visual cylinder only, its moment 2 % over."""
    shape = visual(cylinder("0.0349999", "0.0200001"), rpy=ROTOR_RPY)
    (finding,) = lint(moving(shape + ROTOR), "IN023")
    assert finding.severity == Severity.WARNING
    assert "its only geometry is visual, often a schematic stand-in for the part" in (
        finding.detail
    )


def test_firm_overshoots_stay_errors(lint):
    # every digit written: 2.3 % over is no rounding
    precise = collision(cylinder("0.0349999", "0.0200001"), rpy=ROTOR_RPY)
    mass = inertial("0.0890001", 0.000111842, 5.9647e-05, 5.9647e-05)
    (finding,) = lint(moving(precise + mass), "IN023")
    assert finding.severity == Severity.ERROR and "a warning" not in finding.detail
    # Unitree B1's thigh rotor (b1.urdf): 38 % over its 0.05 m cylinder, beyond any rounding
    b1 = inertial(0.266, 0.000485657, 0.00091885, 0.000485657)
    b1_shape = cylinder(0.05, 0.02)
    along_y = "1.5707963267948966 0 0"
    b1_body = collision(b1_shape, rpy=along_y) + visual(b1_shape, rpy=along_y)
    (finding,) = lint(moving(b1_body + b1), "IN023")
    assert finding.severity == Severity.ERROR and "iyy" in finding.message
    # a placeholder on visual geometry only: far beyond what any stand-in allows
    (finding,) = lint(moving(visual(b1_shape) + inertial(0.266, 1.0)), "IN023")
    assert finding.severity == Severity.ERROR


def test_a_configured_severity_wins(lint):
    shape = visual(cylinder(0.035, 0.02), rpy=ROTOR_RPY)
    (finding,) = lint(moving(shape + ROTOR), "IN023", severities={"IN023": Severity.ERROR})
    assert finding.severity == Severity.ERROR


def _example_robot_data(relative: str) -> Path:
    try:
        share = importlib.metadata.distribution("example-robot-data").locate_file(
            "cmeel.prefix/share/example-robot-data"
        )
    except importlib.metadata.PackageNotFoundError:
        pytest.skip("example-robot-data is not installed")
    path = Path(str(share)) / relative
    if not path.is_file():
        pytest.skip(f"{relative} not in this example-robot-data")
    return path


def test_the_installed_unitree_robots_through_the_command():
    """The issue's reproducer: Go1 gave 12 errors on its rotor links for a 2 % overshoot."""
    go1 = _example_robot_data("robots/go1_description/urdf/go1.urdf")
    b1 = _example_robot_data("robots/b1_description/urdf/b1.urdf")
    result = CliRunner().invoke(
        lint_command, ["--select", "IN023", "--output-format", "json", str(go1), str(b1)]
    )
    assert result.exit_code == 1, result.stderr
    rotors = [f for f in json.loads(result.stdout) if f["link"].endswith("_rotor")]
    go1_rotors = [f["severity"] for f in rotors if f["file"] == str(go1)]
    assert go1_rotors == ["warning"] * 12
    # B1's thigh and calf rotors are 38 % over their 0.05 m cylinders: still errors; its hip
    # rotors' ∫x² dm = (iyy + izz - ixx)/2 = 2.315e-05 is 16 % over the 0.199 kg × (0.01 m)²
    # of their 0.02 m width (6 % more than the rounding of `0.02` allows): errors too
    b1_rotors = Counter(
        (f["link"].split("_", 1)[1], f["severity"]) for f in rotors if f["file"] == str(b1)
    )
    assert b1_rotors == {("thigh_rotor", "error"): 4, ("calf_rotor", "error"): 4} | {
        ("hip_rotor", "error"): 4
    }


def test_a_tensor_that_is_no_rigid_body_far_from_its_geometry(lint):
    """Found by hypothesis: not positive definite, and a bound of 0 for a box 1.9e8 m away."""
    import warnings

    body = (
        '<inertial><origin rpy="1 1 0.5"/><mass value="1"/>'
        '<inertia ixx="1" ixy="1" ixz="1" iyy="0.5" iyz="1.0" izz="1"/></inertial>'
        '<visual><origin xyz="1 189812532.0 1"/><geometry><box size="1 1 1"/></geometry></visual>'
    )
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        assert lint(moving(body), "IN023") == []


# --- second moments along a direction (Bhatia–Davis) ---------------------------------------------

AXLE_Y = "1.5707963267948966 0 0"


def test_a_wheel_with_the_axial_formula_on_every_axis_is_impossible(lint):
    """The issue's wheel: r = 0.05 m, 0.02 m wide, axle along y, ixx = iyy = izz = ½ m r²:
    ∫y² dm = (ixx + izz - iyy)/2 = ¼ m r² against m (0.01 m)², 6.25 times over."""
    mass, radius, width = 1.0, 0.05, 0.02
    axial = mass * radius**2 / 2
    wheel = collision(cylinder(radius, width), rpy=AXLE_Y)
    (finding,) = lint(moving(wheel + inertial(mass, axial, axial, axial)), "IN023")
    assert finding.severity == Severity.ERROR
    assert finding.expected["kind"] == "along"
    assert finding.expected["axis"] == pytest.approx([0.0, 1.0, 0.0])
    assert finding.expected["max"] == pytest.approx(mass * (width / 2) ** 2)
    assert finding.expected["sides"] == pytest.approx([width / 2, width / 2])
    assert finding.expected["uniform"] == pytest.approx(mass * width**2 / 12)
    assert finding.message == (
        "link `arm`: ∫y² dm = 0.000625 kg·m² exceeds the 0.0001 kg·m² its geometry allows"
    )
    assert finding.detail.startswith(
        "the second moment along y, ∫y² dm = (ixx + izz - iyy)/2 = 0.000625 kg·m², "
        "is more than the 0.0001 kg·m² any 1 kg inside its collision cylinder"
    )
    assert "\n" not in finding.message and "Bhatia–Davis" in finding.help
    # the wheel's own tensor passes: ixx = izz = m (3 r² + w²)/12
    across = mass * (3 * radius**2 + width**2) / 12
    assert lint(moving(wheel + inertial(mass, across, axial, across)), "IN023") == []


def test_a_thin_ring_on_the_rim_is_the_limit_of_both_kinds(lint):
    """A ring of radius r in the mid-plane: ∫y² dm = 0, iyy = m r², ixx = izz = ½ m r²."""
    mass, radius = 1.0, 0.05
    ring = inertial(mass, mass * radius**2 / 2, mass * radius**2, mass * radius**2 / 2)
    assert lint(moving(collision(cylinder(radius, 0.02), rpy=AXLE_Y) + ring), "IN023") == []


def test_an_off_centre_com_tightens_the_bound_but_only_warns(lint):
    """COM 8 mm from the centre plane of a 20 mm wheel: at most m × 0.018 × 0.002 along y,
    but m (0.01 m)² with the COM midway: an error must not rest on where the COM is written."""
    mass = 1.0
    wheel = collision(cylinder(0.05, 0.02), rpy=AXLE_Y)
    # ∫y² dm = (ixx + izz - iyy)/2 = 7.5e-05: beyond 3.6e-05, within 1e-04
    body = wheel + inertial(mass, 0.0012, 0.00225, 0.0012, xyz="0 0.008 0")
    (finding,) = lint(moving(body), "IN023")
    assert finding.expected["kind"] == "along"
    assert finding.expected["max"] == pytest.approx(mass * 0.018 * 0.002)
    assert finding.expected["sides"] == pytest.approx([0.018, 0.002])  # towards -y, +y
    assert finding.expected["max_with_rounding"] > mass * 0.01**2  # the COM anywhere
    assert finding.severity == Severity.WARNING
    assert "a centre of mass off its declared place (0.018 m and 0.002 m" in finding.detail
    mirrored = wheel + inertial(mass, 0.0012, 0.00225, 0.0012, xyz="0 -0.008 0")
    (finding,) = lint(moving(mirrored), "IN023")
    assert finding.expected["axis"] == pytest.approx([0.0, 1.0, 0.0])
    assert finding.expected["sides"] == pytest.approx([0.002, 0.018])
    # ∫y² dm = 3e-04, 3 times m (0.01 m)²: wherever the COM is, impossible
    beyond = wheel + inertial(mass, 0.0012, 0.0018, 0.0012, xyz="0 0.008 0")
    (finding,) = lint(moving(beyond), "IN023")
    assert finding.severity == Severity.ERROR
