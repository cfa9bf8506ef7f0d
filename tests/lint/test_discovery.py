"""lint.discovery: the files a folder gives, with the same case rule as the pre-commit hooks."""

from __future__ import annotations

import re
from pathlib import Path

from kit import remove_tree

from inertia_kit.lint.discovery import ROBOT_FILE, Discovery, expand_paths

REPO = Path(__file__).resolve().parents[2]


def test_the_walk_and_the_hooks_share_one_case_rule():
    hooks = (REPO / ".pre-commit-hooks.yaml").read_text()
    patterns = re.findall(r"^\s*files:\s*(\S+)\s*$", hooks, flags=re.MULTILINE)
    assert patterns and set(patterns) == {ROBOT_FILE}


def test_a_folder_gives_robot_files_whatever_their_case(tmp_path):
    names = ["GEN.URDF", "arm.urdf", "arm.urdf.xacro", "Macros.XACRO", "notes.txt", "x.urdfx"]
    for name in names:
        (tmp_path / name).write_text("<robot/>")
    (tmp_path / ".hidden").mkdir()
    (tmp_path / ".hidden" / "h.urdf").write_text("<robot/>")
    found = [path.name for path in expand_paths([tmp_path])]
    assert found == sorted(["GEN.URDF", "arm.urdf", "arm.urdf.xacro", "Macros.XACRO"])


def _files(root: Path, *names: str) -> None:
    for name in names:
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text("<robot/>")


def _found(root: Path, discovery: Discovery | None = None) -> list[str]:
    return [path.relative_to(root).as_posix() for path in expand_paths([root], discovery)]


def test_a_package_folder_named_build_is_linted_unless_it_is_colcon_output(tmp_path):
    # robot packages may keep generated descriptions in build/: only a workspace's is output
    _files(tmp_path, "pkg/build/robot.urdf", "pkg/install/robot.urdf", "pkg/log/robot.urdf")
    assert _found(tmp_path) == [
        "pkg/build/robot.urdf",
        "pkg/install/robot.urdf",
        "pkg/log/robot.urdf",
    ]
    (tmp_path / "pkg" / "src").mkdir()  # now pkg looks like a workspace root
    assert _found(tmp_path) == []
    _files(tmp_path, "__pycache__/x.urdf", ".venv/y.urdf", "pkg/src/z.urdf")
    assert _found(tmp_path) == ["pkg/src/z.urdf"]


def test_a_deeper_gitignore_re_includes_what_a_higher_one_ignores(tmp_path):
    (tmp_path / ".git").mkdir()
    _files(tmp_path, "a/keep.urdf", "a/drop.urdf", "a/b/keep.urdf", "top.urdf")
    (tmp_path / ".gitignore").write_text("*.urdf\n!top.urdf\n")
    (tmp_path / "a" / ".gitignore").write_text("!keep.urdf\n")
    assert _found(tmp_path) == ["a/b/keep.urdf", "a/keep.urdf", "top.urdf"]
    # no repository above: .gitignore files are not read
    (tmp_path / ".git").rmdir()
    assert len(_found(tmp_path)) == 4


def test_patterns_outside_their_base_match_names_only(tmp_path, monkeypatch):
    _files(tmp_path, "ws/gen/a.urdf", "ws/b.urdf")
    monkeypatch.chdir(tmp_path / "ws")
    # the current folder is the base: `/gen` is anchored there, `b.urdf` matches any depth
    assert _found(tmp_path / "ws", Discovery(extend_exclude=["/gen", "b.urdf"])) == []
    monkeypatch.chdir(tmp_path / "ws" / "gen")
    # outside the base, an anchored pattern matches nothing, a name still does
    assert _found(tmp_path / "ws", Discovery(extend_exclude=["/gen", "b.urdf"])) == ["gen/a.urdf"]


def test_a_stand_in_for_stdin_is_never_walked(tmp_path):
    _files(tmp_path, ".inertia-kit-stdin-0a1b2c3d-robot.urdf", "robot.urdf")
    assert _found(tmp_path) == ["robot.urdf"]


def test_a_file_in_a_folder_that_may_not_be_searched_is_given_as_it_is(tmp_path):
    """
    Path.is_dir raises on it (EACCES) where os.path.isdir says no: the file is given on, and
    reading it says why it cannot be read (it was an internal error: fuzz input 61).
    """
    from kit.permissions import obeying_permissions

    folder = tmp_path / "urdf"
    folder.mkdir()
    (folder / "robot.urdf").write_text("<robot/>")
    (tmp_path / "pyproject.toml").write_text("[tool.inertia-kit]\nignore = ['IN025']\n")
    folder.chmod(0o444)  # its names can be listed, not looked at
    try:
        given = obeying_permissions(lambda: list(expand_paths([folder / "robot.urdf"])))
    finally:
        folder.chmod(0o755)
    assert given == [folder / "robot.urdf"]


def test_a_folder_a_thousand_deep_is_walked_with_its_ignore_files(tmp_path):
    """
    Python 3.11's os.walk recursed (a RecursionError at a depth of 1000: an internal error),
    and each file's ignore files were looked up through all its folders (a 600-deep folder took
    40 s); a .gitignore half way down still applies below it.
    """
    (tmp_path / ".git").mkdir()
    deep = tmp_path
    for depth in range(1100):
        deep = deep / "a"
        deep.mkdir()
        if depth == 550:
            (deep / ".gitignore").write_text("skipped.urdf\n")
    for name in ("kept.urdf", "skipped.urdf"):
        (deep / name).write_text("<robot/>")
    try:
        assert [path.name for path in expand_paths([tmp_path])] == ["kept.urdf"]
    finally:
        remove_tree(tmp_path / "a")  # pytest's clean-up recurses


MJCF = '<?xml version="1.0"?>\n<!-- a licence -->\n<mujoco model="m"><worldbody/></mujoco>\n'


def test_a_folder_gives_the_xml_files_that_are_mjcf_models_only(tmp_path):
    (tmp_path / "arm.xml").write_text(MJCF)
    (tmp_path / "SCENE.XML").write_text(MJCF)
    (tmp_path / "package.xml").write_text("<package format='3'><name>p</name></package>")
    (tmp_path / "robot.xml").write_text("<robot name='r'/>")  # URDF saved as .xml: not picked
    (tmp_path / "launch.xml").write_text("<launch/>")
    (tmp_path / "empty.xml").write_bytes(b"")
    assert [path.name for path in expand_paths([tmp_path])] == ["SCENE.XML", "arm.xml"]


def test_a_hook_hands_over_every_xml_file_and_only_the_mjcf_models_are_linted(tmp_path):
    (tmp_path / "arm.xml").write_text(MJCF)
    (tmp_path / "package.xml").write_text("<package/>")
    given = [tmp_path / "arm.xml", tmp_path / "package.xml"]
    hooked = Discovery(force_exclude=True)
    assert [path.name for path in expand_paths(given, hooked)] == ["arm.xml"]
    # asked for by name without --force-exclude, a file is read (and refused if no robot)
    assert [path.name for path in expand_paths(given)] == ["arm.xml", "package.xml"]
