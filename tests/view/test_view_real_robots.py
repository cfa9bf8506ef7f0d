"""
build_scene over a sample of the published robots (the packages of tests/test_real_robots.py,
each skipped when not installed): only ``InputError`` escapes, every scene is valid JSON with
every link, and no page carries more triangles than its budget.
"""

from __future__ import annotations

import json

import pytest
from test_real_robots import PACKAGES, robot_files

from inertia_kit.errors import InputError
from inertia_kit.view.scene import build_scene

#: files per package, spread evenly over its sorted files: the same ones each run
SAMPLE = 8


@pytest.fixture(autouse=True)
def no_ros_environment(monkeypatch):
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)


@pytest.mark.slow
@pytest.mark.parametrize("package", sorted(PACKAGES))
def test_scenes_of_published_robots(package):
    root = PACKAGES[package]()
    files = robot_files(root)
    sample = [files[int(i * len(files) / SAMPLE)] for i in range(min(SAMPLE, len(files)))]
    built = 0
    for path in sample:
        try:
            scene = build_scene(path, package_paths=[root], triangle_budget=100_000)
        except InputError as error:
            assert error.path is not None, path
            continue
        json.dumps(scene, allow_nan=False)
        assert scene["links"], path
        assert scene["budget"]["triangles"] <= 100_000, path
        for record in scene["links"]:
            for shape in record["visuals"]:
                assert 0 <= shape["mesh"] < len(scene["meshes"])
        built += 1
    assert built > 0
