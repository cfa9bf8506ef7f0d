"""IN001 missing-inertial: which massless bodies are flagged, and the values the message gives."""

from __future__ import annotations

import pytest
from click.testing import CliRunner
from kit import REPO
from kit.moments import box_moments
from kit.urdf import LIMIT, box, collision, cylinder, inertial, joint, link, robot, visual

from inertia_kit.cli.lint import lint_command
from inertia_kit.lint.findings import Severity
from inertia_kit.physics.formatting import fmt

BOX = collision(box(0.1, 0.1, 0.3))
MASS = inertial(3, 0.025, 0.025, 0.005)


def in001(lint, text: str, **options):
    kw = {"options": {"IN001": options}} if options else {}
    return [f for f in lint(text, "IN001", **kw) if f.code == "IN001"]


def test_moving_link_without_inertial_gives_geometry_values(lint):
    findings = in001(lint, robot(link("world"), joint("world", "arm", name="j"), link("arm", BOX)))
    assert [f.link for f in findings] == ["arm"]
    (finding,) = findings
    volume = 0.1 * 0.1 * 0.3
    mass = 1000.0 * volume
    ixx, _, izz = box_moments(mass, (0.1, 0.1, 0.3))
    assert finding.message == "link `arm` moves on joint `j` but has no `<inertial>`"
    message = finding.detail
    assert "revolute joint `j`" in message
    assert f"{fmt(mass, 4)} kg at 1000 kg/m³" in message
    assert f"ixx = {fmt(ixx, 4)}" in message and f"izz = {fmt(izz, 4)}" in message
    assert "Gazebo drops it" in message and "MuJoCo fills in mass" in message
    assert "PyBullet gives it 1 kg" in message
    expected = finding.expected
    assert expected["mass"] == pytest.approx(mass)
    assert expected["volume"] == pytest.approx(volume)
    assert expected["ixx"] == pytest.approx(ixx) and expected["izz"] == pytest.approx(izz)
    assert expected["density"] == 1000.0
    assert finding.severity.name == "ERROR"


def test_without_collision_mujoco_refuses(lint):
    (finding,) = in001(lint, robot(link("world"), joint("world", "arm", name="j"), link("arm")))
    assert "mjMINVAL" in finding.detail and finding.expected is None


@pytest.mark.parametrize("kind", ["continuous", "prismatic", "floating", "planar"])
def test_every_moving_joint_type(lint, kind):
    findings = in001(
        lint, robot(link("world"), joint("world", "arm", kind, name="j"), link("arm", BOX))
    )
    assert [f.link for f in findings] == ["arm"]


def test_mimic_joint_moves(lint):
    text = robot(
        link("world"),
        joint("world", "a", name="j"),
        link("a", MASS + BOX),
        '<joint name="m" type="revolute"><parent link="world"/><child link="b"/>'
        f'<axis xyz="0 0 1"/>{LIMIT}<mimic joint="j" multiplier="1" offset="0"/></joint>',
        link("b", BOX),
    )
    assert [f.link for f in in001(lint, text)] == ["b"]


def test_massless_frames_on_fixed_joints_are_fine(lint):
    text = robot(
        link("world"),
        joint("world", "arm", name="j"),
        link("arm", MASS + BOX),
        joint("arm", "tool0", "fixed", name="tool"),
        link("tool0"),
        joint("arm", "camera", "fixed", name="cam"),
        link("camera", visual(box(0.02, 0.02, 0.02))),
    )
    assert in001(lint, text) == []


def test_massless_moving_link_welded_to_a_link_with_mass_is_lumped(lint):
    text = robot(
        link("world"),
        joint("world", "motor", name="j"),
        link("motor"),
        joint("motor", "arm", "fixed", name="w"),
        link("arm", MASS + BOX),
    )
    assert in001(lint, text) == []


def test_the_inertial_belongs_where_the_geometry_is(lint):
    text = robot(
        link("world"),
        joint("world", "motor", name="j"),
        link("motor"),
        joint("motor", "shell", "fixed", name="w"),
        link("shell", BOX),
    )
    (finding,) = in001(lint, text)
    assert finding.link == "shell"
    assert finding.message == "link `shell` moves with joint `j` but has no `<inertial>`"
    assert "`motor`" in finding.detail and "revolute joint `j`" in finding.detail
    assert finding.expected["mass"] == pytest.approx(3.0)


# --- the root: a massless base ----------------------------------------------------------------

WHEEL = inertial(0.3, 0.0004) + collision(cylinder(0.05, 0.02))


def wheeled(base: str = "", footprint: str = "") -> str:
    """A massless `base_footprint` with `base_link` (holding ``base``) welded to it, 2 wheels."""
    return robot(
        link("base_footprint", footprint),
        joint("base_footprint", "base_link", "fixed", name="footprint_joint"),
        link("base_link", base),
        joint("base_link", "left_wheel", "continuous", name="left"),
        link("left_wheel", WHEEL),
        joint("base_link", "right_wheel", "continuous", name="right"),
        link("right_wheel", WHEEL),
    )


def test_massless_base_above_wheels_says_what_each_engine_does(lint):
    (finding,) = in001(lint, wheeled(collision(box(0.4, 0.3, 0.1))))
    assert finding.link == "base_link" and finding.severity.name == "ERROR"
    assert finding.message == (
        "link `base_link` is welded to the root `base_footprint` but has no `<inertial>`: a "
        "massless base"
    )
    message = finding.detail
    assert "so the robot's base has no mass" in message
    assert (
        "Gazebo drops the base and with it every link below it (`left_wheel` and "
        "`right_wheel`), leaving nothing of the robot to simulate" in message
    )
    assert '"A model must have at least one link"' in message
    assert (
        "Drake makes it a free body without mass, so the robot moves as if it weighed only "
        "the 0.6 kg" in message
    )
    assert "PyBullet gives each of its 2 links 1 kg unless loaded with useFixedBase" in message
    assert "MuJoCo welds the root to the world" in message
    assert finding.expected["mass"] == pytest.approx(12.0)  # the box at 1000 kg/m³
    assert "`world` link by a fixed joint" in finding.help


@pytest.mark.parametrize(
    "base",
    [visual(box(0.4, 0.3, 0.1)), ""],
    ids=["visual-only", "no-geometry"],
)
def test_massless_base_without_collision_is_flagged_too(lint, base):
    (finding,) = in001(lint, wheeled(base))
    site = "base_link" if base else "base_footprint"
    assert finding.link == site and "carries moving links" in finding.detail
    assert "Gazebo drops the base" in finding.detail


def test_a_massless_root_frame_above_a_base_with_mass_is_fine(lint):
    assert in001(lint, wheeled(inertial(5, 0.05) + collision(box(0.4, 0.3, 0.1)))) == []


def test_floating_base_false_takes_the_root_as_fixed(lint):
    text = robot(link("base"), joint("base", "arm", name="j"), link("arm", MASS + BOX))
    (finding,) = in001(lint, text)
    assert finding.link == "base" and "carries moving links" in finding.detail
    assert in001(lint, text, floating_base=False) == []
    # collision geometry on the root still needs mass: it is a body, not a frame
    solid = robot(link("base", BOX), joint("base", "arm", name="j"), link("arm", MASS + BOX))
    assert [f.link for f in in001(lint, solid, floating_base=False)] == ["base"]


def test_many_links_below_are_counted(lint):
    chain = [link("base")]
    for i in range(7):
        chain += [joint("base" if i == 0 else f"l{i - 1}", f"l{i}"), link(f"l{i}", MASS + BOX)]
    (finding,) = in001(lint, robot(*chain))
    assert "(`l0`, `l1`, `l2`, `l3` and 3 more)" in finding.detail


def test_root_with_collision_geometry_needs_mass(lint):
    text = robot(link("base", BOX))
    (finding,) = in001(lint, text)
    assert finding.message == "link `base` is the root but has no `<inertial>`: a massless base"
    detail = finding.detail
    assert finding.link == "base" and "is the root and has collision geometry" in detail
    assert "Gazebo drops it, leaving nothing of the robot to simulate" in detail
    assert "Drake refuses to step it" in detail and "body base is not" in detail


@pytest.mark.parametrize("name", ["world"])
def test_a_world_root_is_the_world(lint, name):
    text = robot(link(name), joint(name, "arm", name="j"), link("arm", MASS + BOX))
    assert in001(lint, text) == []


def test_root_welded_to_a_world_link_is_static(lint):
    text = robot(
        link("world"),
        joint("world", "base", "fixed", name="anchor"),
        link("base", BOX),
        joint("base", "arm", name="j"),
        link("arm", MASS + BOX),
    )
    assert in001(lint, text) == []


def test_the_seed_wheeled_robot_through_the_command(monkeypatch):
    """The acceptance line: plain `inertia-lint` on the seed robot reports its massless base."""
    monkeypatch.chdir(REPO)
    result = CliRunner().invoke(
        lint_command,
        ["examples/my_robot_description/urdf/robot.xacro", "--output-format", "concise"],
    )
    assert result.exit_code == 1
    (line,) = [x for x in result.stdout.splitlines() if " IN001 " in x]
    assert line.startswith("examples/my_robot_description/urdf/robot.xacro:14:3: IN001 ")
    assert "link `base_link` is welded to the root `base_footprint`" in line
    assert "every link below it" not in line  # the detail: not in the concise line


def test_visual_only_root_alone_is_not_simulated(lint):
    text = robot(link("deco", visual(box(1, 1, 1))))
    assert in001(lint, text) == []


def test_a_broken_inertial_is_left_to_other_rules(lint):
    zero = inertial(0, 0)
    text = robot(link("world"), joint("world", "arm", name="j"), link("arm", zero + BOX))
    assert in001(lint, text) == []


def test_one_finding_per_body(lint):
    text = robot(
        link("world"),
        joint("world", "arm", name="j"),
        link("arm", BOX),
        joint("arm", "cover", "fixed", name="w"),
        link("cover", BOX),
    )
    (finding,) = in001(lint, text)
    assert finding.link == "arm" and "`cover`" in finding.detail


# --- a base made massless by its own layout ---------------------------------------------------

CASTER = inertial(0.1, 0.0001) + collision(box(0.05, 0.05, 0.05))
BASE_BOX = (0.4, 0.4, 0.1)


def with_caster(base: str, caster: str = CASTER) -> str:
    """:func:`wheeled`, and a caster (``caster``) welded below `base_link`."""
    text = wheeled(base)
    weld = joint("base_link", "caster", "fixed", name="caster_joint", xyz=(-0.15, 0, -0.05))
    return text.replace("</robot>", f"{weld}{link('caster', caster)}</robot>")


def test_a_base_whose_mass_is_a_small_welded_part_is_massless(lint):
    # the rover: a 0.4 × 0.4 × 0.1 m box without <inertial>, a root frame without one,
    # a 0.1 kg caster welded below
    (finding,) = in001(lint, with_caster(collision(box(*BASE_BOX))))
    volume = BASE_BOX[0] * BASE_BOX[1] * BASE_BOX[2]
    assert finding.link == "base_link" and finding.severity.name == "ERROR"
    assert finding.message == (
        f"link `base_link`: the base declares only 0.1 kg, {fmt(0.1 / volume, 2)} kg/m³ over "
        "its collision box"
    )
    message = finding.detail
    assert "declares only 0.1 kg (in `caster`)" in message
    assert f"{fmt(0.1 / volume, 2)} kg/m³ over its collision box" in message
    assert "below the plausible 50 kg/m³" in message
    assert "so the robot's base has almost no mass" in message
    assert "simulate a 0.1 kg base under the 0.6 kg of the links below it" in message
    assert finding.expected["mass"] == pytest.approx(1000.0 * volume)


def test_the_density_floor_is_an_option(lint):
    text = with_caster(collision(box(*BASE_BOX)))
    # 0.1 kg over 0.016 m³ is 6.25 kg/m³
    assert in001(lint, text, min_base_density=6.0) == []
    assert len(in001(lint, text, min_base_density=6.5)) == 1


def test_a_base_with_its_mass_on_a_welded_inertia_link_is_right(lint):
    # the mass on a welded link without geometry (a `base_inertia` link): 12 kg in the box
    text = with_caster(collision(box(*BASE_BOX)), inertial(12, 0.16))
    assert in001(lint, text) == []


def test_a_base_box_that_declares_a_light_mass_is_left_to_in022(lint):
    text = with_caster(inertial(0.1, 0.001) + collision(box(*BASE_BOX)))
    assert in001(lint, text) == []
    assert [f.link for f in lint(text, "IN022") if f.code == "IN022"] == ["base_link"]


def test_a_light_base_welded_to_the_world_is_static(lint):
    text = with_caster(collision(box(*BASE_BOX)))
    world = link("world") + joint("world", "base_footprint", "fixed", name="w")
    text = text.replace('<link name="base_footprint">', world + '<link name="base_footprint">')
    assert world in text
    assert in001(lint, text) == []


def test_a_base_shape_wider_than_a_robot_is_not_judged(lint):
    # a mesh in millimetres read as metres would be 400 m wide: its volume says nothing
    assert in001(lint, with_caster(collision(box(400, 400, 100)))) == []


def test_the_message_is_one_short_line_and_the_detail_has_the_basis(lint):
    findings = in001(lint, wheeled(collision(box(0.4, 0.3, 0.1))))
    findings += in001(lint, robot(link("world"), joint("world", "arm", name="j"), link("arm", BOX)))
    findings += in001(lint, with_caster(collision(box(*BASE_BOX))))
    for finding in findings:
        assert len(finding.message) <= 100, finding.message
        assert "Gazebo" in finding.detail and "1000 kg/m³" in finding.detail


# --- MJCF: a body without <inertial> is inferred, not missing -------------------------------


def _mjcf_findings(tmp_path, body: str):
    from inertia_kit.description.mjcf.reader import load_mjcf
    from inertia_kit.lint.runner import Selection, lint_robot

    path = tmp_path / "m.xml"
    path.write_text(
        '<mujoco><worldbody><body name="arm" pos="0 0 1"><joint type="hinge"/>'
        f"{body}</body></worldbody></mujoco>"
    )
    return path, [
        f for f in lint_robot(load_mjcf(path), Selection(("IN001",))) if f.code == "IN001"
    ]


def test_an_mjcf_body_weighed_at_the_default_density_is_told_what_mujoco_infers(tmp_path):
    mujoco = pytest.importorskip("mujoco")
    path, (finding,) = _mjcf_findings(tmp_path, '<geom type="box" size="0.1 0.05 0.2"/>')
    mass = mujoco.MjModel.from_xml_path(str(path)).body_mass[1]
    assert finding.severity is Severity.INFO
    assert finding.message == (
        f"body `arm`: no <inertial>; MuJoCo infers {fmt(mass, 4)} kg at the default 1000 kg/m³"
    )
    assert "inertiafromgeom" in finding.detail


@pytest.mark.parametrize(
    "body",
    [
        '<geom type="box" size="0.1 0.05 0.2" density="2700"/>',
        '<geom type="box" size="0.1 0.05 0.2" mass="3"/>',
        '<inertial pos="0 0 0" mass="1" diaginertia="0.01 0.01 0.01"/>'
        '<geom type="box" size="0.1 0.05 0.2"/>',
    ],
)
def test_an_mjcf_body_whose_mass_someone_chose_is_quiet(tmp_path, body):
    assert _mjcf_findings(tmp_path, body)[1] == []
