"""
Configuration files for fuzz inputs: ``pyproject.toml`` with ``[tool.inertia-kit]``,
``.inertia-kit.toml`` and ``.gitignore``, right (every key the configuration knows, every rule
option) or wrong (unknown keys, wrong types, broken TOML, huge values).
"""

from __future__ import annotations

import json
import random

from fuzz.tree import Tree
from inertia_kit.lint import catalog


def _rule_table(rng: random.Random) -> str:
    rule = rng.choice(catalog.RULES)
    lines = [f"[tool.inertia-kit.rules.{rng.choice([rule.CODE, rule.NAME])}]"]
    for option in catalog.options(rule):
        if rng.random() < 0.6:
            lines.append(f"{option.name} = {_value(rng, option.type, option.default)}")
    if rng.random() < 0.5:
        lines.append(f'severity = "{rng.choice(["error", "warning", "info", "fatal"])}"')
    if rng.random() < 0.05:
        lines.append("no_such_option = 1")
    return "\n".join(lines)


def _value(rng: random.Random, kind, default) -> str:
    if rng.random() < 0.1:
        return rng.choice(['"text"', "nan", "inf", "-1", "1e308", "[]", "true", "0"])
    if kind is bool:
        return rng.choice(["true", "false"])
    if kind is int:
        return str(rng.choice([0, 1, 3, 10**6]))
    if kind is float:
        return repr(rng.choice([0.0, 1e-9, 0.5, 2.0, 10.0, 1e9]))
    if kind is str:
        return '"x"'
    return repr(list(default)) if isinstance(default, tuple) else "[]"


def tool_table(rng: random.Random, header: str = "[tool.inertia-kit]") -> str:
    codes = [r.CODE for r in catalog.RULES]
    lines = [header]
    if rng.random() < 0.4:
        chosen = rng.sample(["IN0", "IN01", "IN02", "IN020", "IN07", *codes[:5]], 2)
        lines.append("select = " + json.dumps(chosen))
    if rng.random() < 0.3:
        lines.append(f'ignore = ["{rng.choice(codes)}"]')
    if rng.random() < 0.2:
        lines.append(f'fail-on = "{rng.choice(["error", "warning", "info", "never"])}"')
    if rng.random() < 0.15:
        engine = rng.choice(["all", "mujoco", "drake", "gazebo", "pybullet", "kdl", "bullet"])
        lines.append(f'engines = ["{engine}"]')
    if rng.random() < 0.15:
        pattern = rng.choice(["*.urdf", "urdf/*", "**/*.xacro"])
        lines.append(f'per-file-ignores = {{ "{pattern}" = ["{rng.choice(codes)}"] }}')
    if rng.random() < 0.08:
        lines.append(f"fix = {rng.choice(['true', 'false'])}")
    if rng.random() < 0.08:
        lines.append(f"unsafe-fixes = {rng.choice(['true', 'false'])}")
    if rng.random() < 0.1:
        lines.append(f'exclude = ["{rng.choice(["urdf/", "*.xacro", "meshes/", "**"])}"]')
    if rng.random() < 0.1:
        lines.append(f"respect-gitignore = {rng.choice(['true', 'false'])}")
    if rng.random() < 0.05:
        lines.append("unknown-key = 1")
    if rng.random() < 0.3:
        lines.append(_rule_table(rng).replace("[tool.inertia-kit.", "[" + header[1:-1] + ".", 1))
    if rng.random() < 0.15:
        lines.append(header[:-1] + ".xacro]")
        value = rng.choice(["0", "5", "1", "-1", "1e9", '"x"'])
        lines.append(f"{rng.choice(['timeout', 'memory', 'elements'])} = {value}")
    if rng.random() < 0.15:
        lines.append(header[:-1] + f".links.{rng.choice(['base_link', 'link_1', 'l1', 'nope'])}]")
        value = rng.choice(["1000", "0", "-1", "1e308", "nan", '"heavy"'])
        lines.append(f"{rng.choice(['density', 'mass'])} = {value}")
    return "\n".join(lines) + "\n"


def add_configs(rng: random.Random, tree: Tree) -> None:
    """Some of pyproject.toml, .inertia-kit.toml and .gitignore in ``tree``."""
    roll = rng.random()
    if roll < 0.35:
        body = tool_table(rng)
        if rng.random() < 0.05:
            body = body[: rng.randrange(len(body) + 1)] + rng.choice(["[[[", '"', "= =", "\x00"])
        tree.put("pyproject.toml", '[project]\nname = "robot"\n\n' + body)
    elif roll < 0.5:
        tree.put(
            ".inertia-kit.toml",
            tool_table(rng, "[tool.inertia-kit]")
            .replace("[tool.inertia-kit]\n", "", 1)
            .replace("[tool.inertia-kit.", "["),
        )
    if rng.random() < 0.3:
        patterns = rng.sample(
            [
                "*.stl",
                "build/",
                "urdf/robot.urdf",
                "!urdf/robot.urdf",
                "meshes/",
                "*.xacro",
                "#c",
                "",
                "\\#x",
                "**/",
                "/robot.urdf",
            ],
            3,
        )
        tree.put(".gitignore", "\n".join(patterns) + "\n")
    if rng.random() < 0.3:
        tree.put(".git/HEAD", "ref: refs/heads/main\n")
