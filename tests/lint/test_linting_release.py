"""
A run that streams its report releases each file's settled findings once told (issue 23,
item 5): the results keep only what a later file can still change, the run counts the rest,
and together they are exactly the findings of a run that keeps everything.
"""

from __future__ import annotations

import shutil

import pytest
from kit import EXAMPLES, write
from kit.assets import asset_library

from inertia_kit.lint.merge import Tally, merge
from inertia_kit.lint.paths import lint_paths, linting

#: a link with an impossible tensor in a file robots include: its findings are located there
PARTS = """<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="shared"><inertial><mass value="1"/>
    <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="3"/></inertial></link>
</robot>
"""
ROBOT = """<robot name="{name}" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="parts.xacro"/>
  <link name="base"/>
  <joint name="j" type="fixed"><parent link="base"/><child link="shared"/></joint>
</robot>
"""


@pytest.fixture
def library(tmp_path):
    """Robots, a shared xacro file given with the robots that include it (its findings wait
    for every robot), and an unreadable file."""
    shutil.copytree(EXAMPLES, tmp_path / "examples")
    asset_library(tmp_path / "assets", 30, broken=True)
    write(tmp_path / "parts" / "parts.xacro", PARTS)
    for name in ("a", "b"):
        write(tmp_path / "parts" / f"{name}.urdf.xacro", ROBOT.format(name=name))
    return tmp_path


@pytest.mark.parametrize("jobs", [1, 2])
def test_released_findings_and_what_stays_are_the_whole_run(library, jobs):
    whole = merge(lint_paths([library], jobs=jobs))
    told = []
    with linting([library], jobs=jobs, release=True) as run:
        for step in run:
            for linted in step.ready:
                told.extend(linted.settled)
    kept = [finding for result in run.results for finding in result.findings]
    assert told and kept  # the shared file's findings wait for the end
    assert not {id(f) for f in told} & {id(f) for f in kept}
    streamed = merge(run.results, run.told)
    assert sorted(told + streamed.findings) == sorted(whole.findings)
    assert run.told == Tally.of(told)
    assert streamed.tally == whole.tally
    assert (streamed.failing, streamed.checked, streamed.flagged, streamed.linted) == (
        whole.failing,
        whole.checked,
        whole.flagged,
        whole.linted,
    )
    assert streamed.messages == whole.messages
    assert list(map(str, streamed.errors)) == list(map(str, whole.errors))
    assert sum(result.told for result in run.results) == len(told)
    # what only telling a file needed is gone too
    assert all(not result.reads and not result.environment_values for result in run.results)
