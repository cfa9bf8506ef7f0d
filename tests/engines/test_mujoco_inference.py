"""
A body's mass properties as MuJoCo compiles them (engines.mujoco_inference), against the real
MuJoCo: inferred from primitive geoms (each type, ``mass`` or ``density``, group range,
several geoms), ``inertiafromgeom`` true and false, the bounds and ``balanceinertia``, and the
compiler's refusals.
"""

from __future__ import annotations

import numpy as np
import pytest
from kit.mjcf import MENAGERIE, body_mass_properties, compiled_model, menagerie_models

from inertia_kit.analysis.links import analyse
from inertia_kit.description import model
from inertia_kit.description.mjcf.reader import load_mjcf
from inertia_kit.engines.mujoco_inference import compiled, counted, infers

mujoco = pytest.importorskip("mujoco")


def model_file(tmp_path, body: str, compiler: str = "") -> object:
    path = tmp_path / "m.xml"
    path.write_text(
        f'<mujoco><compiler {compiler}/><worldbody><body name="b" pos="0.1 0 0" euler="0 0 20">'
        f'<joint type="hinge"/>{body}</body></worldbody></mujoco>'
    )
    return path


def ours(path):
    robot = load_mjcf(path)
    return compiled(analyse(robot))["b"]


def assert_as_mujoco(path, result) -> None:
    mjmodel = mujoco.MjModel.from_xml_path(str(path))
    mass, com, moments = body_mass_properties(mjmodel, 1)
    properties = result.mass_properties
    assert result.refusal is None
    assert properties.mass == pytest.approx(mass, rel=1e-12)
    np.testing.assert_allclose(properties.com, com, rtol=1e-10, atol=1e-14)
    np.testing.assert_allclose(properties.principal_moments, moments, rtol=1e-9)


@pytest.mark.parametrize(
    "geoms",
    [
        '<geom type="sphere" size="0.1"/>',
        '<geom type="capsule" size="0.05 0.2" pos="0 0.1 0" euler="30 0 0"/>',
        '<geom type="cylinder" size="0.05 0.2" density="2700"/>',
        '<geom type="box" size="0.1 0.2 0.05" mass="3" pos="0.2 0 0"/>',
        '<geom type="ellipsoid" size="0.1 0.2 0.05" euler="10 20 30"/>',
        '<geom type="capsule" size="0.02" fromto="0 0 0 0.3 0.1 0"/>',
        '<geom type="box" size="0.1 0.1 0.1"/><geom type="sphere" size="0.05" pos="0 0 0.3"/>',
        '<geom type="box" size="0.1 0.1 0.1"/><geom type="sphere" size="0.3" group="4" '
        'density="0"/>',
        '<geom type="box" size="0.1 0.1 0.1"/><geom type="sphere" size="0.3" group="3"/>',
    ],
)
def test_inferred_from_primitives_as_mujoco(tmp_path, geoms):
    path = model_file(tmp_path, geoms, 'inertiagrouprange="0 2"' if 'group="3"' in geoms else "")
    result = ours(path)
    assert result.inferred
    assert_as_mujoco(path, result)


def test_inertiafromgeom_true_ignores_the_inertial(tmp_path):
    body = '<inertial pos="0 0 0" mass="9" diaginertia="1 1 1"/><geom type="box" size=".1 .2 .3"/>'
    path = model_file(tmp_path, body, 'inertiafromgeom="true"')
    result = ours(path)
    assert result.inferred and result.mass_properties.mass != 9
    assert_as_mujoco(path, result)


def test_the_bounds_raise_and_balance_averages(tmp_path):
    body = '<inertial pos="0 0 0" mass="0.001" diaginertia="1e-9 1e-3 5e-3"/>'
    path = model_file(tmp_path, body, 'boundmass="0.01" boundinertia="1e-6" balanceinertia="true"')
    result = ours(path)
    assert (result.raised, result.balanced) == (("mass", "inertia"), True)
    assert_as_mujoco(path, result)


@pytest.mark.parametrize(
    ("body", "compiler", "refusal"),
    [
        ('<inertial pos="0 0 0" mass="1" diaginertia="1 1 3"/>', "", "A + B >= C"),
        (
            '<geom type="box" size=".1 .1 .1" density="0"/><geom type="sphere" size=".1" '
            'density="0"/>',
            "",
            "moving bodies",
        ),
        ('<geom type="box" size=".1 .1 .1" density="0"/>', "", "moving bodies"),
    ],
)
def test_what_the_compiler_refuses(tmp_path, body, compiler, refusal):
    path = model_file(tmp_path, body, compiler)
    result = ours(path)
    assert refusal in result.refusal
    with pytest.raises(ValueError, match=refusal.replace("+", r"\+")):
        mujoco.MjModel.from_xml_path(str(path))


def test_a_welded_child_that_weighs_lets_a_weightless_body_move(tmp_path):
    child = '<body name="c"><geom type="sphere" size="0.1"/></body>'
    path = model_file(tmp_path, child)
    assert ours(path).refusal is None
    assert mujoco.MjModel.from_xml_path(str(path)).body_mass[1] == 0
    path = model_file(tmp_path, child.replace("<geom", '<joint type="hinge"/><geom'))
    assert "moving bodies" in ours(path).refusal
    with pytest.raises(ValueError, match="moving bodies"):
        mujoco.MjModel.from_xml_path(str(path))


#: the bodies of the vendored Menagerie that MuJoCo infers from primitives alone (its meshes are
#: not vendored: a body that counts one is left out), and the count this snapshot has
MENAGERIE_PRIMITIVE_BODIES = 70


def test_the_menagerie_bodies_inferred_from_primitives_are_mujocos():
    compared = 0
    for path in menagerie_models():
        if path.relative_to(MENAGERIE).as_posix() == "aloha/filtered_cartesian_actuators.xml":
            continue  # MuJoCo refuses it alone (tests/description/mjcf)
        robot = load_mjcf(path)
        mjmodel = compiled_model(path, without_meshes=True)
        bodies = compiled(analyse(robot))
        for index, link in enumerate(robot.links[1:], start=1):
            shapes = [s for s in (*link.visuals, *link.collisions) if counted(s, robot.inference)]
            meshes = any(isinstance(s.geometry, model.Mesh | model.Unknown) for s in shapes)
            if not infers(link, robot.inference) or meshes:
                continue
            compared += 1
            mass, com, moments = body_mass_properties(mjmodel, index)
            ours = bodies[link.name]
            assert ours.refusal is None, (path, link.name)
            properties = ours.mass_properties
            assert properties.mass == pytest.approx(mass, rel=1e-9, abs=1e-300), link.name
            if mass > 0:
                np.testing.assert_allclose(properties.principal_moments, moments, rtol=1e-9)
                np.testing.assert_allclose(properties.com, com, rtol=1e-9, atol=1e-12)
    assert compared == MENAGERIE_PRIMITIVE_BODIES


def _events(path):
    from inertia_kit.engines import mujoco as engine

    return engine.events(analyse(load_mjcf(path)))


def test_the_silent_changes_of_the_compiler_are_told(tmp_path):
    body = (
        '<inertial pos="0 0 0" mass="0.001" diaginertia="1e-9 1e-3 5e-3"/>'
        '<geom type="box" size="0.1 0.1 0.1"/>'
    )
    path = model_file(tmp_path, body, 'boundmass="0.01" boundinertia="1e-6" balanceinertia="true"')
    stages = [event.kind for event in _events(path)]
    assert stages == ["bound", "bound", "balance"]
    path = model_file(tmp_path, body, 'inertiafromgeom="true"')
    (event,) = _events(path)
    assert event.kind == "inertiafromgeom"
    assert (
        event.message == "link `b`: MuJoCo ignores its <inertial> for its geoms' (inertiafromgeom)"
    )


def test_a_refusal_is_told_with_mujocos_own_message(tmp_path):
    path = model_file(tmp_path, '<inertial pos="0 0 0" mass="1" diaginertia="1 1 3"/>')
    (event,) = _events(path)
    assert event.kind == "body"
    with pytest.raises(ValueError) as error:
        mujoco.MjModel.from_xml_path(str(path))
    assert event.engine_message in str(error.value)


def test_a_legacy_non_convex_mesh_is_told_with_the_volume_mujoco_counts(tmp_path):
    import trimesh

    bar = trimesh.creation.box((0.3, 0.1, 0.1))
    bar.apply_translation((0.1, 0, 0))
    other = trimesh.creation.box((0.1, 0.3, 0.1))
    other.apply_translation((0, 0.1, 0))
    shape = trimesh.boolean.union([bar, other], engine="manifold")
    shape.export(tmp_path / "l.stl")
    path = tmp_path / "m.xml"
    path.write_text(
        '<mujoco><asset><mesh file="l.stl"/></asset><worldbody><body name="b">'
        '<joint type="hinge"/><geom type="mesh" mesh="l"/></body></worldbody></mujoco>'
    )
    (event,) = _events(path)
    assert event.kind == "legacy"
    mass = mujoco.MjModel.from_xml_path(str(path)).body_mass[1]
    assert mass / 1000 == pytest.approx(shape.volume * (1 + event.facts["excess"]), rel=1e-6)
    assert "heavier than it encloses" in event.message


def test_a_visual_geom_weighed_with_the_colliding_ones_is_told(tmp_path):
    body = (
        '<geom type="box" size="0.1 0.1 0.1"/>'
        '<geom type="box" size="0.1 0.1 0.1" contype="0" conaffinity="0" group="2"/>'
    )
    (event,) = _events(model_file(tmp_path, body))
    assert event.kind == "visual"
    body = body.replace('group="2"', 'group="2" density="0"')
    assert _events(model_file(tmp_path, body)) == []


def test_settotalmass_scales_every_body_as_mujoco(tmp_path):
    path = tmp_path / "m.xml"
    path.write_text(
        '<mujoco><compiler settotalmass="10"/><worldbody><body name="a"><joint/>'
        '<geom type="box" size=".1 .2 .3"/><body name="b" pos="1 0 0"><joint/>'
        '<inertial pos="0.1 0 0" mass="2" diaginertia="1 2 3"/></body></body></worldbody></mujoco>'
    )
    bodies = compiled(analyse(load_mjcf(path)))
    mjmodel = mujoco.MjModel.from_xml_path(str(path))
    for index, name in ((1, "a"), (2, "b")):
        mass, com, moments = body_mass_properties(mjmodel, index)
        ours = bodies[name].mass_properties
        assert ours.mass == pytest.approx(mass, rel=1e-12)
        np.testing.assert_allclose(ours.com, com, atol=1e-15)
        np.testing.assert_allclose(ours.principal_moments, moments, rtol=1e-9)
