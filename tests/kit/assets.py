"""An asset library for the scan tests: many small robots in ten folders."""

from __future__ import annotations

from pathlib import Path

from kit import urdf, write
from kit.meshes import write_box_stl


def asset_library(folder: Path, count: int, *, broken: bool = False) -> Path:
    """``count`` small robots in ten folders, a third with a mesh, a third with a wrong tensor;
    with ``broken``, the last of them an unreadable file (``g0/broken.urdf``)."""
    write_box_stl(folder / "meshes" / "box.stl", (0.1, 0.2, 0.3))
    for n in range(count - 1 if broken else count):
        body = [urdf.box_inertial(1.0 + n, (0.1, 0.2, 0.3))]
        if n % 3 == 1:
            body = [urdf.inertial(1.0 + n, 1.0, 1.0, 0.0)]
        shape = urdf.mesh("../meshes/box.stl") if n % 3 == 2 else urdf.box(0.1, 0.2, 0.3)
        write(
            folder / f"g{n % 10}" / f"r{n}.urdf",
            urdf.robot(urdf.link("l", *body, urdf.collision(shape))),
        )
    if broken:
        write(folder / "g0" / "broken.urdf", "<robot name='r'><link name='l'>")
    return folder
