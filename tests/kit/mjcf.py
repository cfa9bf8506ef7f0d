"""
MJCF for the tests: models compiled by the real MuJoCo (its values are what the reader must
give), also without their mesh files (the vendored Menagerie holds the XML only), and small
models written inline.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

#: the XML files (and licences) of a MuJoCo Menagerie snapshot: tests/data/menagerie/SOURCE.md
MENAGERIE = Path(__file__).resolve().parent.parent / "data" / "menagerie"


def menagerie_models() -> list[Path]:
    """Every whole model of the snapshot (root <mujoco> with a <worldbody>), sorted."""
    return sorted(
        path
        for path in MENAGERIE.glob("*/*.xml")
        if b"<worldbody" in path.read_bytes() and b"<mujoco" in path.read_bytes()
    )


def compiled_model(path: Path, *, without_meshes: bool = False):
    """
    ``mujoco.MjModel`` of the model at ``path``. ``without_meshes``: its mesh geoms made small
    spheres and its meshes, textures and height fields removed first (the files are not
    there), and every body that would infer its mass properties from a mesh given a stand-in
    ``<inertial>``: the bodies that wrote one, and those of primitives only, compile to their
    own values.
    """
    import mujoco

    spec = mujoco.MjSpec.from_file(str(path))
    if without_meshes:
        weighed_meshes = set()
        for geom in spec.geoms:
            if geom.meshname or geom.type == mujoco.mjtGeom.mjGEOM_HFIELD:
                weighed_meshes.add(geom.parent.name)
                geom.type = mujoco.mjtGeom.mjGEOM_SPHERE
                geom.size = np.array([0.01, 0.0, 0.0])
                geom.meshname = ""
                geom.hfieldname = ""
        for asset in [*spec.meshes, *spec.textures, *spec.hfields]:
            spec.delete(asset)
        for material in spec.materials:
            material.textures = [""] * len(material.textures)
        for body in spec.bodies[1:]:
            if not body.explicitinertial and body.name in weighed_meshes:
                body.explicitinertial = True
                body.mass = 1.0
                body.inertia = np.ones(3)
                body.ipos = np.zeros(3)
                body.iquat = np.array([1.0, 0, 0, 0])
    return spec.compile()


def body_mass_properties(mjmodel, body: int):
    """``(mass, com, principal moments sorted)`` of body ``body`` as MuJoCo compiled it."""
    return (
        float(mjmodel.body_mass[body]),
        np.array(mjmodel.body_ipos[body]),
        np.sort(np.array(mjmodel.body_inertia[body])),
    )


def written_mass_properties(inertial):
    """``(mass, com, principal moments sorted)`` of a model ``<inertial>``, in its body's frame."""
    from inertia_kit.physics.frames import rpy_matrix

    turn = rpy_matrix(inertial.origin.rpy)
    tensor = np.array(
        [
            [inertial.ixx, inertial.ixy, inertial.ixz],
            [inertial.ixy, inertial.iyy, inertial.iyz],
            [inertial.ixz, inertial.iyz, inertial.izz],
        ]
    )
    moments = np.sort(np.linalg.eigvalsh(turn @ tensor @ turn.T))
    return inertial.mass, np.array(inertial.origin.xyz), moments


def body_pose(mjmodel, body: int) -> np.ndarray:
    """The 4×4 pose of body ``body`` in its parent's frame, as MuJoCo compiled it."""
    import mujoco

    matrix = np.eye(4)
    rotation = np.zeros(9)
    mujoco.mju_quat2Mat(rotation, mjmodel.body_quat[body])
    matrix[:3, :3] = rotation.reshape(3, 3)
    matrix[:3, 3] = mjmodel.body_pos[body]
    return matrix
