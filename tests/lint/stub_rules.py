"""
The stub catalogue of the configuration and runner tests: IN098 stub-heavy (fires on a link
heavier than its `limit` option; options of every type) and IN099 stub-other, the robot they
lint, and a file writer. The ``stub_rules`` fixture (conftest.py) makes them the catalogue.
"""

from __future__ import annotations

import types
from pathlib import Path

from kit.urdf import moving

from inertia_kit.lint.findings import Severity
from inertia_kit.lint.options import Option

# a massless base and a 3 kg moving link `arm` with a tiny tensor
ROBOT = moving(
    '<inertial><mass value="3"/>'
    '<inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>',
    name="arm",
)


def stub_rule(code: str, name: str, *options: Option) -> types.ModuleType:
    """A stub rule: fires on every link whose mass exceeds its `limit` option."""
    rule = types.ModuleType(f"inertia_kit.lint.rules.{code.lower()}_{name.replace('-', '_')}")
    rule.CODE, rule.NAME, rule.SEVERITY, rule.SCOPE = code, name, Severity.WARNING, "link"
    rule.SUMMARY, rule.OPTIONS = name, options

    def check(link, ctx):
        mass = None if link.link.inertial is None else link.link.inertial.mass
        if isinstance(mass, float) and mass > ctx.option("limit"):
            yield ctx.finding(f"{link.name}: {mass} > {ctx.option('limit')}", link.link.source)

    rule.check = check
    return rule


HEAVY = stub_rule(
    "IN098",
    "stub-heavy",
    Option("limit", float, 1.0, "the most a link may weigh, kg"),
    Option("count", int, 3, "an integer"),
    Option("strict", bool, False, "a flag"),
    Option("links", list[str], [], "link names"),
    Option("mode", str, "a", "a word"),
)
OTHER = stub_rule(
    "IN099", "stub-other", Option("limit", float, 100.0, "the most a link may weigh, kg")
)


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path
