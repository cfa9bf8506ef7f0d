"""
The include graph of a repository (which robots read which files), its cache, and where the
repository is.
"""

from __future__ import annotations

import pytest
from kit import write
from kit.urdf import link_lines, robot_lines
from kit.xacro_projects import LEAF, age, middle, project, robot

from inertia_kit.lint import include_cache, include_graph
from inertia_kit.lint.fragments import repository_root


@pytest.fixture
def cache(tmp_path, monkeypatch):
    folder = tmp_path / "cache"
    monkeypatch.setenv("INERTIA_KIT_CACHE_DIR", str(folder))
    monkeypatch.delenv("INERTIA_KIT_NO_CACHE", raising=False)
    return folder


def _repository(root):
    package = project(
        root,
        {
            "urdf/leaf.xacro": LEAF,
            "urdf/middle.xacro": middle("leaf.xacro"),
            "urdf/arm.urdf.xacro": robot("middle.xacro", "a=1"),
            "urdf/plain.urdf": robot_lines(link_lines("only", 1, 0.1)),
        },
    )
    age(root)
    return package / "urdf"


def test_robots_and_the_files_they_read(tmp_path, cache):
    urdf = _repository(tmp_path / "repo")
    graph = include_graph.include_graph(tmp_path / "repo")
    arm = include_graph.real(urdf / "arm.urdf.xacro")
    assert graph.robots == {
        arm: (
            arm,
            include_graph.real(urdf / "middle.xacro"),
            include_graph.real(urdf / "leaf.xacro"),
        )
    }
    assert graph.includers(urdf / "leaf.xacro") == [arm]
    assert graph.includers(urdf / "middle.xacro") == [arm]
    assert graph.includers(urdf / "arm.urdf.xacro") == []  # not by itself
    assert (graph.scanned, graph.reused) == (4, 0)


def test_files_that_include_nothing_are_not_expanded(tmp_path, cache, monkeypatch):
    """The cheap first pass: leaf.xacro and plain.urdf name no include; only the robot and the
    middle fragment are expanded."""
    from inertia_kit.description.urdf import xacro_expand

    expanded = []
    real_expand = xacro_expand.expand

    def counting(path, **options):
        expanded.append(path)
        return real_expand(path, **options)

    monkeypatch.setattr(xacro_expand, "expand", counting)
    urdf = _repository(tmp_path / "repo")
    include_graph.include_graph(tmp_path / "repo")
    assert sorted(expanded) == sorted(
        include_graph.real(urdf / name) for name in ("arm.urdf.xacro", "middle.xacro")
    )


def test_only_robots_that_may_include_a_wanted_file_are_expanded(tmp_path, cache, monkeypatch):
    """Asked only for includers of given files, the graph expands what may include them (from
    the includes as written) and gives the same includers; what it ruled out is kept as its
    static closure, which answers a later run without reading the files again."""
    from inertia_kit.description import loader
    from inertia_kit.description.urdf import xacro_expand

    expanded, reached = [], []
    real_expand, real_reach = xacro_expand.expand, loader.files_reached

    def expanding(path, **options):
        expanded.append(path)
        return real_expand(path, **options)

    def reaching(path, *args, **options):
        reached.append(path)
        return real_reach(path, *args, **options)

    monkeypatch.setattr(xacro_expand, "expand", expanding)
    monkeypatch.setattr(loader, "files_reached", reaching)
    urdf = _repository(tmp_path / "repo")
    full = include_graph.include_graph(tmp_path / "repo", cache_dir=tmp_path / "other")
    robot, middle = (include_graph.real(urdf / name) for name in ("arm.urdf.xacro", "middle.xacro"))
    for name, expands, reaches, passed in (
        ("arm.urdf.xacro", [], [robot, middle], 2),  # neither can include the robot
        ("plain.urdf", [], [], 2),  # their closures, kept, say they cannot include it either
        ("leaf.xacro", [robot, middle], [], 0),  # they reach it: expanded
    ):
        expanded.clear()
        reached.clear()
        graph = include_graph.include_graph(tmp_path / "repo", wanted=[urdf / name])
        assert (sorted(expanded), sorted(reached)) == (sorted(expands), sorted(reaches)), name
        assert graph.includers(urdf / name) == full.includers(urdf / name)
        assert graph.passed == passed


def test_a_yaml_file_asked_about_is_not_answered_from_closures_that_leave_yaml_out(tmp_path, cache):
    """A closure kept for an XML file leaves load_yaml out: asked about a YAML file, the robot
    that loads it is expanded, and found to read it."""
    package = project(
        tmp_path / "repo",
        {
            "urdf/leaf.xacro": LEAF,
            "urdf/arm.urdf.xacro": robot("leaf.xacro", "a=${c}").replace(
                '<link name="base"/>',
                "<xacro:property name=\"c\" value=\"${xacro.load_yaml('c.yaml')['a']}\"/>\n"
                '  <link name="base"/>',
            ),
            "urdf/c.yaml": "a: 1\n",
        },
    )
    age(tmp_path / "repo")
    urdf = package / "urdf"
    ruled_out = include_graph.include_graph(tmp_path / "repo", wanted=[urdf / "arm.urdf.xacro"])
    assert ruled_out.passed == 1  # the robot: nothing it includes is the robot
    graph = include_graph.include_graph(tmp_path / "repo", wanted=[urdf / "c.yaml"])
    assert graph.includers(urdf / "c.yaml") == [include_graph.real(urdf / "arm.urdf.xacro")]


def test_a_robot_that_read_a_wanted_file_is_expanded_again(tmp_path, cache):
    """A stale entry that read a wanted file is scanned again, whatever its includes say now:
    broken by the change, it still reports the error for that file."""
    urdf = _repository(tmp_path / "repo")
    include_graph.include_graph(tmp_path / "repo")
    write(urdf / "arm.urdf.xacro", robot("nowhere.xacro", "a=1"))
    age(tmp_path / "repo")
    graph = include_graph.include_graph(tmp_path / "repo", wanted=[urdf / "leaf.xacro"])
    assert graph.includers(urdf / "leaf.xacro") == [include_graph.real(urdf / "arm.urdf.xacro")]


def test_the_cache_serves_a_second_scan_and_survives_corruption(tmp_path, cache):
    urdf = _repository(tmp_path / "repo")
    first = include_graph.include_graph(tmp_path / "repo")
    (stored,) = (cache / "includes-v2").glob("repo-*.json")
    second = include_graph.include_graph(tmp_path / "repo")
    assert (second.scanned, second.reused) == (0, 4)
    assert second.robots == first.robots

    for damage in (b"", b"garbage", stored.read_bytes()[:-20], b"00000000 {}"):
        stored.write_bytes(damage)
        again = include_graph.include_graph(tmp_path / "repo")
        assert (again.scanned, again.robots) == (4, first.robots)
    # rewritten whole
    assert include_graph.include_graph(tmp_path / "repo").scanned == 0
    assert urdf.exists()


def test_other_xacro_arguments_are_another_cache(tmp_path, cache):
    _repository(tmp_path / "repo")
    include_graph.include_graph(tmp_path / "repo")
    other = include_graph.include_graph(tmp_path / "repo", xacro_args={"x": "1"})
    assert other.scanned == 4
    assert len(list((cache / "includes-v2").glob("repo-*.json"))) == 2


def test_recently_changed_files_are_not_stored(tmp_path, cache):
    """A file changed within the timestamp tick could change again unseen: scanned again."""
    urdf = _repository(tmp_path / "repo")
    write(urdf / "middle.xacro", middle("leaf.xacro") + "\n")  # now
    include_graph.include_graph(tmp_path / "repo")
    again = include_graph.include_graph(tmp_path / "repo")
    assert again.scanned == 2  # middle.xacro and the robot that read it


def test_no_cache_file_without_a_cache(tmp_path, cache, monkeypatch):
    monkeypatch.setenv("INERTIA_KIT_NO_CACHE", "1")
    _repository(tmp_path / "repo")
    include_graph.include_graph(tmp_path / "repo")
    assert include_graph.include_graph(tmp_path / "repo").scanned == 4
    assert not cache.exists()


def test_an_entry_is_current_while_its_files_are(tmp_path):
    file = write(tmp_path / "a.xacro", "x")
    entry = include_cache.Entry("plain", ((str(file), include_cache.stamp(str(file))),))
    assert entry.current()
    assert include_cache.Entry.from_json(entry.to_json()) == entry
    write(file, "xy")
    assert not entry.current()
    file.unlink()
    assert not entry.current()


# --- which folder is the repository -----------------------------------------------------------


def test_the_repository_is_the_git_top_level(tmp_path):
    (tmp_path / ".git").mkdir()
    write(tmp_path / "pkg" / "package.xml", "<package/>")
    write(tmp_path / "pkg" / ".inertia-kit.toml", "")
    file = write(tmp_path / "pkg" / "urdf" / "a.xacro", LEAF)
    assert repository_root(file) == (tmp_path, "the git top level")


def test_else_the_folder_of_the_configuration(tmp_path):
    write(tmp_path / "pkg" / "package.xml", "<package/>")
    write(tmp_path / "pyproject.toml", "[tool.inertia-kit]\n")
    file = write(tmp_path / "pkg" / "urdf" / "a.xacro", LEAF)
    assert repository_root(file) == (tmp_path, "the folder of pyproject.toml")


def test_else_the_package_root_else_the_folder(tmp_path):
    write(tmp_path / "pkg" / "package.xml", "<package/>")
    file = write(tmp_path / "pkg" / "urdf" / "a.xacro", LEAF)
    assert repository_root(file) == (tmp_path / "pkg", "the package root")
    lone = write(tmp_path / "lone" / "b.xacro", LEAF)
    root, why = repository_root(lone)
    assert root == tmp_path / "lone"
    assert why.startswith("the file's folder")
