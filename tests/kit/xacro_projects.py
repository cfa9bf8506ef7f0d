"""
Repositories of xacro robots that share fragments, for the fragment tests: a leaf fragment
holding a macro (whose link's mass is a parameter, so a test can break it), included by robots
directly, through another fragment, or through ``$(find pkg)``.

Every project is a package ``arm_description`` (``package.xml``) in a folder with ``.git``
(the repository the robots are looked for in). :func:`age` sets every file's mtime in the past,
so that the include graph's cache stores them (it skips files changed in the last 2 s).
"""

from __future__ import annotations

import os
import shutil
import time
from pathlib import Path

from kit import EXAMPLES, write

PACKAGE = "arm_description"
HEAD = '<?xml version="1.0"?>\n'
XACRO = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'

# the macro's <mass> stands on line 6 of leaf.xacro
LEAF = f"""{HEAD}<robot {XACRO}>
  <xacro:macro name="arm_link" params="name mass">
    <link name="${{name}}">
      <inertial>
        <mass value="${{mass}}"/>
        <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/>
      </inertial>
    </link>
  </xacro:macro>
</robot>
"""
LEAF_MASS_LINE = 6


def robot(include: str, *calls: str, name: str = "arm") -> str:
    """A robot that includes ``include`` and calls ``arm_link`` for each ``name=mass``."""
    body = "".join(
        f'  <xacro:arm_link name="{link}" mass="{mass}"/>\n'
        for link, mass in (call.split("=") for call in calls)
    )
    joints = "".join(
        f'  <joint name="j_{link}" type="revolute"><parent link="base"/><child link="{link}"/>'
        '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>\n'
        for link in (call.split("=")[0] for call in calls)
    )
    return (
        f'{HEAD}<robot name="{name}" {XACRO}>\n  <xacro:include filename="{include}"/>\n'
        f'  <link name="base"/>\n{body}{joints}</robot>\n'
    )


def middle(include: str) -> str:
    """A fragment that only includes another."""
    return f'{HEAD}<robot {XACRO}>\n  <xacro:include filename="{include}"/>\n</robot>\n'


def project(root: Path, files: dict[str, str]) -> Path:
    """``files`` (relative to the package folder) in package ``arm_description`` of a
    repository at ``root``; the package folder."""
    (root / ".git").mkdir(parents=True, exist_ok=True)
    package = root / PACKAGE
    write(package / "package.xml", f"<package><name>{PACKAGE}</name></package>\n")
    for name, text in files.items():
        write(package / name, text)
    return package


def age(root: Path, seconds: float = 60.0) -> None:
    """Every file below ``root`` last changed ``seconds`` ago, each a different mtime."""
    past = time.time() - seconds
    for index, path in enumerate(sorted(p for p in root.rglob("*") if p.is_file())):
        os.utime(path, (past + index * 0.01, past + index * 0.01))


def seed_wheeled_robot(root: Path) -> Path:
    """The seed wheeled robot (examples/my_robot_description) in a repository at ``root``."""
    (root / ".git").mkdir(parents=True, exist_ok=True)
    target = root / "my_robot_description"
    shutil.copytree(EXAMPLES / "my_robot_description", target)
    return target / "urdf"


def wheel_macro_span(text: str) -> tuple[int, int]:
    """Where the ``wheel`` macro (the one the robot calls) of wheels.xacro starts and ends."""
    start = text.index('<xacro:macro name="wheel"')
    return start, text.index("</xacro:macro>", start)
