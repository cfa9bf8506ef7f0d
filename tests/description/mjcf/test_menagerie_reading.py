"""
Every model of the vendored MuJoCo Menagerie snapshot (tests/data/menagerie/SOURCE.md) reads,
with its bodies in MuJoCo's order and names, each body where MuJoCo puts it, and each body's
written mass properties (mass, centre of mass, principal moments) what MuJoCo compiles, to
1e-9 relative (issue 22, item 6). The snapshot holds the XML only: the mesh geoms are made
small spheres for MuJoCo, which changes no body with an ``<inertial>``.
"""

from __future__ import annotations

import numpy as np
import pytest
from kit.mjcf import (
    MENAGERIE,
    body_mass_properties,
    body_pose,
    compiled_model,
    menagerie_models,
    written_mass_properties,
)

from inertia_kit.description import model
from inertia_kit.description.mjcf.reader import load_mjcf
from inertia_kit.physics.frames import transform

mujoco = pytest.importorskip("mujoco")

#: files of the snapshot MuJoCo itself refuses alone
REFUSED = {
    "aloha/filtered_cartesian_actuators.xml": "its actuators name `left/gripper`, which only "
    "the scene that attaches two arms has",
}
MODELS = [p for p in menagerie_models() if p.relative_to(MENAGERIE).as_posix() not in REFUSED]


def _relative(a: np.ndarray, b: np.ndarray, scale: float) -> float:
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b)))) / scale


def _mujoco_size(geometry) -> tuple[str, np.ndarray] | None:
    """A primitive of the model as MuJoCo's type and ``size`` (radii, half-lengths)."""
    if isinstance(geometry, model.Sphere):
        return "SPHERE", np.array([geometry.radius, 0, 0])
    if isinstance(geometry, model.Capsule):
        return "CAPSULE", np.array([geometry.radius, geometry.length / 2, 0])
    if isinstance(geometry, model.Cylinder):
        return "CYLINDER", np.array([geometry.radius, geometry.length / 2, 0])
    if isinstance(geometry, model.Box):
        return "BOX", np.array(geometry.size) / 2
    if isinstance(geometry, model.Ellipsoid):
        return "ELLIPSOID", np.array(geometry.radii)
    return None


def _same_primitives(link, mjmodel, body: int) -> None:
    """The body's geoms: as many as MuJoCo's, each primitive one with MuJoCo's type, size and
    pose (mesh geoms are placed by MuJoCo at their mesh's centroid: not compared here)."""
    shapes = [*link.visuals, *link.collisions]
    ids = [g for g in range(mjmodel.ngeom) if mjmodel.geom_bodyid[g] == body]
    assert len(shapes) == len(ids), link.name
    remaining = list(ids)
    for shape in shapes:
        primitive = _mujoco_size(shape.geometry)
        if primitive is None:
            continue
        kind, size = primitive
        pose = transform(shape.origin.xyz, shape.origin.rpy)
        for g in remaining:
            rotation = np.zeros(9)
            mujoco.mju_quat2Mat(rotation, mjmodel.geom_quat[g])
            same = (
                mjmodel.geom_type[g] == getattr(mujoco.mjtGeom, f"mjGEOM_{kind}")
                and np.allclose(size[size > 0], mjmodel.geom_size[g][size > 0], rtol=1e-9)
                and np.allclose(pose[:3, 3], mjmodel.geom_pos[g], rtol=1e-9, atol=1e-12)
                and _same_axes(kind, pose[:3, :3], rotation.reshape(3, 3))
            )
            if same:
                remaining.remove(g)
                break
        else:
            raise AssertionError(f"{link.name}: {shape.source} is not MuJoCo's geom")


def _same_axes(kind: str, ours: np.ndarray, theirs: np.ndarray) -> bool:
    """The same rotation (a sphere's needs none; a capsule's or cylinder's only its axis)."""
    if kind == "SPHERE":
        return True
    if kind in ("CAPSULE", "CYLINDER"):
        return bool(np.allclose(ours[:, 2], theirs[:, 2], atol=1e-9))
    return bool(np.allclose(ours, theirs, atol=1e-9))


def test_the_snapshot_is_there():
    assert len(MODELS) >= 170
    assert len({p.parent for p in MODELS}) >= 60


@pytest.mark.parametrize("path", MODELS, ids=lambda p: p.relative_to(MENAGERIE).as_posix())
def test_a_model_reads_as_mujoco_compiles_it(path):
    robot = load_mjcf(path)
    mjmodel = compiled_model(path, without_meshes=True)
    assert robot.format == "mjcf"
    assert robot.links[0].name == "world"
    assert len(robot.links) == mjmodel.nbody
    for body, link in enumerate(robot.links[1:], start=1):
        name = mujoco.mj_id2name(mjmodel, mujoco.mjtObj.mjOBJ_BODY, body)
        assert link.name == (name or f"body {body}")
        joint = robot.parent_joint(link.name)
        pose = transform(joint.origin.xyz, joint.origin.rpy)
        expected = body_pose(mjmodel, body)
        assert _relative(pose, expected, max(1.0, np.abs(expected).max())) < 1e-9, link.name
        _same_primitives(link, mjmodel, body)
        inertial = link.inertial
        if inertial is None or robot.inference.from_geometry == "always":
            continue  # tests/engines/test_mujoco_inference.py
        mass, com, moments = body_mass_properties(mjmodel, body)
        _, _, ours = written_mass_properties(inertial)
        assert abs(inertial.mass - mass) <= 1e-9 * mass, link.name
        assert _relative(ours, moments, max(moments.max(), 1e-300)) < 1e-9, link.name
        assert _relative(inertial.origin.xyz, com, max(1e-3, np.linalg.norm(com))) < 1e-9
