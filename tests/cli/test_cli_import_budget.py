"""
What a lint run imports, checked by module name rather than by time (issue 13, item 5):
start-up is most of a run on a small robot, and a module that slips into the import graph of
every run costs every commit. ``benchmarks/lint.py`` times the same runs.
"""

from __future__ import annotations

import ast
import importlib.util
import os
import shutil
import subprocess
import sys
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest
from kit import write
from kit.meshes import box_triangles, write_textured_collada
from kit.urdf import box, box_inertial, collision, joint, link, mesh, robot

from inertia_kit.physics import mesh_cache

ROOT = Path(__file__).resolve().parents[2]


def _budget() -> ModuleType:
    """benchmarks/import_budget.py: the benchmark and these tests check the same lists."""
    path = ROOT / "benchmarks" / "import_budget.py"
    spec = importlib.util.spec_from_file_location("import_budget", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


#: a plain URDF needs no xacro, nor what xacro and its YAML and ``$(find)`` support pull in; a
#: warm cache reads no mesh file, so it needs no mesh library
NOT_FOR_PLAIN_URDF = _budget().NOT_FOR_PLAIN_URDF
NOT_FOR_WARM_CACHE = _budget().NOT_FOR_WARM_CACHE


def lint_and_list(paths: list[Path], heavy: tuple[str, ...], env: dict[str, str]) -> list[str]:
    """Run ``inertia-lint PATHS`` in a fresh interpreter; the ``heavy`` packages it imported."""
    code = (
        "import sys\n"
        "from inertia_kit.cli import lint_main\n"
        f"code = lint_main({[str(p) for p in paths]!r}, standalone_mode=False)\n"
        "assert code in (0, 1, None), code\n"
        f"heavy = {heavy!r}\n"
        "found = {h for h in heavy for m in sys.modules if m == h or m.startswith(h + '.')}\n"
        "print(sorted(found), file=sys.stderr)\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, env=env
    )
    assert done.returncode == 0, done.stderr
    return ast.literal_eval(done.stderr.strip().splitlines()[-1])


def environment(cache: Path) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k != mesh_cache.ENV_DISABLE}
    return {**env, "PYTHONPATH": str(ROOT), mesh_cache.ENV_DIR: str(cache)}


def test_plain_urdf_lint_imports_no_xacro_and_no_mesh_library(tmp_path: Path) -> None:
    size = (0.1, 0.2, 0.3)
    urdf = write(
        tmp_path / "arm.urdf",
        robot(
            link("base", box_inertial(2.0, size), collision(box(*size))),
            link("arm", box_inertial(1.0, size), collision(box(*size))),
            joint("base", "arm"),
        ),
    )
    heavy = NOT_FOR_PLAIN_URDF + NOT_FOR_WARM_CACHE
    assert lint_and_list([urdf], heavy, environment(tmp_path / "cache")) == []


def test_meshed_robot_on_a_warm_cache_imports_no_mesh_library(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A COLLADA mesh: read (by physics.collada) or served by the cache, it needs neither
    trimesh nor pycollada."""
    size = (0.1, 0.2, 0.3)
    dae = write_textured_collada(
        tmp_path / "meshes" / "part.dae",
        box_triangles(size, low=np.multiply(size, -0.5)),
        image=False,
    )
    urdf = write(
        tmp_path / "arm.urdf",
        robot(
            link("base", box_inertial(2.0, size), collision(mesh("meshes/part.dae"))),
            link("arm", box_inertial(1.0, size), collision(mesh("meshes/part.dae"))),
            joint("base", "arm"),
        ),
    )
    cache = tmp_path / "cache"
    env = environment(cache)
    # the miss reads the file (and the run may not store it: it was written just now)
    assert lint_and_list([urdf], NOT_FOR_WARM_CACHE, env) == []

    monkeypatch.setattr(mesh_cache, "RACY_SECONDS", 0.0)  # a file written just now is stored
    mesh_cache.cached_mesh_solid(dae, cache_dir=cache)
    assert lint_and_list([urdf], NOT_FOR_WARM_CACHE, env) == []


def test_xacro_lint_imports_no_web_modules(tmp_path: Path) -> None:
    """Writing the expanded tree escapes text as xml.sax.saxutils does, without importing it:
    saxutils pulls in urllib.request, http.client, email and ssl on every expansion.

    The package is linted from a copy outside any git repository: a ``.gitignore`` on the walk
    brings in pathspec, which with typing_extensions before 4.16 imports asyncio and so ssl,
    a chain of the environment's, not of writing the tree."""
    package = shutil.copytree(ROOT / "examples" / "mrm_description", tmp_path / "mrm_description")
    xacro = package / "urdf" / "mrm.xacro"
    web = ("urllib.request", "http.client", "email", "ssl", "xml.sax.saxutils")
    assert lint_and_list([xacro], ("xacro", *web), environment(tmp_path / "cache")) == ["xacro"]


def test_ignore_files_without_patterns_need_no_pathspec(tmp_path: Path) -> None:
    """git's template ``.git/info/exclude`` and a ``.gitignore`` of comments ignore nothing:
    the walk reads them without importing pathspec (5 to 20 ms, more with asyncio)."""
    (tmp_path / ".git" / "info").mkdir(parents=True)
    (tmp_path / ".git" / "info" / "exclude").write_text(
        "# git ls-files --others --exclude-from=.git/info/exclude\n# *.[oa]\n# *~\n"
    )
    (tmp_path / ".gitignore").write_text("# nothing ignored yet\n\n   \n")
    size = (0.1, 0.2, 0.3)
    write(tmp_path / "arm.urdf", robot(link("base", box_inertial(1.0, size)), link("arm")))
    env = environment(tmp_path / "cache")
    assert lint_and_list([tmp_path], ("pathspec",), env) == []
    (tmp_path / ".gitignore").write_text("# a pattern now\n\\#scratch.urdf\n")
    assert lint_and_list([tmp_path], ("pathspec",), env) == ["pathspec"]
