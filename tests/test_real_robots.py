"""
Published robot descriptions from PyPI packages, loaded file by file: whatever they hold, only
``InputError`` may escape ``load``, and what loads is a consistent model.

Each package is optional (skipped when not installed): ``pybullet`` (pybullet_data), ``rtb-data``
(Robotics Toolbox's xacro robots), ``example-robot-data``, ``dexmate-urdf``,
``fourier-robot-descriptions`` and ``airo-models``. Install them with ``pip install --no-deps``:
only their files are used.
"""

from __future__ import annotations

import importlib.metadata
import math
import os
import time
from collections import Counter
from pathlib import Path

import pytest

from inertia_kit.description import model
from inertia_kit.description.loader import load
from inertia_kit.errors import InputError

#: Files loaded per package at most; larger packages are sampled evenly, the same files each run.
MAX_FILES = 1500
#: Seconds one file may take to load (the slowest real file takes well under one).
MAX_SECONDS_PER_FILE = 10.0


def _module_folder(module: str) -> Path:
    imported = pytest.importorskip(module)
    return Path(next(iter(imported.__path__)))


def _distribution_folder(distribution: str, relative: str) -> Path:
    try:
        folder = Path(importlib.metadata.distribution(distribution).locate_file(relative))
    except importlib.metadata.PackageNotFoundError:
        pytest.skip(f"{distribution} is not installed")
    if not folder.is_dir():
        pytest.skip(f"{distribution} has no {relative}")
    return folder


#: name -> the folder its robot files live in (the data root passed as the package path)
PACKAGES = {
    "pybullet": lambda: _module_folder("pybullet_data"),
    "rtb-data": lambda: _module_folder("rtbdata"),
    "example-robot-data": lambda: _distribution_folder(
        "example-robot-data", "cmeel.prefix/share/example-robot-data"
    ),
    "dexmate-urdf": lambda: _module_folder("dexmate_urdf"),
    "fourier-robot-descriptions": lambda: _module_folder("fourier_robot_descriptions"),
    "airo-models": lambda: _module_folder("airo_models"),
}


@pytest.fixture(autouse=True)
def no_ros_environment(monkeypatch):
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)


def robot_files(root: Path) -> list[Path]:
    files = sorted(
        path
        for path in root.rglob("*")
        if path.name.endswith((".urdf", ".xacro")) and path.is_file()
    )
    if len(files) > MAX_FILES:
        step = len(files) / MAX_FILES
        files = [files[int(index * step)] for index in range(MAX_FILES)]
    return files


def check_consistent(robot: model.Robot, path: Path) -> None:
    """What every loaded robot must satisfy, however odd its file."""
    assert robot.files and robot.files[0] == str(path)
    if robot.fragment:
        assert robot.links == () and robot.joints == ()
        return
    for invalid in robot.invalid:
        assert isinstance(invalid, model.Invalid)
        try:
            value = float(invalid.text)
        except ValueError:
            continue
        # a text Python reads as a finite number is invalid only for URDF's stricter grammar
        assert not math.isfinite(value) or "_" in invalid.text or not invalid.text.isascii()
    for link in robot.links:
        assert link.source.path and link.source.line is not None
        for shape in (*link.visuals, *link.collisions):
            geometry = shape.geometry
            if isinstance(geometry, model.Mesh):
                if geometry.path is None:
                    assert geometry.problem
                else:
                    assert geometry.problem is None and os.path.isfile(geometry.path)


def sweep(root: Path) -> tuple[Counter, Counter, list[str]]:
    """Load every robot file below ``root``: (outcome counts, InputError messages, crashes)."""
    counts: Counter = Counter()
    errors: Counter = Counter()
    crashes: list[str] = []
    for path in robot_files(root):
        started = time.perf_counter()
        try:
            robot = load(path, package_paths=[root])
        except InputError as error:
            assert error.path is not None and error.message, path
            counts["input_error"] += 1
            errors[error.message.split(":")[0]] += 1
        except Exception as error:  # the point of the sweep
            crashes.append(f"{path.relative_to(root)}: {type(error).__name__}: {error}")
        else:
            check_consistent(robot, path)
            counts["fragment" if robot.fragment else "loaded"] += 1
            counts["invalid"] += len(robot.invalid)
            for link in robot.links:
                for shape in (*link.visuals, *link.collisions):
                    if isinstance(shape.geometry, model.Mesh):
                        counts["meshes"] += 1
                        counts["meshes_unresolved"] += shape.geometry.path is None
        elapsed = time.perf_counter() - started
        assert elapsed < MAX_SECONDS_PER_FILE, f"{path} took {elapsed:.1f} s"
    return counts, errors, crashes


@pytest.mark.parametrize("package", sorted(PACKAGES))
def test_only_input_errors_escape(package):
    root = PACKAGES[package]()
    counts, errors, crashes = sweep(root)
    print(f"\n{package}: {dict(counts)}; InputError: {dict(errors)}")
    assert crashes == []
    assert counts["loaded"] > 0
    # most published files are loadable robots: a regression would show here first
    total = counts["loaded"] + counts["fragment"] + counts["input_error"]
    assert counts["loaded"] + counts["fragment"] >= 0.7 * total


# --- notable robots ----------------------------------------------------------------------------


def test_pybullet_kuka_iiwa():
    root = PACKAGES["pybullet"]()
    robot = load(root / "kuka_iiwa" / "model.urdf", package_paths=[root])
    assert [link.name for link in robot.links] == [f"lbr_iiwa_link_{i}" for i in range(8)]
    assert len(robot.joints) == 7 and robot.root == "lbr_iiwa_link_0"
    assert all(link.inertial is not None for link in robot.links)
    meshes = [s.geometry for link in robot.links for s in (*link.visuals, *link.collisions)]
    assert meshes and all(isinstance(m, model.Mesh) and m.path for m in meshes)


@pytest.mark.parametrize(
    ("relative", "links"),
    [
        # ' <?xml version="0.0" ?>': a space first and version 0.0, both refused by libxml2
        ("bicycle/bike.urdf", 4),
        # a NUL byte after </robot>
        ("humanoid/humanoid.urdf", 16),
        # a blank line before the XML declaration, and the xacro namespace, unused
        ("differential/diff_ring.urdf", None),
    ],
)
def test_pybullet_files_that_tinyxml_reads(relative, links):
    root = PACKAGES["pybullet"]()
    path = root / relative
    if not path.is_file():
        pytest.skip(f"{relative} not in this pybullet_data")
    robot = load(path, package_paths=[root])
    assert robot.links and (links is None or len(robot.links) == links)
    for link in robot.links:
        line = path.read_bytes().split(b"\n")[link.source.line - 1]
        assert line[link.source.column - 1 : link.source.column] == b"<"


def test_pybullet_comma_separated_vector_is_invalid():
    root = PACKAGES["pybullet"]()
    path = root / "bicycle" / "bike.urdf"
    if not path.is_file():
        pytest.skip("bike.urdf not in this pybullet_data")
    robot = load(path, package_paths=[root])
    lines = path.read_text().split("\n")
    assert robot.invalid
    for invalid in robot.invalid:
        # xyz="0.07, 0, -0.69": urdfdom refuses it, PyBullet reads it
        assert invalid.attribute == "xyz" and "," in invalid.text
        line = lines[invalid.source.line - 1]
        assert line[invalid.source.column - 1 :].startswith("<origin")


def test_rtb_trossen_xacro_expands_through_find():
    root = PACKAGES["rtb-data"]()
    path = root / "xacro" / "trossen_descriptions" / "urdf" / "px100.urdf.xacro"
    if not path.is_file():
        pytest.skip("px100 not in this rtb-data")
    robot = load(path, package_paths=[root])
    assert robot.name == "px100" and len(robot.links) >= 10
    assert all(link.inertial is not None for link in robot.links)
    meshes = [s.geometry for link in robot.links for s in (*link.visuals, *link.collisions)]
    assert meshes and all(m.path for m in meshes if isinstance(m, model.Mesh))


def test_rtb_missing_package_names_the_include(tmp_path):
    root = PACKAGES["rtb-data"]()
    path = root / "xacro" / "kuka_description" / "kuka_kr10" / "urdf" / "kr10r1100sixx.xacro"
    if not path.is_file():
        pytest.skip("kr10 not in this rtb-data")
    with pytest.raises(InputError) as caught:
        load(path, package_paths=[root])
    assert "kuka_kr10_support" in caught.value.message
    assert (caught.value.path, caught.value.line) == (str(path), 3)


def test_example_robot_data_meshes_resolve_in_its_ament_prefix(monkeypatch):
    share = PACKAGES["example-robot-data"]()
    path = share / "robots" / "ur_description" / "urdf" / "ur5_robot.urdf"
    if not path.is_file():
        pytest.skip("ur5_robot.urdf not in this example-robot-data")
    # its URIs say package://example-robot-data, the folder name under share/ (package.xml
    # names the package example_robot_descriptions): found as an ament prefix
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(share.parent.parent))
    robot = load(path, package_paths=[share])
    meshes = [s.geometry for link in robot.links for s in (*link.visuals, *link.collisions)]
    assert meshes and all(m.path for m in meshes if isinstance(m, model.Mesh))


# --- inertia-fill on the xacro files -------------------------------------------------------------


@pytest.mark.parametrize("package", sorted(PACKAGES))
def test_fill_plans_on_real_xacro_files(package):
    """--fix all planned on every xacro robot (nothing written): only InputError escapes, the
    edits of a plan never overlap, and every file they change is still well-formed XML."""
    from lxml import etree

    from inertia_kit.fill.plan import plan_fill

    root = PACKAGES[package]()
    files = [p for p in robot_files(root) if p.suffix == ".xacro"]
    if not files:
        pytest.skip(f"{package} has no xacro files")
    counts: Counter = Counter()
    crashes: list[str] = []
    for path in files:
        try:
            plan = plan_fill(path, fix="all", package_paths=[root])
            changes = plan.changes()
        except InputError:
            counts["input_error"] += 1
            continue
        except Exception as error:  # the point of the sweep
            crashes.append(f"{path.relative_to(root)}: {type(error).__name__}: {error}")
            continue
        counts["planned"] += 1
        counts["links"] += len(plan.changed_links)
        counts["refused"] += len(plan.refused)
        counts["files_changed"] += len(changes)
        for source, text in changes:
            etree.fromstring(source.encode(text))  # raises on a broken edit
    print(f"\n{package}: {dict(counts)}")
    assert crashes == []
