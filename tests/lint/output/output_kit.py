"""
The world the output-format tests lint, through the command line: a URDF and a xacro robot
whose macro lives in an included fragment (FILES), and three stub rules (an error, a warning,
an info) so that the output depends on nothing the rule authors may still change. The
``robots`` fixture (conftest.py) writes the files and makes the stubs the catalogue.
"""

from __future__ import annotations

import json
import types

from click.testing import CliRunner

from inertia_kit.cli import main
from inertia_kit.lint.findings import Severity


def _moving_link(joint: str, parent: str, child: str, mass: str, moment: str) -> str:
    """A revolute joint and its child link, whose tensor is ``moment`` about every axis."""
    return f"""  <joint name="{joint}" type="revolute">
    <parent link="{parent}"/><child link="{child}"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
  <link name="{child}">
    <inertial>
      <mass value="{mass}"/>
      <inertia ixx="{moment}" ixy="0" ixz="0" iyy="{moment}" iyz="0" izz="{moment}"/>
    </inertial>
  </link>
"""


# the <mass> of `upper` is on line 10, that of `fore` on line 20
ARM = (
    '<?xml version="1.0"?>\n<robot name="arm">\n  <link name="base"/>\n'
    + _moving_link("shoulder", "base", "upper", "0", "0.001")
    + _moving_link("elbow", "upper", "fore", "25", "0.1")
    + "</robot>\n"
)
CART = """<?xml version="1.0"?>
<robot name="cart" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="wheel.xacro"/>
  <link name="body">
    <inertial>
      <mass value="0.005"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/>
    </inertial>
  </link>
  <xacro:wheel name="left" mass="-1"/>
  <xacro:wheel name="right" mass="1"/>
</robot>
"""
WHEEL = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="wheel" params="name mass">
    <joint name="${name}_joint" type="continuous">
      <parent link="body"/><child link="${name}_wheel"/>
      <axis xyz="0 1 0"/>
    </joint>
    <link name="${name}_wheel">
      <inertial>
        <mass value="${mass}"/>
        <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/>
      </inertial>
    </link>
  </xacro:macro>
</robot>
"""
FILES = {"robots/arm.urdf": ARM, "robots/cart.urdf.xacro": CART, "robots/wheel.xacro": WHEEL}


def stub_rule(code, name, severity, test, message, *, help=None, detail=None, expected=False):
    """A link rule on the declared mass: ``test(mass)`` fires it at the ``<mass>`` element."""
    rule = types.ModuleType(f"inertia_kit.lint.rules.{code.lower()}_{name.replace('-', '_')}")
    rule.CODE, rule.NAME, rule.SEVERITY, rule.SCOPE = code, name, severity, "link"
    rule.SUMMARY = f"stub: {name}"

    def check(link, ctx):
        inertial = link.link.inertial
        mass = None if inertial is None else inertial.mass
        if isinstance(mass, float) and test(mass):
            yield ctx.finding(
                message.format(link=link.name, mass=mass),
                inertial.mass_source,
                link=link.name,
                expected={"mass": 10.0} if expected else None,
                help=help,
                detail=detail,
            )

    rule.check = check
    return rule


ZERO = stub_rule(
    "IN097",
    "stub-non-positive",
    Severity.ERROR,
    lambda m: m <= 0,
    "link `{link}`: mass = {mass:g} kg is not positive",
    help="give the link's real mass",
)
HEAVY = stub_rule(
    "IN098",
    "stub-heavy",
    Severity.WARNING,
    lambda m: m > 10,
    "link `{link}`: {mass:g} kg, more than 10 kg",
    detail="a stub's limit: 10 kg",
    expected=True,
)
LIGHT = stub_rule("IN099", "stub-light", Severity.INFO, lambda m: 0 < m < 0.01, "{mass:g} kg")
STUBS = (ZERO, HEAVY, LIGHT)


def lint(*args: str) -> tuple[int, str, str]:
    try:
        runner = CliRunner(mix_stderr=False)  # click < 8.2
    except TypeError:
        runner = CliRunner()
    result = runner.invoke(main, ["lint", *args], catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


NOTE = (
    "note: robots/wheel.xacro: linted through the robots that include it: robots/cart.urdf.xacro\n"
)
SUMMARY = "Found 2 errors, 1 warning, 1 info in 2 files.\n"
NO_FINDINGS = "No findings in 1 file.\n"


def no_findings(output_format: str) -> tuple[int, str, str]:
    """Lint a file on which the selected stub finds nothing, in ``output_format``."""
    return lint("--output-format", output_format, "--select", "IN098", "robots/cart.urdf.xacro")


def dumps(value) -> str:
    return json.dumps(value, indent=2, ensure_ascii=False) + "\n"
