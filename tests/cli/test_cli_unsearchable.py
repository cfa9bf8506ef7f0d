"""
A robot in a folder that may not be searched (mode 0o444: its names can be listed, nothing in it
looked at): every command says it cannot read it (exit 2), none has an internal error. pathlib's
``exists``/``is_file``/``is_dir`` raise PermissionError there, where os.path's answer no; the
fuzz run found eight places (issue 19). As root, the commands run in a child that obeys file
modes (kit.permissions).
"""

from __future__ import annotations

import pytest
from click.testing import CliRunner
from kit.permissions import obeying_permissions
from kit.urdf import NEGATIVE_MASS_ARM

from inertia_kit.cli import main

COMMANDS = [
    ["lint", "."],
    ["lint", "urdf/robot.urdf"],
    ["lint", "--fix", "--unsafe-fixes", "urdf/robot.urdf"],
    ["lint", "--add-noqa", "."],
    ["fill", "urdf/robot.urdf"],
    ["fill", "-o", "filled.urdf", "urdf/robot.urdf"],
    ["report", "urdf/robot.urdf"],
    ["view", "-o", "review.html", "urdf/robot.urdf"],
    ["mass", "mesh", "urdf/robot.urdf"],
]


@pytest.mark.parametrize("mode", [0o444, 0o000])
@pytest.mark.parametrize("args", COMMANDS, ids=" ".join)
def test_a_robot_in_a_folder_that_may_not_be_searched_is_an_input_error(
    tmp_path, monkeypatch, args, mode
):
    (tmp_path / ".git").mkdir()
    folder = tmp_path / "urdf"
    folder.mkdir()
    (folder / "robot.urdf").write_text(NEGATIVE_MASS_ARM)
    monkeypatch.chdir(tmp_path)
    folder.chmod(mode)

    def run() -> tuple[int, str]:
        result = CliRunner().invoke(main, args)
        return result.exit_code, result.output

    try:
        code, output = obeying_permissions(run)
    finally:
        folder.chmod(0o755)
    assert "internal error" not in output and "Traceback" not in output, output
    assert code in (0, 2), output  # a folder walk that cannot look in it finds nothing there
    if "." not in args and "mesh" not in args:
        assert (code, "Permission denied" in output) == (2, True), output
    assert code == 2 or "." in args, output
