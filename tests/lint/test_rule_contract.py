"""
Every rule module keeps the rule contract (the docstring of `inertia_kit.lint.rules`): the
attributes every rule has, well formed; the optional ones, well formed when present; and no
other upper-case constant its own code does not read (a misspelt or retired contract attribute).
The checker itself is tested on rules that break the contract.
"""

from __future__ import annotations

import ast
import importlib.util
import inspect
import re
import textwrap
import typing
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

from inertia_kit.engines.vocabulary import ENGINES
from inertia_kit.lint import catalog, rules
from inertia_kit.lint.documents import rule_documents
from inertia_kit.lint.findings import FixRule, Repairs, Safety, Severity
from inertia_kit.lint.options import Option

REQUIRED = ("CODE", "NAME", "SEVERITY", "SCOPE", "SUMMARY", "check")
OPTIONAL = (
    "OPTIONS",
    "ENGINE",
    "DESCRIPTION_FORMATS",
    "SUPERSEDES",
    "FIX",
    "TEXT_FIX",
    "SPOILS_GEOMETRY",
    "WEIGHED",
)
CONTRACT = (*REQUIRED, *OPTIONAL)
CONSTANT = re.compile(r"[A-Z][A-Z0-9_]*")


def _fits(value: Any, kind: Any) -> bool:
    """Whether a default is a value of an option type (``float``, ``list[str]``, ``(int, str)``)."""
    if isinstance(kind, tuple):
        return any(_fits(value, k) for k in kind)
    origin = typing.get_origin(kind)
    if origin in (list, tuple):
        items = [a for a in typing.get_args(kind) if a is not Ellipsis]
        return isinstance(value, origin) and all(_fits(v, items[0]) for v in value if items)
    if kind is Any:
        return True
    if kind is int:
        return isinstance(value, int) and not isinstance(value, bool)
    return isinstance(value, kind)


def _options(rule: ModuleType) -> list[str]:
    options = rule.OPTIONS
    if not isinstance(options, tuple) or not all(isinstance(o, Option) for o in options):
        return ["OPTIONS: a tuple of Option"]
    problems = []
    names = [option.name for option in options]
    if len(set(names)) != len(names):
        problems.append(f"OPTIONS: names twice: {names}")
    for option in options:
        if not re.fullmatch(r"[a-z][a-z0-9_]*", option.name):
            problems.append(f"OPTIONS: `{option.name}` is not snake_case")
        if not _fits(option.default, option.type):
            problems.append(f"OPTIONS: `{option.name}` defaults to {option.default!r}")
        if not isinstance(option.help, str) or not option.help or "\n" in option.help:
            problems.append(f"OPTIONS: `{option.name}` has no one-line help")
    return problems


def _unread_constants(rule: ModuleType) -> list[str]:
    """Upper-case names the module assigns but never reads (and the contract does not know)."""
    tree = ast.parse(inspect.getsource(rule))
    assigned = [
        target.id
        for node in tree.body
        if isinstance(node, (ast.Assign, ast.AnnAssign))
        for target in (node.targets if isinstance(node, ast.Assign) else [node.target])
        if isinstance(target, ast.Name)
    ]
    read = {
        node.id
        for node in ast.walk(tree)
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load)
    }
    return [
        f"{name}: no contract attribute, and the rule does not read it"
        for name in assigned
        if CONSTANT.fullmatch(name) and name not in CONTRACT and name not in read
    ]


def violations(rule: ModuleType) -> list[str]:
    """What in ``rule`` breaks the contract; empty when nothing does."""
    missing = [name for name in REQUIRED if not hasattr(rule, name)]
    if missing:
        return [f"{name}: missing" for name in missing]
    problems = []
    code, name = rule.CODE, rule.NAME
    if not isinstance(code, str) or not re.fullmatch(r"IN\d{3}", code):
        problems.append(f"CODE: {code!r} is no code like IN020")
    if not isinstance(name, str) or not re.fullmatch(r"[a-z0-9]+(-[a-z0-9]+)*", name):
        problems.append(f"NAME: {name!r} is not kebab-case")
    elif isinstance(code, str):
        module = f"{code.lower()}_{name.replace('-', '_')}"
        if rule.__name__ != f"inertia_kit.lint.rules.{module}":
            problems.append(f"module: {rule.__name__} is not named {module}")
        if not (rule.__doc__ or "").startswith(f"{code} {name}: "):
            problems.append(f"docstring: does not start with `{code} {name}: `")
    if not isinstance(rule.SEVERITY, Severity):
        problems.append(f"SEVERITY: {rule.SEVERITY!r} is no Severity")
    if rule.SCOPE not in ("link", "robot", "suppressions"):
        problems.append(f'SCOPE: {rule.SCOPE!r} is not "link", "robot" or "suppressions"')
    if not isinstance(rule.SUMMARY, str) or not rule.SUMMARY or "\n" in rule.SUMMARY:
        problems.append("SUMMARY: not one line of text")
    if not callable(rule.check) or len(inspect.signature(rule.check).parameters) != 2:
        problems.append("check: not a function of (target, ctx)")
    if hasattr(rule, "OPTIONS"):
        problems += _options(rule)
    if hasattr(rule, "ENGINE") and rule.ENGINE not in ENGINES:
        problems.append(f"ENGINE: {rule.ENGINE!r} is none of {', '.join(ENGINES)}")
    if hasattr(rule, "DESCRIPTION_FORMATS"):
        formats = rule.DESCRIPTION_FORMATS
        known = set(catalog.ALL_FORMATS)
        if not isinstance(formats, tuple) or not formats or not set(formats) < known:
            problems.append(f"DESCRIPTION_FORMATS: {formats!r} is no tuple of some formats")
    if hasattr(rule, "SUPERSEDES"):
        known = set(catalog.names()) - {code}
        superseded = rule.SUPERSEDES
        if not isinstance(superseded, tuple) or not superseded or not set(superseded) <= known:
            problems.append(f"SUPERSEDES: {superseded!r} is no tuple of other rules' codes")
    if hasattr(rule, "FIX"):
        problems += _fix(rule.FIX)
    if hasattr(rule, "TEXT_FIX") and not isinstance(rule.TEXT_FIX, Safety):
        problems.append("TEXT_FIX: not a Safety")
    if hasattr(rule, "TEXT_FIX") and hasattr(rule, "FIX"):
        problems.append("TEXT_FIX and FIX: a rule's findings offer one kind of fix")
    if hasattr(rule, "SPOILS_GEOMETRY") and rule.SPOILS_GEOMETRY is not True:
        problems.append("SPOILS_GEOMETRY: not True")
    if hasattr(rule, "WEIGHED") and rule.WEIGHED is not True:
        problems.append("WEIGHED: not True")
    return problems + _unread_constants(rule)


def _fix(fix: Any) -> list[str]:
    if not isinstance(fix, FixRule):
        return ["FIX: no FixRule"]
    problems = []
    if fix.how not in ("geometry", "slip", "com", "com-slip"):
        problems.append(f"FIX: how {fix.how!r} is none of geometry, slip, com, com-slip")
    if fix.safety not in (Safety.SAFE, Safety.UNSAFE) or not isinstance(fix.repairs, Repairs):
        problems.append("FIX: safety must be safe or unsafe, repairs a Repairs")
    if (fix.how == "slip") != (fix.safety is Safety.SAFE):
        # only undoing a recognised slip is provably right; values from geometry are a judgment
        problems.append("FIX: a slip's fix is safe, every other one unsafe")
    if not isinstance(fix.title, str) or not fix.title or "\n" in fix.title:
        problems.append("FIX: no one-line title")
    return problems


@pytest.mark.parametrize("rule", catalog.RULES, ids=[rule.CODE for rule in catalog.RULES])
def test_every_rule_keeps_the_contract(rule):
    assert violations(rule) == []


@pytest.mark.parametrize("rule", catalog.RULES, ids=[rule.CODE for rule in catalog.RULES])
def test_the_document_lists_every_option(rule):
    text = rule_documents()[rule.CODE].read_text(encoding="utf-8")
    section = text.split("## Options\n", 1)[1].split("\n## ", 1)[0].strip()
    declared = catalog.options(rule)
    for option in declared:
        assert f"`{option.name}`" in section, f"{rule.CODE}: `{option.name}` not documented"
    if not declared:
        assert section.startswith("None"), f"{rule.CODE} has no options: its document says None"


@pytest.mark.parametrize("rule", catalog.RULES, ids=[rule.CODE for rule in catalog.RULES])
def test_the_document_says_the_fix_and_its_safety(rule):
    """A `Fix:` line under "## What it does": safe, unsafe, or none, as the rule's FIX."""
    text = rule_documents()[rule.CODE].read_text(encoding="utf-8")
    lines = [line for line in text.splitlines() if line.startswith("Fix: ")]
    assert len(lines) == 1, f"{rule.CODE}: no single `Fix:` line"
    word = {"safe/unsafe": "safe for an exact fit, unsafe"}.get(
        catalog.fix_safety_text(rule), catalog.fix_safety_text(rule)
    )
    assert lines[0].startswith(f"Fix: {word}"), f"{rule.CODE}: {lines[0]!r}, its FIX is {word}"


def test_the_contract_is_documented_where_rules_are_written():
    for name in CONTRACT:
        assert f"``{name}" in rules.__doc__, f"{name} is not in the rule contract's docstring"


# --- the checker on rules that break the contract ----------------------------------------------

GOOD = '''
    """IN098 stub-rule: a rule that keeps the contract."""
    from inertia_kit.lint.findings import FixRule, Repairs, Safety, Severity
    from inertia_kit.lint.options import Option

    CODE = "IN098"
    NAME = "stub-rule"
    SEVERITY = Severity.WARNING
    SCOPE = "link"
    SUMMARY = "a stub"
    LIMIT = 2.0  # the rule's own constant: read below
    OPTIONS = (Option("factor", float, LIMIT, "a factor"),)
    ENGINE = "mujoco"
    SUPERSEDES = ("IN020",)
    FIX = FixRule("geometry", Safety.UNSAFE, Repairs.IMPOSSIBLE, "recompute")


    def check(link, ctx):
        yield from ()
'''


def _module(tmp_path: Path, source: str, name: str = "in098_stub_rule") -> ModuleType:
    path = tmp_path / f"{name}.py"
    path.write_text(textwrap.dedent(source))
    spec = importlib.util.spec_from_file_location(f"inertia_kit.lint.rules.{name}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_checker_passes_a_good_rule(tmp_path):
    assert violations(_module(tmp_path, GOOD)) == []


@pytest.mark.parametrize(
    ("old", "new", "problem"),
    [
        ('SUPERSEDES = ("IN020",)', 'SUPERSEDE = ("IN020",)', "SUPERSEDE: no contract attribute"),
        ("Safety.UNSAFE", "Safety.SAFE", "FIX: a slip's fix is safe, every other one unsafe"),
        ('FIX = FixRule("geometry"', 'FIX = ("geometry"', "FIX: no FixRule"),
        ('ENGINE = "mujoco"', 'ENGINE = "bullet"', "ENGINE: 'bullet' is none of"),
        (
            'OPTIONS = (Option("factor", float, LIMIT, "a factor"),)',
            'OPTIONS = {"factor": float}\n    DEFAULTS = {"factor": 2.0}',
            "OPTIONS: a tuple of Option",
        ),
        ("LIMIT, ", "2, ", "OPTIONS: `factor` defaults to 2"),
        ('"a factor"', '""', "OPTIONS: `factor` has no one-line help"),
        ('Option("factor"', 'Option("Factor"', "OPTIONS: `Factor` is not snake_case"),
        ('("IN020",)', '("IN098",)', "SUPERSEDES: ('IN098',) is no tuple"),
        (
            'SCOPE = "link"',
            'SCOPE = "file"',
            'SCOPE: \'file\' is not "link", "robot" or "suppressions"',
        ),
        ("Severity.WARNING", '"warning"', "SEVERITY: 'warning' is no Severity"),
        ('CODE = "IN098"', 'CODE = "IN98"', "CODE: 'IN98' is no code like IN020"),
        ('NAME = "stub-rule"', 'NAME = "stub_rule"', "NAME: 'stub_rule' is not kebab-case"),
        ('"""IN098 stub-rule:', '"""IN098:', "docstring: does not start with `IN098 stub-rule: `"),
        ('SUMMARY = "a stub"', 'SUMMARY = ""', "SUMMARY: not one line of text"),
        ("def check(link, ctx):", "def check(link):", "check: not a function of (target, ctx)"),
        ('SUMMARY = "a stub"', "", "SUMMARY: missing"),
    ],
)
def test_the_checker_finds_what_breaks_the_contract(tmp_path, old, new, problem):
    assert old in GOOD
    found = violations(_module(tmp_path, GOOD.replace(old, new)))
    assert any(p.startswith(problem) for p in found), found


def test_the_checker_wants_the_module_named_after_the_rule(tmp_path):
    found = violations(_module(tmp_path, GOOD, name="in098_other_name"))
    assert found == ["module: inertia_kit.lint.rules.in098_other_name is not named in098_stub_rule"]
