"""
Files of the tree that are not what they seem, through the real commands: every file we read
(the robot, a xacro include, package.xml, configuration, ignore files, meshes and the buffers a
mesh names) replaced by a named pipe (a read would block for ever) or a link to ``/dev/zero``
(a read never ends), or larger than its bound. Each run ends at once: a clear message naming
the file (exit 2) where the file was needed, the file passed over where it is optional, never
a hang, a MemoryError or an internal error.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner
from kit import write
from kit.meshes import box_triangles, write_binary_stl
from kit.urdf import LIMIT

from inertia_kit.cli import lint_main

pytestmark = pytest.mark.skipif(
    not hasattr(os, "mkfifo") or not os.path.exists("/dev/zero"), reason="POSIX file system"
)

ROBOT = f"""\
<robot name="r">
  <link name="world"/>
  <joint name="j" type="revolute"><parent link="world"/><child link="arm"/>
    <axis xyz="0 0 1"/>{LIMIT}</joint>
  <link name="arm">
    <inertial><mass value="-1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><geometry><mesh filename="package://pkg/meshes/part.stl"/></geometry></collision>
  </link>
</robot>
"""
XACRO = """\
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="world"/>
  <xacro:include filename="inc.xacro"/>
</robot>
"""
INCLUDED = '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="b"/></robot>\n'


@pytest.fixture
def repo(tmp_path: Path) -> Path:
    """A git repository holding the package ``pkg``: a URDF with an STL mesh, a xacro robot
    with an include, a configuration file and a .gitignore."""
    root = tmp_path / "repo"
    (root / ".git" / "info").mkdir(parents=True)
    write(root / ".git" / "info" / "exclude", "# git's template\n")
    write(root / "pyproject.toml", "[tool.inertia-kit]\nignore = []\n")
    write(root / "pkg" / "package.xml", "<package><name>pkg</name></package>\n")
    write(root / "pkg" / ".gitignore", "*.gen.urdf\n")
    write(root / "pkg" / "urdf" / "robot.urdf", ROBOT)
    write(root / "pkg" / "urdf" / "robot.xacro", XACRO)
    write(root / "pkg" / "urdf" / "inc.xacro", INCLUDED)
    write_binary_stl(root / "pkg" / "meshes" / "part.stl", box_triangles((0.1, 0.1, 0.1)))
    return root


def plant(path: Path, kind: str) -> None:
    """Replace ``path`` by a named pipe or a symbolic link to ``/dev/zero``."""
    path.unlink()
    if kind == "fifo":
        os.mkfifo(path)
    else:
        path.symlink_to("/dev/zero")


def run(command: str, *args: str, cwd: Path) -> subprocess.CompletedProcess:
    """A console command in a child process, stopped (and failed) if it blocks."""
    code = f"import sys; from inertia_kit.cli import {command}; sys.exit({command}())"
    try:
        return subprocess.run(
            [sys.executable, "-c", code, *args],
            cwd=cwd,
            capture_output=True,
            text=True,
            timeout=60,
            env={**os.environ, "INERTIA_KIT_CACHE_DIR": str(cwd / ".cache")},
        )
    except subprocess.TimeoutExpired:
        pytest.fail(f"{command} {' '.join(args)} was still running after 60 s")


def assert_clean(result: subprocess.CompletedProcess) -> None:
    output = result.stdout + result.stderr
    assert "internal error" not in output and "Traceback" not in output, output


# (file planted, what to run on, expected exit code, a word of the message naming the file)
NEEDED = [
    ("pkg/urdf/robot.urdf", "pkg/urdf/robot.urdf", "robot.urdf"),
    ("pkg/urdf/inc.xacro", "pkg/urdf/robot.xacro", "inc.xacro"),
    ("pyproject.toml", "pkg", "pyproject.toml"),
    (".git/info/exclude", "pkg", "exclude"),
]


@pytest.mark.parametrize("kind", ["fifo", "zero"])
@pytest.mark.parametrize(("planted", "target", "named"), NEEDED)
def test_a_needed_file_that_is_not_a_regular_file_is_refused_naming_it(
    repo, kind, planted, target, named
):
    plant(repo / planted, kind)
    for command, args in (
        ("lint_main", ["--output-format", "concise"]),
        ("fill_main", ["--diff"]),
    ):
        result = run(command, *args, target, cwd=repo)
        assert_clean(result)
        assert result.returncode == 2, result.stdout + result.stderr
        assert named in result.stderr
        assert "not a regular file" in result.stderr


@pytest.mark.parametrize("kind", ["fifo", "zero"])
@pytest.mark.parametrize("planted", ["pkg/package.xml", "pkg/meshes/part.stl"])
def test_an_optional_file_that_is_not_a_regular_file_is_passed_over(repo, kind, planted):
    plant(repo / planted, kind)
    result = run("lint_main", "--output-format", "concise", "pkg/urdf/robot.urdf", cwd=repo)
    assert_clean(result)
    assert result.returncode == 1  # the negative mass, and the mesh not found
    assert "IN002" in result.stdout
    for command, args in (("main", ["report"]), ("main", ["view", "-o", "page.html"])):
        assert_clean(run(command, *args, "pkg/urdf/robot.urdf", cwd=repo))


def test_a_gitignore_linked_to_dev_zero_is_not_read_as_git_does(repo):
    plant(repo / "pkg" / ".gitignore", "zero")
    write(repo / "pkg" / "urdf" / "x.gen.urdf", ROBOT)
    result = run("lint_main", "--output-format", "concise", "pkg", cwd=repo)
    assert_clean(result)
    assert result.returncode == 1
    assert "x.gen.urdf" in result.stdout  # the link's patterns (none) were not read


def test_a_gitignore_that_is_a_named_pipe_is_refused_naming_it(repo):
    plant(repo / "pkg" / ".gitignore", "fifo")
    result = run("lint_main", "pkg", cwd=repo)
    assert_clean(result)
    assert result.returncode == 2
    assert ".gitignore: is a named pipe, not a regular file" in result.stderr


@pytest.mark.parametrize("name", ["pyproject.toml", "pkg/.gitignore"])
def test_configuration_and_ignore_files_over_their_bound_are_refused(repo, name):
    text = "[tool.inertia-kit]\n" if name.endswith(".toml") else ""
    write(repo / name, text + "# padding\n" * 200_000)  # 2 MB
    result = CliRunner().invoke(lint_main, [str(repo / "pkg")])
    assert result.exit_code == 2
    assert f"{Path(name).name}: is larger than 1 MB" in result.output


def test_a_robot_over_its_bound_is_refused_naming_it(repo, monkeypatch):
    from inertia_kit.description import safexml

    monkeypatch.setattr(safexml, "MAX_BYTES", 100)
    result = CliRunner().invoke(lint_main, [str(repo / "pkg" / "urdf" / "robot.urdf")])
    assert result.exit_code == 2
    assert "robot.urdf: is larger than 100 bytes; no robot description" in result.output


def test_stdin_over_the_bound_is_refused(monkeypatch):
    from inertia_kit.description import safexml

    monkeypatch.setattr(safexml, "MAX_BYTES", 100)
    result = CliRunner().invoke(lint_main, ["-"], input=ROBOT)
    assert result.exit_code == 2
    assert "larger than 100 bytes" in result.output


@pytest.mark.parametrize("suffix", [".stl", ".obj"])
def test_a_mesh_over_its_bound_is_unreadable_naming_it(repo, monkeypatch, suffix):
    from kit.meshes import obj

    from inertia_kit.physics import mesh_cache, mesh_formats

    monkeypatch.setattr(mesh_cache, "cache_dir", lambda *a, **k: None, raising=False)
    monkeypatch.setattr(mesh_formats, "MAX_STL_BYTES", 100)
    monkeypatch.setattr(mesh_formats, "MAX_MESH_BYTES", 100)
    mesh = repo / "pkg" / "meshes" / f"big{suffix}"
    if suffix == ".obj":
        write(mesh, obj(box_triangles((0.1, 0.1, 0.1))))
    else:
        write_binary_stl(mesh, box_triangles((0.1, 0.1, 0.1)))
    robot = write(repo / "pkg" / "urdf" / "big.urdf", ROBOT.replace("part.stl", mesh.name))
    # IN034's message names the file, its detail (shown by `full`) the bound
    result = CliRunner().invoke(lint_main, ["--output-format", "full", str(robot)])
    assert result.exit_code == 1, result.output
    assert f"big{suffix}" in result.output and "larger than 100 bytes" in result.output


def test_a_gltf_buffer_that_is_not_a_regular_file_is_not_read(repo):
    import trimesh

    folder = repo / "pkg" / "meshes"
    files = trimesh.creation.box((0.1, 0.1, 0.1)).export(file_type="gltf")
    for name, data in files.items():
        write(folder / name, data)
    buffer = next(name for name in files if name.endswith(".bin"))
    plant(folder / buffer, "fifo")
    robot = write(repo / "pkg" / "urdf" / "gltf.urdf", ROBOT.replace("part.stl", "model.gltf"))
    result = run("lint_main", "--output-format", "concise", str(robot), cwd=repo)
    assert_clean(result)
    assert result.returncode == 1
    assert "IN034" in result.stdout and "model.gltf" in result.stdout


def test_a_report_into_a_named_pipe_is_written_into_it_and_the_pipe_stays(tmp_path):
    """``-o`` a pipe another process reads (or, as root, ``/dev/null``: a rename over it made
    it a regular file for the whole system) is written into, never replaced."""
    import threading

    robot = write(tmp_path / "r.urdf", ROBOT)
    fifo = tmp_path / "report.json"
    os.mkfifo(fifo)
    received: list[bytes] = []
    reader = threading.Thread(target=lambda: received.append(fifo.read_bytes()), daemon=True)
    reader.start()
    result = CliRunner().invoke(
        lint_main, ["-q", "--output-format", "json", "-o", str(fifo), str(robot)]
    )
    reader.join(timeout=30)
    assert result.exit_code == 1, result.output
    assert received and b'"code": "IN' in received[0]
    assert fifo.is_fifo()


def test_a_named_pipe_among_the_files_of_a_folder_is_passed_over(tmp_path):
    """A walk reads the first bytes of each .xml to tell MJCF from other XML: a pipe there (or
    a link to one) waited for a writer for ever; a --list naming one is an unreadable asset."""
    write(tmp_path / "lib" / "r.urdf", ROBOT)
    for name in ("model.xml", "pipe.urdf"):
        os.mkfifo(tmp_path / "lib" / name)
    command = [sys.executable, "-m", "inertia_kit", "lint", "-q", "--exit-zero", "lib"]
    done = subprocess.run(command, cwd=tmp_path, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    (tmp_path / "list.txt").write_text("lib/pipe.urdf\nlib/r.urdf\n")
    command = [sys.executable, "-m", "inertia_kit", "scan", "-q", "--list", "list.txt"]
    done = subprocess.run(
        [*command, "-o", "o.jsonl"], cwd=tmp_path, capture_output=True, text=True, timeout=60
    )
    assert done.returncode == 1, done.stderr
    lines = (tmp_path / "o.jsonl").read_text().splitlines()
    assert '"status":"unreadable"' in lines[0] and "is a named pipe" in lines[0]
