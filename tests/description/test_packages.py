"""Package lookup without ROS (precedence, discovery, fallbacks) and mesh URI resolution."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from kit import REPO

from inertia_kit.description.packages import PackageResolver, package_name, resolve_uri

EXAMPLES = REPO / "examples"


def make_package(folder: Path, name: str | None = None) -> Path:
    """A package folder; with ``name``, a ``package.xml`` naming it."""
    folder.mkdir(parents=True, exist_ok=True)
    if name is not None:
        (folder / "package.xml").write_text(
            f'<?xml version="1.0"?>\n<package format="3">\n  <name>{name}</name>\n</package>\n'
        )
    return folder


def touch(path: Path, text: str = "solid\nendsolid\n") -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


@pytest.fixture
def tiers(tmp_path: Path) -> dict[str, Path]:
    """``pkg_a`` in every tier: explicit path, ROS_PACKAGE_PATH, AMENT_PREFIX_PATH, workspace."""
    return {
        "explicit": make_package(tmp_path / "explicit" / "deep" / "pkg_a", "pkg_a"),
        "ros": make_package(tmp_path / "ros" / "pkg_a", "pkg_a"),
        "ament": make_package(tmp_path / "ament" / "share" / "pkg_a", "pkg_a"),
        "discovered": make_package(tmp_path / "ws" / "src" / "pkg_a", "pkg_a"),
        "input": touch(tmp_path / "ws" / "src" / "pkg_b" / "urdf" / "robot.urdf", "<robot/>"),
    }


def resolver_for(tiers: dict[str, Path], drop: set[str] = frozenset()) -> PackageResolver:
    env = {}
    if "ros" not in drop:
        env["ROS_PACKAGE_PATH"] = os.pathsep.join([str(tiers["ros"].parent), "/nonexistent"])
    if "ament" not in drop:
        env["AMENT_PREFIX_PATH"] = str(tiers["ament"].parent.parent)
    explicit = () if "explicit" in drop else (tiers["explicit"].parent.parent,)
    return PackageResolver(explicit, start=tiers["input"], env=env)


@pytest.mark.parametrize(
    ("drop", "expected"),
    [
        (set(), "explicit"),
        ({"explicit"}, "ros"),
        ({"explicit", "ros"}, "ament"),
        ({"explicit", "ros", "ament"}, "discovered"),
    ],
)
def test_precedence_explicit_ros_ament_discovery(tiers, drop, expected):
    assert resolver_for(tiers, drop).find("pkg_a") == tiers[expected]


def test_explicit_entry_may_be_the_package_itself(tmp_path):
    package = make_package(tmp_path / "some" / "where", "renamed_pkg")
    assert PackageResolver([package], env={}).find("renamed_pkg") == package


def test_package_xml_name_wins_over_folder_name(tmp_path):
    # examples/robot1's package.xml names it `myrobot`
    resolver = PackageResolver([EXAMPLES], env={})
    assert resolver.find("myrobot") == EXAMPLES / "robot1"
    assert resolver.find("robot1") is None
    assert resolver.find("mrm_description") == EXAMPLES / "mrm_description"


def test_folder_named_after_package_without_package_xml(tmp_path):
    bare = make_package(tmp_path / "descriptions" / "bare_description")
    assert PackageResolver([tmp_path / "descriptions"], env={}).find("bare_description") == bare
    assert PackageResolver([bare], env={}).find("bare_description") == bare
    rospath = {"ROS_PACKAGE_PATH": str(tmp_path / "descriptions")}
    assert PackageResolver(env=rospath).find("bare_description") == bare
    # an ancestor of the input named after the package
    robot = touch(bare / "urdf" / "robot.urdf", "<robot/>")
    assert PackageResolver(start=robot, env={}).find("bare_description") == bare


def test_discovery_walks_up_from_the_input(tmp_path):
    package = make_package(tmp_path / "repo" / "my_robot_description", "my_robot_description")
    robot = touch(package / "urdf" / "deep" / "robot.urdf", "<robot/>")
    sibling = make_package(tmp_path / "repo" / "my_robot_meshes", "my_robot_meshes")
    resolver = PackageResolver(start=robot, env={})
    assert resolver.find("my_robot_description") == package
    assert resolver.find("my_robot_meshes") == sibling
    assert resolver.find("nowhere_pkg") is None


def test_discovery_uses_near_before_start(tmp_path):
    first = make_package(tmp_path / "one" / "shared", "shared")
    second = make_package(tmp_path / "two" / "shared", "shared")
    resolver = PackageResolver(start=first, env={})
    assert resolver.find("shared") == first
    assert resolver.find("shared", near=second / "x.xacro") == second


def test_ignored_and_hidden_folders_are_skipped(tmp_path):
    make_package(tmp_path / "ws" / "ignored" / "pkg_x", "pkg_x")
    (tmp_path / "ws" / "ignored" / "COLCON_IGNORE").touch()
    make_package(tmp_path / "ws" / ".hidden" / "pkg_y", "pkg_y")
    resolver = PackageResolver([tmp_path / "ws"], env={})
    assert resolver.find("pkg_x") is None
    assert resolver.find("pkg_y") is None


def test_search_depth_is_bounded(tmp_path):
    deep = tmp_path.joinpath(*["d"] * 8, "deep_pkg")
    make_package(deep, "deep_pkg")
    assert PackageResolver([tmp_path], env={}).find("deep_pkg") is None


def test_results_are_cached(tmp_path):
    package = make_package(tmp_path / "pkgs" / "cached_pkg", "cached_pkg")
    resolver = PackageResolver([tmp_path / "pkgs"], env={})
    assert resolver.find("cached_pkg") == package
    (package / "package.xml").unlink()
    package.rmdir()
    assert resolver.find("cached_pkg") == package
    assert PackageResolver([tmp_path / "pkgs"], env={}).find("cached_pkg") is None


def test_environment_defaults_to_os_environ(tmp_path, monkeypatch):
    package = make_package(tmp_path / "env_pkg", "env_pkg")
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path))
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    assert PackageResolver().find("env_pkg") == package


def test_package_xml_is_read_without_entities(tmp_path):
    secret = touch(tmp_path / "secret.txt", "stolen_name")
    folder = tmp_path / "evil"
    folder.mkdir()
    (folder / "package.xml").write_text(
        f'<?xml version="1.0"?>\n<!DOCTYPE package [<!ENTITY e SYSTEM "{secret.as_uri()}">]>\n'
        "<package><name>&e;</name></package>\n"
    )
    assert package_name(folder) is None
    (folder / "package.xml").write_text("<package><name>broken</package>")
    assert package_name(folder) is None


# --- resolve_uri ----------------------------------------------------------------------------


@pytest.fixture
def meshes(tmp_path: Path) -> dict[str, Path]:
    package = make_package(tmp_path / "pkgs" / "robot_meshes", "robot_meshes")
    return {
        "package": package,
        "stl": touch(package / "meshes" / "arm link.stl"),
        "urdf_dir": (tmp_path / "robot" / "urdf"),
        "relative": touch(tmp_path / "robot" / "meshes" / "base.stl"),
    }


def test_resolve_package_uri(meshes):
    resolver = PackageResolver([meshes["package"].parent], env={})
    path, problem = resolver.resolve_uri(
        "package://robot_meshes/meshes/arm%20link.stl", meshes["urdf_dir"]
    )
    assert (path, problem) == (meshes["stl"], None)
    path, problem = resolver.resolve_uri("$(find robot_meshes)/meshes/arm link.stl", "/")
    assert (path, problem) == (meshes["stl"], None)


def test_resolve_package_uri_missing_package_says_what_to_do(meshes):
    path, problem = PackageResolver(env={}).resolve_uri(
        "package://no_such_pkg/meshes/a.stl", meshes["urdf_dir"]
    )
    assert path is None
    assert "`no_such_pkg` not found" in problem
    assert "--package-path" in problem


def test_resolve_package_uri_missing_file(meshes):
    resolver = PackageResolver([meshes["package"]], env={})
    path, problem = resolver.resolve_uri("package://robot_meshes/meshes/gone.stl", "/")
    assert path == meshes["package"] / "meshes" / "gone.stl"
    assert "does not exist" in problem
    assert str(meshes["package"]) in problem


def test_resolve_file_uris_and_paths(meshes):
    resolver = PackageResolver(env={})
    absolute = meshes["relative"]
    base = meshes["urdf_dir"]
    assert resolver.resolve_uri(absolute.as_uri(), base) == (absolute, None)
    assert resolver.resolve_uri(f"file://{absolute}", base) == (absolute, None)
    assert resolver.resolve_uri("file://../meshes/base.stl", base) == (absolute, None)
    assert resolver.resolve_uri("../meshes/base.stl", base) == (absolute, None)
    assert resolver.resolve_uri(str(absolute), "/elsewhere") == (absolute, None)
    # the module-level function builds a resolver near base_dir
    assert resolve_uri("../meshes/base.stl", base) == (absolute, None)


@pytest.mark.parametrize(
    ("uri", "fragment"),
    [
        ("../meshes/missing.stl", "does not exist"),
        ("file:///nonexistent/x.stl", "does not exist"),
        ("https://example.com/x.stl", "not resolved (nothing is fetched)"),
        ("", "empty mesh filename"),
        ("package:///x.stl", "names no package"),
        ("..", "is not a file"),
    ],
)
def test_resolve_uri_problems_never_raise(meshes, uri, fragment):
    _, problem = PackageResolver(env={}).resolve_uri(uri, meshes["urdf_dir"])
    assert problem is not None and fragment in problem
