"""Regenerate this example's STL meshes: `python make_meshes.py` (needs trimesh and manifold3d)."""

from pathlib import Path

import manifold3d
import numpy as np
import trimesh

HERE = Path(__file__).parent / "meshes"


def solid(manifold: manifold3d.Manifold) -> trimesh.Trimesh:
    mesh = manifold.to_mesh()
    return trimesh.Trimesh(np.asarray(mesh.vert_properties)[:, :3], np.asarray(mesh.tri_verts))


def main() -> None:
    HERE.mkdir(exist_ok=True)
    # base: a 120 × 120 × 50 mm housing, authored in metres, origin at its bottom centre
    base = manifold3d.Manifold.cube((0.12, 0.12, 0.05), center=True).translate((0, 0, 0.025))
    solid(base).export(HERE / "base.stl")
    # pan: a 80 mm turntable 30 mm high, authored in millimetres (the URDF scales it by 0.001)
    pan = manifold3d.Manifold.cylinder(30.0, 40.0, 40.0, circular_segments=96)
    solid(pan).export(HERE / "pan.stl")
    # tilt: a U bracket, two cheeks on a plate, in millimetres
    plate = manifold3d.Manifold.cube((70.0, 40.0, 6.0), center=True).translate((0, 0, 3.0))
    cheek = manifold3d.Manifold.cube((6.0, 40.0, 60.0), center=True)
    bracket = plate + cheek.translate((-32.0, 0, 30.0)) + cheek.translate((32.0, 0, 30.0))
    solid(bracket).export(HERE / "tilt_bracket.stl")


if __name__ == "__main__":
    main()
