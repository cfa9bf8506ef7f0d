"""Package lookup without ROS (precedence, discovery, fallbacks) and mesh URI resolution."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from kit import REPO
from kit.meshes import write_box_stl

from inertia_kit.description.package_files import package_name
from inertia_kit.description.urdf.packages import PackageResolver, resolve_uri

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


def hostile_workspace(tmp_path: Path) -> Path:
    """A workspace ``src`` holding loops of links (a <-> b, a link to itself, a link to its
    parent folder, a dangling link) beside a package ``real_pkg`` two levels down."""
    src = tmp_path / "ws" / "src"
    package = make_package(src / "group" / "real_pkg", "real_pkg")
    (src / "a").symlink_to("b")
    (src / "b").symlink_to("a")
    (src / "self").symlink_to("self")
    (src / "group" / "up").symlink_to("..")
    (src / "gone").symlink_to("nowhere")
    touch(package / "urdf" / "robot.urdf", "<robot/>")
    return src


def test_loops_of_links_are_passed_over_and_each_folder_visited_once(tmp_path):
    from inertia_kit.description.package_files import walk

    src = hostile_workspace(tmp_path)
    robot = src / "group" / "real_pkg" / "urdf" / "robot.urdf"
    for resolver in (
        PackageResolver(start=robot, env={}),
        PackageResolver([src], env={}),
        PackageResolver([src / "a"], env={"ROS_PACKAGE_PATH": str(src / "self")}),
    ):
        assert resolver.find("unknown_pkg") is None
        assert resolver.resolve("package://unknown_pkg/m.stl", robot).path is None
    assert PackageResolver([src], env={}).find("real_pkg") == src / "group" / "real_pkg"
    visited = [p.relative_to(src) for p in walk(src)]
    assert sorted(map(str, visited)) == [".", "group", "group/real_pkg"]


def test_a_folder_with_more_entries_than_the_bound_is_read_up_to_it(tmp_path, monkeypatch):
    from inertia_kit.description import package_files

    for index in range(30):
        (tmp_path / f"f{index:02}").mkdir()
    assert len(package_files.folder_entries(tmp_path)) == 30
    assert len(package_files.folder_entries(tmp_path, limit=7)) == 7
    monkeypatch.setattr(package_files, "MAX_ENTRIES", 5)
    assert len(list(package_files.walk(tmp_path))) == 1 + 5


def test_the_walks_of_one_search_are_bounded_together(tmp_path, monkeypatch):
    from inertia_kit.description.urdf import package_lookup

    folder = tmp_path
    for _ in range(6):  # a `src` at every level, each with 20 folders
        for index in range(20):
            (folder / "src" / f"f{index}").mkdir(parents=True)
        folder = folder / "src" / "f0"
    robot = touch(folder / "robot.urdf", "<robot/>")
    walked: list[Path] = []
    real = package_lookup.walk
    monkeypatch.setattr(
        package_lookup,
        "walk",
        lambda root, limit=10**9: (walked.append(f) or f for f in real(root, limit)),
    )
    monkeypatch.setattr(package_lookup, "MAX_FOLDERS_IN_ALL", 50)
    assert PackageResolver(start=robot, env={}).find("unknown_pkg") is None
    assert 0 < len(walked) <= 50


def test_lint_with_loops_under_the_workspace_and_the_package_path(tmp_path):
    from click.testing import CliRunner

    from inertia_kit.cli import lint_main

    src = hostile_workspace(tmp_path)
    robot = src / "group" / "real_pkg" / "urdf" / "robot.urdf"
    robot.write_text(
        '<robot name="r"><link name="base"><collision><geometry>'
        '<mesh filename="package://unknown_pkg/m.stl"/></geometry></collision></link></robot>'
    )
    for extra in ([], ["--package-path", str(src)], ["--package-path", str(src / "a")]):
        result = CliRunner().invoke(lint_main, ["--output-format", "concise", *extra, str(robot)])
        assert result.exit_code == 1, result.output
        assert "IN030" in result.output and "internal error" not in result.output


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
        # names longer than the file system allows (OSError from stat): not found, no raise
        ("a" * 300 + ".stl", "does not exist"),
        ("package://" + "p" * 300 + "/x.stl", "not found"),
        ("$(find " + "q" * 300 + ")/x.stl", "not found"),
        ("/" + "d" * 300 + "/x.stl", "does not exist"),
    ],
)
def test_resolve_uri_problems_never_raise(meshes, uri, fragment):
    _, problem = PackageResolver(env={}).resolve_uri(uri, meshes["urdf_dir"])
    assert problem is not None and fragment in problem


# --- the resolution rules, one at a time ------------------------------------------------------


def register(prefix: Path, name: str) -> Path:
    """An install prefix whose ament resource index registers ``name``; its share folder."""
    touch(prefix / "share" / "ament_index" / "resource_index" / "packages" / name, "")
    share = prefix / "share" / name
    share.mkdir(parents=True, exist_ok=True)
    return share


def resolve(uri: str, file: Path, paths=(), env=None):
    return PackageResolver(paths, start=file, env=env or {}).resolve(uri, file.parent)


@pytest.fixture
def robot_file(tmp_path: Path) -> Path:
    return touch(tmp_path / "robot" / "urdf" / "robot.urdf", "<robot/>")


def test_rule_package_path(tmp_path, robot_file):
    mesh = touch(make_package(tmp_path / "pkgs" / "deep" / "arm", "arm") / "m" / "a.stl")
    found = resolve("package://arm/m/a.stl", robot_file, [tmp_path / "pkgs"])
    assert (found.path, found.rule, found.problem) == (mesh, "package-path", None)
    assert "package.xml names it" in found.how


def test_rule_ros_package_path(tmp_path, robot_file):
    mesh = touch(make_package(tmp_path / "ros" / "arm", "arm") / "m" / "a.stl")
    found = resolve(
        "package://arm/m/a.stl", robot_file, env={"ROS_PACKAGE_PATH": str(mesh.parents[2])}
    )
    assert (found.path, found.rule) == (mesh, "ros-package-path")


def test_rule_ament_prefix_path_with_the_resource_index(tmp_path, robot_file):
    mesh = touch(register(tmp_path / "install", "arm") / "m" / "a.stl")
    found = resolve(
        "package://arm/m/a.stl", robot_file, env={"AMENT_PREFIX_PATH": str(tmp_path / "install")}
    )
    assert (found.path, found.rule) == (mesh, "ament")
    assert "registered in the ament index of AMENT_PREFIX_PATH" in found.how


@pytest.mark.parametrize("given", ["prefix", "share"])
def test_rule_ament_prefix_given_as_package_path(tmp_path, robot_file, given):
    # a package path that is an install prefix, or its share folder, is searched as a prefix:
    # the registered name wins over what package.xml says
    share = register(tmp_path / "install", "my-robot")
    make_package(share, "my_robot_description")
    mesh = touch(share / "m" / "a.stl")
    entry = tmp_path / "install" if given == "prefix" else tmp_path / "install" / "share"
    found = resolve("package://my-robot/m/a.stl", robot_file, [entry])
    assert (found.path, found.rule) == (mesh, "ament")
    assert "the prefix given" in found.how


def test_rule_ament_prefix_above_the_file(tmp_path):
    share = register(tmp_path / "prefix", "my-robot")
    make_package(share, "my_robot_description")
    mesh = touch(share / "robots" / "arm" / "meshes" / "a.stl")
    urdf = touch(share / "robots" / "arm" / "urdf" / "arm.urdf", "<robot/>")
    found = resolve("package://my-robot/robots/arm/meshes/a.stl", urdf)
    assert (found.path, found.rule) == (mesh, "ament")
    assert "the prefix above the file" in found.how


def test_rule_enclosing_package_by_package_xml_name(tmp_path):
    package = make_package(tmp_path / "checkout" / "renamed", "arm_description")
    mesh = touch(package / "meshes" / "a.stl")
    urdf = touch(package / "urdf" / "arm.urdf", "<robot/>")
    found = resolve("package://arm_description/meshes/a.stl", urdf)
    assert (found.path, found.rule) == (mesh, "enclosing-package")
    assert found.how.endswith("(its package.xml names it)")


def test_rule_enclosing_package_by_folder_name_whatever_package_xml_says(tmp_path):
    package = make_package(tmp_path / "arm-data", "arm_descriptions")
    mesh = touch(package / "meshes" / "a.stl")
    urdf = touch(package / "urdf" / "arm.urdf", "<robot/>")
    found = resolve("package://arm-data/meshes/a.stl", urdf)
    assert (found.path, found.rule) == (mesh, "enclosing-package")
    assert "folder named like the package (its package.xml says `arm_descriptions`)" in found.how


def test_rule_next_to_the_file(tmp_path, robot_file):
    mesh = touch(robot_file.parent / "meshes" / "a.stl")
    assert resolve("meshes/a.stl", robot_file).rule == "next-to-file"
    # package:// stripped, as PyBullet reads it
    found = resolve("package://meshes/a.stl", robot_file)
    assert (found.path, found.rule) == (mesh, "next-to-file")
    assert found.how.startswith("package:// stripped")


def test_rule_search_path(tmp_path, robot_file):
    mesh = touch(tmp_path / "data" / "differential" / "ring.stl")
    found = resolve("differential/ring.stl", robot_file, [tmp_path / "data"])
    assert (found.path, found.rule) == (mesh, "search-path")
    assert found.searched == (
        f"next to the file: {robot_file.parent / 'differential' / 'ring.stl'}",
    )
    # package://pkg/rest stripped under each package path: Pinocchio's package directories,
    # also for package:/// (an empty package name, which Pinocchio joins with a double slash)
    touch(tmp_path / "data" / "arm" / "m" / "a.stl")
    assert resolve("package://arm/m/a.stl", robot_file, [tmp_path / "data"]).rule == "package-path"
    bare = touch(tmp_path / "share" / "arm_data" / "m" / "a.stl")
    make_package(bare.parents[1], "other_name")
    found = resolve("package://arm_data/m/a.stl", robot_file, [tmp_path / "share"])
    assert (found.path, found.rule) == (bare, "search-path")
    found = resolve("package:///arm_data/m/a.stl", robot_file, [tmp_path / "share"])
    assert (found.path, found.rule) == (bare, "search-path")


def test_rule_absolute(tmp_path, robot_file):
    mesh = touch(tmp_path / "abs" / "a.stl")
    assert resolve(str(mesh), robot_file).rule == "absolute"
    assert resolve(mesh.as_uri(), robot_file).rule == "absolute"


def test_rules_are_documented_in_order():
    from inertia_kit.description.urdf.package_lookup import RULES

    assert list(RULES) == [
        "package-path",
        "ros-package-path",
        "ament",
        "enclosing-package",
        "next-to-file",
        "search-path",
        "absolute",
    ]


# --- when candidates disagree -----------------------------------------------------------------


@pytest.fixture
def disagreeing(tmp_path: Path) -> dict[str, Path]:
    """``arm`` on the package path (package.xml only) and enclosing the file (with meshes)."""
    return {
        "given": make_package(tmp_path / "share" / "arm", "arm"),
        "enclosing": make_package(tmp_path / "site" / "arm"),
        "urdf": touch(tmp_path / "site" / "arm" / "urdf" / "arm.urdf", "<robot/>"),
    }


def test_the_candidate_holding_the_mesh_wins(disagreeing):
    mesh = touch(disagreeing["enclosing"] / "meshes" / "a.stl")
    found = resolve(
        "package://arm/meshes/a.stl", disagreeing["urdf"], [disagreeing["given"].parent]
    )
    assert (found.path, found.rule) == (mesh, "enclosing-package")
    assert found.searched[0] == (
        f"--package-path, package.xml names it, in {disagreeing['given'].parent}: "
        f"{disagreeing['given'] / 'meshes' / 'a.stl'}"
    )


def test_when_both_hold_it_the_first_rule_wins(disagreeing):
    touch(disagreeing["enclosing"] / "meshes" / "a.stl")
    mesh = touch(disagreeing["given"] / "meshes" / "a.stl")
    found = resolve(
        "package://arm/meshes/a.stl", disagreeing["urdf"], [disagreeing["given"].parent]
    )
    assert (found.path, found.rule) == (mesh, "package-path")


def test_when_none_holds_it_the_first_is_reported_with_every_place(disagreeing):
    found = resolve(
        "package://arm/meshes/a.stl", disagreeing["urdf"], [disagreeing["given"].parent]
    )
    assert found.rule is None and found.path == disagreeing["given"] / "meshes" / "a.stl"
    assert f"does not exist (package `arm` is {disagreeing['given']}" in found.problem
    places = [s.split(": ", 1)[1] for s in found.searched if ": /" in s]
    assert str(disagreeing["enclosing"] / "meshes" / "a.stl") in places
    assert str(disagreeing["urdf"].parent / "arm" / "meshes" / "a.stl") in places  # stripped


def test_find_takes_the_candidate_holding_what_follows(disagreeing):
    resolver = PackageResolver([disagreeing["given"].parent], env={})
    assert resolver.find("arm", disagreeing["urdf"]) == disagreeing["given"]
    assert resolver.find("arm", disagreeing["urdf"], "urdf/arm.urdf") == disagreeing["enclosing"]
    assert resolver.find("arm", disagreeing["urdf"], "nothing/here") == disagreeing["given"]


def test_xacro_find_uses_the_same_rules(disagreeing, tmp_path):
    # $(find arm)/urdf/parts.xacro: the package path's arm (package.xml only) lacks it; the
    # enclosing folder has it, and a mesh named through $(find) is labelled with that rule
    from inertia_kit.description.loader import load

    mesh = touch(disagreeing["enclosing"] / "meshes" / "a.stl")
    touch(
        disagreeing["enclosing"] / "urdf" / "parts.xacro",
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="part"><visual>'
        '<geometry><mesh filename="$(find arm)/meshes/a.stl"/></geometry></visual></link>'
        "</robot>",
    )
    top = touch(
        disagreeing["enclosing"] / "urdf" / "arm.urdf.xacro",
        '<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="$(find arm)/urdf/parts.xacro"/></robot>',
    )
    robot = load(top, package_paths=[disagreeing["given"].parent])
    geometry = robot.link("part").visuals[0].geometry
    assert (geometry.path, geometry.rule) == (str(mesh), "enclosing-package")


# --- the three layouts of issue 11, built small, through the commands -------------------------


def mesh_robot(*uris: str) -> str:
    shapes = "".join(
        f'<collision><geometry><mesh filename="{u}"/></geometry></collision>' for u in uris
    )
    return f'<robot name="r"><link name="part">{shapes}</link></robot>'


def example_robot_data(root: Path) -> dict[str, Path]:
    """As installed from PyPI: URIs say example-robot-data, so do the folder and the ament index
    under the install prefix; only package.xml says example_robot_descriptions."""
    share = register(root / "site-packages" / "cmeel.prefix", "example-robot-data")
    make_package(share, "example_robot_descriptions")
    ur = share / "robots" / "ur_description"
    write_box_stl(ur / "meshes" / "ur5" / "collision" / "base.stl", (0.1, 0.1, 0.1))
    write_box_stl(share / "robots" / "talos_data" / "meshes" / "torso.stl", (0.1, 0.1, 0.1))
    ur5 = touch(
        ur / "urdf" / "ur5_robot.urdf",
        mesh_robot(
            "package://example-robot-data/robots/ur_description/meshes/ur5/collision/base.stl"
        ),
    )
    talos = touch(
        share / "robots" / "talos_data" / "robots" / "talos.urdf",
        mesh_robot("package:///example-robot-data/robots/talos_data/meshes/torso.stl"),
    )
    return {"package_path": share, "ur5": ur5, "talos": talos}


def robot_properties_fingers(root: Path) -> dict[str, Path]:
    """share/robot_properties_fingers holds only a package.xml (found through --package-path
    share); the meshes are in site-packages/robot_properties_fingers, next to the URDFs."""
    share = register(root / "venv", "robot_properties_fingers")
    make_package(share, "robot_properties_fingers")
    package = root / "venv" / "lib" / "python3.11" / "site-packages" / "robot_properties_fingers"
    write_box_stl(package / "meshes" / "base.stl", (0.1, 0.1, 0.1))
    finger = touch(
        package / "urdf" / "finger.urdf",
        mesh_robot("package://robot_properties_fingers/meshes/base.stl"),
    )
    return {"package_path": share.parent, "finger": finger}


def pybullet_data(root: Path) -> dict[str, Path]:
    """Mesh paths relative to PyBullet's search path (the data root), and package:// URIs that
    PyBullet reads with package:// stripped, next to the URDF."""
    data = root / "pybullet_data"
    write_box_stl(data / "differential" / "diff_ring.stl", (0.1, 0.1, 0.1))
    write_box_stl(data / "franka_panda" / "meshes" / "link0.stl", (0.1, 0.1, 0.1))
    ring = touch(data / "differential" / "diff_ring.urdf", mesh_robot("differential/diff_ring.stl"))
    panda = touch(data / "franka_panda" / "panda.urdf", mesh_robot("package://meshes/link0.stl"))
    return {"package_path": data, "diff_ring": ring, "panda": panda}


LAYOUTS = {
    "example-robot-data": (example_robot_data, {"ur5": "ament", "talos": "search-path"}),
    "robot_properties_fingers": (robot_properties_fingers, {"finger": "enclosing-package"}),
    "pybullet": (pybullet_data, {"diff_ring": "search-path", "panda": "next-to-file"}),
}


def invoke(command, *args: str):
    from click.testing import CliRunner

    try:
        runner = CliRunner(mix_stderr=False)  # click < 8.2
    except TypeError:
        runner = CliRunner()
    return runner.invoke(command, list(args), catch_exceptions=False)


@pytest.fixture
def no_ros(monkeypatch):
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)


@pytest.mark.parametrize("layout", sorted(LAYOUTS))
def test_issue_layouts_lint_without_in030(tmp_path, no_ros, layout):
    from inertia_kit.cli import lint_main

    build, _ = LAYOUTS[layout]
    files = build(tmp_path)
    robots = [str(p) for name, p in files.items() if name != "package_path"]
    args = ("--select", "IN030", "--package-path", str(files["package_path"]), *robots)
    result = invoke(lint_main, *args)
    assert result.exit_code == 0, result.stdout
    assert result.stdout == ""


@pytest.mark.parametrize("layout", sorted(LAYOUTS))
def test_issue_layouts_report_the_rule(tmp_path, no_ros, layout):
    import json

    from inertia_kit.cli import main

    build, rules = LAYOUTS[layout]
    files = build(tmp_path)
    for name, rule in rules.items():
        args = ("report", "--format", "json", "--package-path", str(files["package_path"]))
        result = invoke(main, *args, str(files[name]))
        assert result.exit_code == 0, result.stdout
        (mesh,) = json.loads(result.stdout)["links"][0]["meshes"]
        assert mesh["rule"] == rule, name
        assert Path(mesh["path"]).is_file() and mesh["problem"] is None


# --- the installed packages (skipped when absent) -------------------------------------------


def _installed(module: str) -> Path:
    imported = pytest.importorskip(module)
    return Path(next(iter(imported.__path__)))


def _site(relative: str) -> Path:
    import site

    for folder in site.getsitepackages():
        if (Path(folder) / relative).exists():
            return Path(folder) / relative
    pytest.skip(f"{relative} is not installed")


def _meshes(robot):
    from inertia_kit.description import model

    return [
        s.geometry
        for link in robot.links
        for s in (*link.visuals, *link.collisions)
        if isinstance(s.geometry, model.Mesh)
    ]


@pytest.mark.parametrize(
    ("relative", "rule"),
    [
        ("robots/ur_description/urdf/ur5_robot.urdf", "ament"),
        ("robots/talos_data/robots/talos_full_v2.urdf", "search-path"),
    ],
)
def test_installed_example_robot_data(no_ros, relative, rule):
    from inertia_kit.description.loader import load

    share = _site("cmeel.prefix/share/example-robot-data")
    if not (share / relative).is_file():
        pytest.skip(f"{relative} not in this example-robot-data")
    meshes = _meshes(load(share / relative, package_paths=[share]))
    assert meshes and all(m.path for m in meshes)
    assert {m.rule for m in meshes if m.filename.startswith("package:///")} <= {rule}
    assert rule in {m.rule for m in meshes}


def test_installed_robot_properties_fingers(no_ros):
    import sys

    from inertia_kit.description.loader import load

    package = _installed("robot_properties_fingers")
    share = Path(sys.prefix) / "share"
    if not (share / "robot_properties_fingers" / "package.xml").is_file():
        pytest.skip("no share/robot_properties_fingers in this environment")
    prefix = "package://robot_properties_fingers/"
    rules = set()
    for urdf in sorted((package / "urdf").rglob("*.urdf")):
        for mesh in _meshes(load(urdf, package_paths=[share])):
            # resolved exactly when the package holds the file (some URDFs of 2.0 name a
            # meshes/stl/ folder that the wheel does not ship)
            exists = (package / mesh.filename.removeprefix(prefix)).is_file()
            assert (mesh.path is not None) == exists, (urdf, mesh.filename)
            rules.add(mesh.rule)
    assert rules <= {"enclosing-package", None} and "enclosing-package" in rules


@pytest.mark.parametrize(
    ("relative", "rules"),
    [
        ("differential/diff_ring.urdf", {"search-path"}),
        ("racecar/racecar_differential.urdf", {"next-to-file", "search-path"}),
        ("franka_panda/panda.urdf", {"next-to-file"}),
        ("xarm/xarm6_with_gripper.urdf", {"next-to-file"}),
    ],
)
def test_installed_pybullet_data(no_ros, relative, rules):
    from inertia_kit.description.loader import load

    data = _installed("pybullet_data")
    if not (data / relative).is_file():
        pytest.skip(f"{relative} not in this pybullet_data")
    meshes = _meshes(load(data / relative, package_paths=[data]))
    assert meshes and all(m.path for m in meshes)
    assert {m.rule for m in meshes} == rules


def test_installed_pybullet_mesh_that_is_truly_absent(no_ros):
    # kuka_iiwa/model_for_sdf.urdf names meshes/coarse/, which pybullet_data does not ship
    from inertia_kit.description.loader import load

    data = _installed("pybullet_data")
    path = data / "kuka_iiwa" / "model_for_sdf.urdf"
    if not path.is_file() or (data / "kuka_iiwa" / "meshes" / "coarse").exists():
        pytest.skip("model_for_sdf.urdf not as in pybullet 3.2")
    missing = [m for m in _meshes(load(path, package_paths=[data])) if m.path is None]
    assert missing and all("coarse" in m.filename for m in missing)
    assert missing[0].searched[0].startswith("next to the file: ")
    assert any(s.startswith("search path (--package-path): ") for s in missing[0].searched)
