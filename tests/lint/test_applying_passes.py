"""
`--fix` runs its passes in memory and writes once: a run killed between two passes leaves every
file as it was, each pass lints the text the one before produced (xacro includes too, expanded
in a forked child), the result is the one writing each pass gave, and another writer's save at
any moment of the passes is kept, nothing written (exit 2).
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from kit import EXAMPLES, write
from kit.concurrency import CHANGED
from kit.in_process import lint_in_process, run_split

from inertia_kit.description.edits import write_all_atomic
from inertia_kit.lint.applying import MAX_PASSES, fix_file, one_pass
from inertia_kit.lint.runner import lint_file

# its centre of mass lies outside its box (IN021, an unsafe fix moves it to the centroid); only
# then is the tensor judged about the right point, impossible (IN023, recomputed): two passes
ARM = """\
    <link name="arm">
      <inertial><origin xyz="0 0 0.2" rpy="0 0 0"/><mass value="3059.84"/><inertia ixx="133.142" ixy="0" ixz="0" iyy="133.142" iyz="0" izz="10.7485"/></inertial>
      <visual><geometry><box size="0.1477 0.483 0.0429"/></geometry></visual>
    </link>
"""  # noqa: E501
# the same line after both passes
FIXED = '<inertial><origin xyz="0 0 0" rpy="0 0 0"/><mass value="3059.84"/><inertia ixx="59.9549" ixy="0" ixz="0" iyy="6.03189" iyz="0" izz="65.0482"/></inertial>'  # noqa: E501

_BASE = """\
  <link name="base"/>
  <joint name="j" type="revolute">
    <parent link="base"/>
    <child link="arm"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
"""
_XACRO = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def urdf_project(root: Path) -> tuple[Path, Path]:
    """A URDF robot whose fix takes two passes: (the robot, the file the fix edits)."""
    robot = write(
        root / "arm.urdf", f'<?xml version="1.0"?>\n<robot name="r">\n{_BASE}{ARM}</robot>\n'
    )
    return robot, robot


def xacro_project(root: Path) -> tuple[Path, Path]:
    """A xacro robot whose arm comes from a macro of an included file, which both passes edit:
    the second must lint the first one's edit of it."""
    parts = write(
        root / "urdf/parts.xacro",
        f'<?xml version="1.0"?>\n<robot {_XACRO}>\n  <xacro:macro name="arm">\n'
        f"{textwrap.indent(ARM, '  ')}  </xacro:macro>\n</robot>\n",
    )
    robot = write(
        root / "urdf/robot.urdf.xacro",
        f'<?xml version="1.0"?>\n<robot name="r" {_XACRO}>\n'
        f'  <xacro:include filename="parts.xacro"/>\n{_BASE}  <xacro:arm/>\n</robot>\n',
    )
    return robot, parts


PROJECTS = {"urdf": urdf_project, "xacro": xacro_project}


def snapshot(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in folder.rglob("*") if p.is_file()}


def fixed(robot: Path):
    """The file fixed as `--fix --unsafe-fixes` does: passes in memory, one write."""
    return fix_file(lambda: lint_file(robot, fixes="all"), True, write=True)


def fixed_pass_by_pass(robot: Path) -> int:
    """The file fixed as `--fix` did before it wrote once: each pass written, the next linted
    from the disk (the reference the one write must equal). Returns the passes that changed."""
    for number in range(MAX_PASSES):
        result = lint_file(robot, fixes="all")
        step = one_pass(result.findings, True, result.reads)
        if not step.changes:
            return number
        write_all_atomic([(s.path, s.encode(text), s.original) for s, text in step.changes])
    return MAX_PASSES


@pytest.mark.parametrize("project", PROJECTS)
def test_both_passes_are_written_at_once(tmp_path: Path, project: str):
    robot, edited = PROJECTS[project](tmp_path)
    outcome = fixed(robot)
    assert (outcome.result.error, outcome.passes, outcome.fixed) == (None, 2, 3)
    assert FIXED in edited.read_text()


@pytest.mark.parametrize("project", PROJECTS)
def test_a_run_killed_between_two_passes_leaves_every_file_as_it_was(tmp_path: Path, project):
    """SIGKILL once the second pass has linted (the first pass's edits made): nothing of them
    is on the disk. (Writing each pass, the first pass's half of the fix was.)"""
    robot, _ = PROJECTS[project](tmp_path)
    before = snapshot(tmp_path)
    script = textwrap.dedent(
        f"""
        import os, signal, sys
        from inertia_kit.lint import applying
        from inertia_kit.lint.paths import lint_paths

        done = []
        original = applying.one_pass

        def one_pass(*args, **kwargs):
            if done:  # the second pass: the first one's edits are made
                os.kill(os.getpid(), signal.SIGKILL)
            step = original(*args, **kwargs)
            done.append(len(step.changes))
            print("first pass changed", len(step.changes), file=sys.stderr, flush=True)
            return step

        applying.one_pass = one_pass
        lint_paths([{str(robot)!r}], fix=True, unsafe_fixes=True)
        """
    )
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert run.returncode == -9, run.stderr
    assert "first pass changed 1" in run.stderr
    assert snapshot(tmp_path) == before


def _robots() -> list[str]:
    found = []
    for package in sorted(EXAMPLES.iterdir()):
        found += [str(p.relative_to(EXAMPLES)) for p in sorted((package / "urdf").glob("*"))]
    return [*found, *PROJECTS]


@pytest.mark.parametrize("name", _robots())
def test_the_one_write_equals_writing_each_pass(tmp_path: Path, name: str):
    """On every example robot (and fragment) and the two-pass projects, the files written at
    once are those that writing each pass gave, byte for byte."""
    copies = []
    for side in ("once", "each"):
        root = tmp_path / side
        if name in PROJECTS:
            robot = PROJECTS[name](root)[0]
        else:
            shutil.copytree(EXAMPLES / Path(name).parts[0], root / Path(name).parts[0])
            robot = root / name
        copies.append((root, robot))
    (once, robot_once), (each, robot_each) = copies
    before = snapshot(once)
    outcome = fixed(robot_once)
    passes = fixed_pass_by_pass(robot_each)
    assert snapshot(once) == snapshot(each)
    assert outcome.passes == passes
    assert (snapshot(once) != before) == (passes > 0)


def _save_theirs(path: Path) -> None:
    path.write_bytes(path.read_bytes() + b"<!-- theirs -->\n")


@pytest.mark.parametrize(
    ("project", "saved"),
    [("urdf", "edited"), ("xacro", "edited"), ("xacro", "robot")],
)
def test_a_save_between_two_passes_is_kept_and_nothing_written(
    tmp_path: Path, monkeypatch, project: str, saved: str
):
    """Another writer saves a file after the first pass: the run writes nothing, exits 2 with
    the message the other writers give, and the file holds their save. (Writing each pass, the
    first pass's edits were under it.) Their file is the one the fix edits, or (xacro) the
    robot, which the passes read but do not edit."""
    from inertia_kit.cli.lint import lint_command
    from inertia_kit.lint import paths

    lint_in_process(monkeypatch)
    robot, edited = PROJECTS[project](tmp_path)
    theirs = edited if saved == "edited" else robot
    linted = []

    def lint_then_save(*args, **kwargs):
        if len(linted) == 1:  # between the first pass and the second
            _save_theirs(theirs)
        linted.append(1)
        return lint_file(*args, **kwargs)

    monkeypatch.setattr(paths, "lint_file", lint_then_save)
    before = snapshot(tmp_path)
    code, _, err = run_split(lint_command, ["--fix", "--unsafe-fixes", str(robot)])
    assert len(linted) >= 2
    assert code == 2 and CHANGED in err, err
    expected = dict(before)
    key = str(theirs.relative_to(tmp_path))
    expected[key] = before[key] + b"<!-- theirs -->\n"
    assert snapshot(tmp_path) == expected
