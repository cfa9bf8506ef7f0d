"""
``inertia-lint -j N``: the output of worker processes is byte-identical to one process's, in
every format and mode; bad values are usage errors; the mesh cache is shared safely.
"""

from __future__ import annotations

import json
import shutil
import time
import zlib
from pathlib import Path

import pytest
from click.testing import CliRunner
from kit import EXAMPLES
from test_real_robots import PACKAGES

from inertia_kit.cli.lint import lint_command
from inertia_kit.physics.mesh_cache import RACY_SECONDS
from inertia_kit.physics.mesh_cache_entries import decode

MODES = [
    ("--output-format", "full"),
    ("--output-format", "concise"),
    ("--output-format", "json"),
    ("--output-format", "github"),
    ("--output-format", "sarif"),
    ("--statistics",),
    ("--statistics", "--output-format", "json"),
    ("--diff",),
    ("--diff", "--unsafe-fixes"),
    ("--engine", "all", "--output-format", "concise"),
]


def lint(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(lint_command, [str(arg) for arg in args])
    return result.exit_code, result.stdout, result.stderr


def tree(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*.*"))}


@pytest.mark.parametrize("mode", MODES, ids=" ".join)
def test_two_jobs_print_what_one_prints_on_the_examples(mode, tmp_path, monkeypatch):
    monkeypatch.chdir(EXAMPLES.parent)
    monkeypatch.setenv("INERTIA_KIT_CACHE_DIR", str(tmp_path / "cache"))
    one = lint("-j", "1", *mode, "examples")
    assert one[0] in (1, 2) and (one[1] or "--statistics" in mode)  # the examples have findings
    assert lint("-j", "2", *mode, "examples") == one


def test_zero_jobs_and_the_default_print_what_one_prints(tmp_path, monkeypatch):
    """``-j 0`` and no ``-j``: the usable cores, a number of workers as ``-j 2`` is above (the
    formats and modes are the same code whatever the number; one of them here)."""
    monkeypatch.chdir(EXAMPLES.parent)
    monkeypatch.setenv("INERTIA_KIT_CACHE_DIR", str(tmp_path / "cache"))
    one = lint("-j", "1", "--output-format", "json", "examples")
    assert one[0] == 1 and json.loads(one[1])  # the examples have findings
    assert lint("-j", "0", "--output-format", "json", "examples") == one  # 0: the usable cores
    assert lint("--output-format", "json", "examples") == one  # the default: the usable cores


@pytest.mark.parametrize("example", sorted(p.name for p in EXAMPLES.iterdir()))
def test_two_jobs_on_each_example_and_its_files(example, monkeypatch):
    monkeypatch.chdir(EXAMPLES)
    files = sorted(str(p.relative_to(EXAMPLES)) for p in (EXAMPLES / example).rglob("*.*"))
    files = [f for f in files if f.endswith((".urdf", ".xacro"))]
    for given in ([example], files):
        assert lint("-j", "2", *given) == lint("-j", "1", *given)


@pytest.mark.parametrize("unsafe", [(), ("--unsafe-fixes",)])
def test_fix_with_two_jobs_writes_and_prints_what_one_does(unsafe, tmp_path, monkeypatch):
    outcomes = []
    for jobs in ("1", "2"):
        folder = tmp_path / f"j{jobs}"
        shutil.copytree(EXAMPLES, folder / "examples")
        monkeypatch.chdir(folder)
        before = tree(folder)
        outcomes.append((lint("-j", jobs, "--fix", *unsafe, "examples"), tree(folder)))
    assert outcomes[0] == outcomes[1]
    assert outcomes[0][1] != before  # the fixes wrote something


@pytest.mark.parametrize("value", ["-1", "x", "1.5", ""])
def test_a_bad_number_of_jobs_is_a_usage_error(value):
    code, stdout, stderr = lint("-j", value, str(EXAMPLES))
    assert (code, stdout) == (2, "")
    assert "Invalid value for '-j' / '--jobs'" in stderr
    assert "Traceback" not in stderr


def test_many_workers_fill_a_cold_mesh_cache_with_whole_entries(tmp_path, monkeypatch):
    """Eight robots share three meshes: eight workers race to store each entry."""
    package = Path(shutil.copytree(EXAMPLES / "pan_tilt_description", tmp_path / "pan_tilt"))
    robot = package / "urdf" / "pan_tilt.urdf"
    # 100 times the pan link's izz: the findings compare it with its mesh's
    robot.write_text(robot.read_text().replace('izz="0.000325256"', 'izz="0.0325256"'))
    for number in range(1, 8):
        shutil.copy(robot, robot.with_name(f"pan_tilt_{number}.urdf"))
    time.sleep(RACY_SECONDS + 0.1)  # a mesh changed more recently is not stored
    monkeypatch.chdir(tmp_path)
    runs = {}
    for jobs in ("1", "8"):
        monkeypatch.setenv("INERTIA_KIT_CACHE_DIR", str(tmp_path / f"cache{jobs}"))
        runs[jobs] = lint("-j", jobs, "--output-format", "json", "pan_tilt")
        entries = sorted((tmp_path / f"cache{jobs}").rglob("*.json"))
        assert len(entries) == 3  # one per mesh, each whole: its checksum and key hold
        for entry in entries:
            data = entry.read_bytes()
            assert int(data[:8], 16) == zlib.crc32(data[9:-1])
            document = json.loads(data[9:-1])
            decode(data, document["key"], document["code"])
            assert Path(document["key"]["path"]).parent == (package / "meshes").resolve()
    assert runs["8"] == runs["1"]
    assert {f["code"] for f in json.loads(runs["1"][1])} == {"IN011", "IN020", "IN023"}
    monkeypatch.setenv("INERTIA_KIT_CACHE_DIR", str(tmp_path / "cache8"))
    assert lint("-j", "8", "--output-format", "json", "pan_tilt") == runs["1"]  # warm


@pytest.mark.slow
@pytest.mark.parametrize("package", sorted(PACKAGES))
def test_two_jobs_print_what_one_prints_on_installed_robot_packages(package, tmp_path, monkeypatch):
    folder = str(PACKAGES[package]())  # skips when the package is not installed
    monkeypatch.setenv("INERTIA_KIT_CACHE_DIR", str(tmp_path / "cache"))
    for mode in (("--output-format", "concise"), ("--output-format", "json")):
        one = lint("-j", "1", *mode, "--package-path", folder, folder)
        assert one[1]
        assert lint("-j", "2", *mode, "--package-path", folder, folder) == one


def test_fill_accepts_jobs_and_does_what_it_does_without(monkeypatch):
    from inertia_kit.cli.fill import fill_command

    monkeypatch.chdir(EXAMPLES)

    def fill(*args: str) -> tuple[int, str, str]:
        result = CliRunner().invoke(fill_command, list(args))
        return result.exit_code, result.stdout, result.stderr

    without = fill("--check", ".")
    assert without[0] == 1  # an example has a link to fill
    assert fill("-j", "2", "--check", ".") == without
    assert fill("-j", "x", "--check", ".")[0] == 2
