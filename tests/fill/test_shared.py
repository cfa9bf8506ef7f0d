"""fill.shared: robots that include one fragment agree on what is written there, or nothing is."""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from inertia_kit.cli.fill import fill_command

# a part whose values depend on a property each robot sets: two shapes (no single-shape formula),
# so a fill writes numbers in the fragment, which one robot's numbers would make wrong for the
# other
PARTS = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="part">
    <link name="arm">
      <inertial>
        <mass value="1"/>
        <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
      </inertial>
      <collision><geometry><box size="${size} 0.1 0.1"/></geometry></collision>
      <collision><origin xyz="0 0 0.2"/><geometry><sphere radius="0.05"/></geometry></collision>
    </link>
  </xacro:macro>
</robot>
"""


def robot(name: str, size: float) -> str:
    return f"""<?xml version="1.0"?>
<robot name="{name}" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="size" value="{size}"/>
  <xacro:include filename="parts.xacro"/>
  <link name="world"/>
  <joint name="j" type="revolute"><parent link="world"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <xacro:part/>
</robot>
"""


def fill(*args: str):
    return CliRunner().invoke(fill_command, list(args))


def project(folder: Path, sizes: tuple[float, float]) -> list[str]:
    (folder / "parts.xacro").write_text(PARTS)
    for name, size in zip("ab", sizes, strict=True):
        (folder / f"{name}.urdf.xacro").write_text(robot(name, size))
    return [str(folder / "a.urdf.xacro"), str(folder / "b.urdf.xacro")]


def test_robots_that_disagree_on_a_shared_element_leave_it_and_say_why(tmp_path):
    paths = project(tmp_path, (0.1, 0.3))
    for _ in range(2):  # the same refusal every run: a fixed point, not a flip-flop
        result = fill("--fix", "all", *paths)
        assert result.exit_code == 1
        assert (tmp_path / "parts.xacro").read_text() == PARTS
        refusals = [line for line in result.stderr.splitlines() if "not filled" in line]
        assert len(refusals) == 2
        for line in refusals:
            assert "compute other values for it" in line
            assert "a.urdf.xacro: 1 kg" in line and "b.urdf.xacro: 1 kg" in line


def test_robots_that_agree_on_a_shared_element_fill_it_once(tmp_path):
    paths = project(tmp_path, (0.1, 0.1))
    first = fill("--fix", "all", *paths)
    assert first.exit_code == 1, first.stderr
    filled = (tmp_path / "parts.xacro").read_text()
    assert filled != PARTS and "not filled" not in first.stderr
    second = fill("--fix", "all", *paths)
    assert second.exit_code == 0, second.stderr
    assert (tmp_path / "parts.xacro").read_text() == filled
