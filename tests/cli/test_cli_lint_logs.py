"""
trimesh's and pycollada's logs never reach the terminal through the real `inertia-lint`: a
textured COLLADA file whose textures cannot be loaded (the image is missing, or Pillow is not
installed) made trimesh log "unable to load bumpmap" with a full traceback; a texture is
irrelevant to mass. The API side (a library user's logging set-up) is in
tests/physics/test_mesh_logs.py.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from console_scripts import console_script
from kit import write
from kit.meshes import box_triangles, textured_collada, without_pillow, write_textured_collada
from kit.urdf import collision, mesh, moving

SIZE = (0.1, 0.2, 0.3)  # 0.006 m³: 6 kg at the default 1000 kg/m³

ROBOT = moving(collision(mesh("part.dae")), "arm")


def lint_command(path: Path, pythonpath: Path | None = None) -> subprocess.CompletedProcess:
    env = dict(os.environ, INERTIA_KIT_NO_CACHE="1")  # every run reads the mesh
    if pythonpath is not None:
        env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(pythonpath), env.get("PYTHONPATH")]))
    return subprocess.run(
        [console_script("inertia-lint"), "--select", "IN001,IN034", str(path)],
        capture_output=True,
        text=True,
        env=env,
    )


@pytest.mark.parametrize("case", ["image-missing", "no-pillow"])
def test_textured_dae_gives_no_library_log_on_stderr(tmp_path: Path, case: str):
    robot = tmp_path / "robot"
    write_textured_collada(robot / "part.dae", box_triangles(SIZE), image=case == "no-pillow")
    path = write(robot / "robot.urdf", ROBOT)
    pythonpath = without_pillow(tmp_path / "no-pillow") if case == "no-pillow" else None

    done = lint_command(path, pythonpath)

    assert done.returncode == 1, done.stderr
    # no trimesh, no traceback: the summary, and the IN001 fix from the mesh it offers
    assert done.stderr.splitlines() == [
        "Found 1 error in 1 file.",
        "1 hidden fix can be enabled with the --unsafe-fixes option.",
    ]
    # the mass is computed from the triangles all the same
    assert "IN001" in done.stdout and "holds 0.006 m³: 6 kg" in done.stdout


def test_a_textured_dae_that_cannot_be_read_is_still_in034(tmp_path: Path):
    text = textured_collada(box_triangles(SIZE))
    write(tmp_path / "part.dae", text[: text.index("<library_geometries>") + 40])  # cut short
    path = write(tmp_path / "robot.urdf", ROBOT)

    done = lint_command(path)

    assert done.returncode == 1
    assert "IN034" in done.stdout and "cannot read the file as COLLADA" in done.stdout
    assert "Traceback" not in done.stderr and "trimesh" not in done.stderr


def test_real_textured_robots_give_no_library_log(tmp_path: Path):
    """example-robot-data's ANYmal and TIAGo meshes are textured DAE files (jpg, png)."""
    robots = Path(sys.prefix, "lib").glob(
        "python3*/site-packages/cmeel.prefix/share/example-robot-data/robots"
    )
    folder = next(iter(robots), None)
    if folder is None:
        pytest.skip("example-robot-data is not installed")
    files = [
        folder / "anymal_c_simple_description/urdf/anymal.urdf",
        folder / "anymal_b_simple_description/robots/anymal.urdf",
        folder / "tiago_description/robots/tiago.urdf",
    ]
    assert all(f.is_file() for f in files)
    env = dict(os.environ, INERTIA_KIT_NO_CACHE="1")
    env["PYTHONPATH"] = os.pathsep.join(
        filter(None, [str(without_pillow(tmp_path)), env.get("PYTHONPATH")])
    )
    done = subprocess.run(
        [console_script("inertia-lint"), *map(str, files)], capture_output=True, text=True, env=env
    )
    assert done.returncode == 1
    # the summary: counts, and the fixes offered
    summary = re.compile(r"Found |\[\*\] \d+ fixable with|\d+ hidden fix(es)? can be enabled")
    assert [line for line in done.stderr.splitlines() if not summary.match(line)] == []
