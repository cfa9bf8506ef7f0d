"""lint.discovery: the files a folder gives, with the same case rule as the pre-commit hooks."""

from __future__ import annotations

import re
from pathlib import Path

from inertia_kit.lint.discovery import ROBOT_FILE, expand_paths

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
