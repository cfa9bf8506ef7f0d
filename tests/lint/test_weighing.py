"""
Severity by consequence (lint.weighing): an error on a welded link's own values is lowered when
the link carries a negligible share of its lumped body, and says that share; a defect that
matters to the body keeps its severity.
"""

from __future__ import annotations

import pytest
from kit.moments import box_moments
from kit.urdf import box, box_inertial, collision, inertial, joint, link, robot

from inertia_kit.lint.findings import Severity
from inertia_kit.physics.formatting import fmt

TRUNK = (5.0, (0.4, 0.2, 0.1))  # kg, m


def trunk_with(*frames: tuple[str, str, str]) -> str:
    """
    A trunk on a revolute joint from the world, and each ``(name, body, kind)`` frame on a
    ``kind`` joint at (0.2, 0, 0) of it: Unitree Go1's layout of camera and IMU frames.
    """
    parts = [
        link("world"),
        joint("world", "trunk"),
        link("trunk", box_inertial(TRUNK[0], TRUNK[1]), collision(box(*TRUNK[1]))),
    ]
    for name, body, kind in frames:
        parts += [joint("trunk", name, kind, xyz=(0.2, 0, 0)), link(name, body)]
    return robot(*parts)


#: Go1's camera frames: 1e-5 kg with 1e-6 kg·m² (radius of gyration 0.32 m) in a 1 mm box
CAMERA = inertial(1e-5, 1e-6) + collision(box(0.001, 0.001, 0.001))


def on(findings, name):
    return {f.code: f for f in findings if f.link == name}


def test_a_welded_sensor_frame_gets_warnings_that_say_its_share(lint):
    found = on(lint(trunk_with(("camera", CAMERA, "fixed"))), "camera")
    assert set(found) == {"IN020", "IN023"}
    mass_share = 100 * 1e-5 / (TRUNK[0] + 1e-5)
    for finding in found.values():
        assert finding.severity is Severity.WARNING
        assert f"it adds {fmt(mass_share, 2)} % of the mass and " in finding.detail
        assert f"of the inertia of the body `trunk` it is welded into ({fmt(5.00001, 4)} kg)" in (
            finding.detail
        )


def test_the_same_frame_on_a_moving_joint_is_an_error(lint):
    # alone in its body, its impossible tensor is what the engines integrate
    found = on(lint(trunk_with(("camera", CAMERA, "revolute"))), "camera")
    assert found["IN023"].severity is Severity.ERROR
    assert "it adds" not in (found["IN023"].detail or "")


def test_a_big_welded_part_with_an_impossible_tensor_stays_an_error(lint):
    # a 1 kg battery in a 0.1 m cube welded to the trunk, its tensor 10 times what any 1 kg in
    # it can have: it is a fifth of the lumped mass
    ixx = 10 * 1.0 * 3 * 0.05**2
    battery = inertial(1.0, ixx) + collision(box(0.1, 0.1, 0.1))
    found = on(lint(trunk_with(("battery", battery, "fixed"))), "battery")
    assert found["IN023"].severity is Severity.ERROR
    assert "it adds" not in (found["IN023"].detail or "")


def test_a_massless_fixed_frame_is_no_error(lint):
    # Unitree Go2's `imu` and `radar`: <mass value="0"/> and a zero tensor on a fixed joint
    findings = lint(
        trunk_with(("imu", inertial(0, 0), "fixed"), ("radar", inertial(0, 0), "fixed"))
    )
    assert [f for f in findings if f.severity is not Severity.INFO] == []
    for name in ("imu", "radar"):
        finding = on(findings, name)["IN002"]
        assert finding.severity is Severity.INFO
        assert "it adds nothing to the body `trunk`" in finding.detail


@pytest.mark.parametrize(
    ("body", "why"),
    [
        (inertial(0, 1e-6), "Drake puts a 1 kg sphere there"),
        (inertial(-1e-5, 1e-6), "Drake puts a 1 kg sphere there"),
    ],
    ids=["tensor-on-zero-mass", "negative-mass"],
)
def test_a_massless_frame_engines_replace_stays_an_error(lint, body, why):
    finding = on(lint(trunk_with(("imu", body, "fixed"))), "imu")["IN002"]
    assert finding.severity is Severity.ERROR, why


def test_a_configured_severity_wins(lint):
    found = on(
        lint(trunk_with(("camera", CAMERA, "fixed")), severities={"IN023": Severity.ERROR}),
        "camera",
    )
    assert found["IN023"].severity is Severity.ERROR
    assert found["IN020"].severity is Severity.WARNING


def test_a_frame_on_a_light_body_is_judged_by_that_body(lint):
    # the same camera on a 2 g trunk is half of what the engines integrate
    light = robot(
        link("world"),
        joint("world", "trunk"),
        link("trunk", inertial(2e-5, 1e-8), collision(box(0.01, 0.01, 0.01))),
        joint("trunk", "camera", "fixed", xyz=(0.2, 0, 0)),
        link("camera", CAMERA),
    )
    assert on(lint(light, "IN023"), "camera")["IN023"].severity is Severity.ERROR


def test_the_trunk_itself_is_not_lowered_by_the_frames_it_carries(lint):
    izz = box_moments(*TRUNK)[2]
    wrong = robot(
        link("world"),
        joint("world", "trunk"),
        link("trunk", inertial(TRUNK[0], 10 * izz), collision(box(*TRUNK[1]))),
        joint("trunk", "camera", "fixed", xyz=(0.2, 0, 0)),
        link("camera", inertial(1e-5, 1e-8)),
    )
    assert on(lint(wrong, "IN023"), "trunk")["IN023"].severity is Severity.ERROR


def test_a_massless_frame_is_left_as_it_is_by_fill(tmp_path):
    # a massless collision shell welded to the trunk (Unitree A1's `FL_thigh_shoulder`):
    # inertia-fill --fix invalid gave it the 0.17 kg of its cylinder while IN002 was an error
    from click.testing import CliRunner

    from inertia_kit.cli.fill import fill_command

    shell = inertial(0, 0) + collision(box(0.05, 0.05, 0.05))
    path = tmp_path / "robot.urdf"
    path.write_text(trunk_with(("shell", shell, "fixed")))
    before = path.read_bytes()
    result = CliRunner().invoke(fill_command, ["--fix", "invalid", str(path)])
    assert result.exit_code == 0, result.output
    assert path.read_bytes() == before
    # the same shell on a moving joint needs its mass
    path.write_text(trunk_with(("shell", shell, "revolute")))
    assert CliRunner().invoke(fill_command, ["--fix", "invalid", str(path)]).exit_code == 1


def test_a_massless_frame_welded_to_the_world_is_no_error(lint):
    text = trunk_with(("base", inertial(0, 0), "fixed")).replace(
        '<joint name="j_trunk" type="revolute">', '<joint name="j_trunk" type="fixed">'
    )
    assert '<joint name="j_trunk" type="fixed">' in text
    (finding,) = [f for f in lint(text, "IN002") if f.link == "base"]
    assert finding.severity is Severity.INFO
    assert "it is welded to the world, which engines never move" in finding.detail


def test_a_body_whose_own_values_are_no_real_part_cannot_make_a_frame_negligible(lint):
    # the trunk's tensor in kg·mm² (a million times its box's) makes the frame's share of the
    # body's moments tiny; left out as no real part's, the frame is judged against what remains
    trunk, box_size = TRUNK
    moments = [1e6 * m for m in box_moments(trunk, box_size)]
    slipped = robot(
        link("world"),
        joint("world", "trunk"),
        link("trunk", inertial(trunk, *moments), collision(box(*box_size))),
        joint("trunk", "camera", "fixed", xyz=(0.2, 0, 0)),
        link("camera", CAMERA),
        joint("trunk", "mount", "fixed", xyz=(0.1, 0, 0)),
        link("mount", box_inertial(0.01, (0.02, 0.02, 0.02)), collision(box(0.02, 0.02, 0.02))),
    )
    found = on(lint(slipped), "camera")
    assert found["IN023"].severity is Severity.ERROR
    assert "it adds" not in (found["IN023"].detail or "")
    # with the trunk's own values the camera is negligible beside it (not beside a 10 g mount)
    plain = slipped.replace(inertial(trunk, *moments), box_inertial(trunk, box_size))
    assert on(lint(plain), "camera")["IN023"].severity is Severity.WARNING


def test_a_massless_frame_beside_no_real_part_is_still_info(lint):
    # a zero-mass frame adds nothing to any body, whatever its other members declare
    trunk, box_size = TRUNK
    moments = [1e6 * m for m in box_moments(trunk, box_size)]
    text = robot(
        link("world"),
        joint("world", "trunk"),
        link("trunk", inertial(trunk, *moments), collision(box(*box_size))),
        joint("trunk", "tool", "fixed", xyz=(0.2, 0, 0)),
        link("tool", inertial(0, 0)),
    )
    assert on(lint(text), "tool")["IN002"].severity is Severity.INFO
