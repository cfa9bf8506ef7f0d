"""
Every rule document in rules/ runs: its `fail` example triggers that rule and nothing else,
its `fixed` example triggers nothing. The index lists every rule, and every rule has a document.
IN000 (a file that could not be linted, not a rule) has one too: its `fail` example is reported
as IN000 alone, through the command.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from pathlib import Path

import pytest
from kit import REPO

from inertia_kit.lint import catalog
from inertia_kit.lint.output.common import UNLINTED
from inertia_kit.lint.runner import Selection, lint_file

RULES_DIR = REPO / "rules"
DOCS = sorted(RULES_DIR.glob("IN[0-9][0-9][0-9]-*.md"))
HEADINGS = [
    "## What it does",
    "## Why is this bad?",
    "## Example",
    "## Use instead",
    "## Fix safety",
    "## Options",
    "## References",
]
BLOCK = re.compile(r"```xml (fail|fixed)(?: name=(\S+))?\n(.*?)```", re.DOTALL)
# mesh files the examples use: ```stl name=part.stl blocks (ASCII STL), written beside every
# example of the document before it is linted
MESH = re.compile(r"```stl name=(\S+)\n(.*?)```", re.DOTALL)


def examples(doc: Path) -> dict[str, list[tuple[str, str]]]:
    found: dict[str, list[tuple[str, str]]] = {"fail": [], "fixed": []}
    for kind, name, text in BLOCK.findall(doc.read_text()):
        found[kind].append((name or "robot.urdf", text))
    return found


def meshes(doc: Path) -> list[tuple[str, str]]:
    return MESH.findall(doc.read_text())


def engines_of(doc: Path) -> tuple[str, ...]:
    """An engine rule's document is linted with its engine chosen (`--engine`); others with none."""
    code = doc.stem.split("-", 1)[0]
    rule = catalog.find(code)
    engine = None if rule is None else catalog.engine(rule)
    return () if engine is None else (engine,)


def lint_example(
    tmp_path: Path,
    name: str,
    text: str,
    files: Iterable[tuple[str, str]] = (),
    engines: tuple[str, ...] = (),
):
    for mesh_name, mesh_text in files:
        mesh_path = tmp_path / mesh_name
        mesh_path.parent.mkdir(parents=True, exist_ok=True)
        mesh_path.write_text(mesh_text)
    path = tmp_path / name
    path.write_text(text)
    result = lint_file(path, Selection(engines=engines))
    assert result.error is None, result.error
    return result.findings


@pytest.mark.parametrize("doc", DOCS, ids=[d.stem for d in DOCS])
def test_document_shape(doc):
    text = doc.read_text()
    code, name = doc.stem.split("-", 1)
    assert text.startswith(f"# {code} {name}\n")
    positions = [text.find(h) for h in HEADINGS]
    assert all(p >= 0 for p in positions), [
        h for h, p in zip(HEADINGS, positions, strict=True) if p < 0
    ]
    assert positions == sorted(positions)
    found = examples(doc)
    assert found["fail"] and found["fixed"]


@pytest.mark.parametrize("doc", DOCS, ids=[d.stem for d in DOCS])
def test_fail_example_triggers_only_its_rule(doc, tmp_path):
    code = doc.stem.split("-", 1)[0]
    if code == UNLINTED:
        return unlinted_example(doc, tmp_path)
    for name, text in examples(doc)["fail"]:
        findings = lint_example(tmp_path, name, text, meshes(doc), engines_of(doc))
        codes = {f.code for f in findings}
        assert codes == {code}, [str((f.code, f.message)) for f in findings]


def unlinted_example(doc: Path, tmp_path: Path) -> None:
    """The IN000 document's failing example, through `inertia-lint --output-format json`."""
    import json

    from click.testing import CliRunner

    from inertia_kit.cli import lint_main

    for name, text in examples(doc)["fail"]:
        path = tmp_path / name
        path.write_text(text)
        result = CliRunner().invoke(lint_main, ["--output-format", "json", str(path)])
        assert result.exit_code == 2, result.output
        entries = json.loads(result.stdout)
        assert [(e["code"], e["name"], e["file"]) for e in entries] == [
            (UNLINTED, "unreadable-file", str(path))
        ]
        assert entries[0]["line"] is not None


@pytest.mark.parametrize("doc", DOCS, ids=[d.stem for d in DOCS])
def test_fixed_example_triggers_nothing(doc, tmp_path):
    for name, text in examples(doc)["fixed"]:
        findings = lint_example(tmp_path, name, text, meshes(doc), engines_of(doc))
        assert findings == [], [str((f.code, f.message)) for f in findings]


def test_every_rule_has_a_document_and_an_index_entry():
    index = (RULES_DIR / "README.md").read_text()
    for rule in catalog.RULES:
        doc = RULES_DIR / f"{rule.CODE}-{rule.NAME}.md"
        assert doc.is_file(), f"{rule.CODE} has no document {doc.name}"
        assert f"[{rule.CODE}]({doc.name})" in index, f"{rule.CODE} missing from rules/README.md"


def test_the_index_says_what_the_listing_says():
    """rules/README.md's table: each rule's name, severity and fix as `inertia-kit rules`
    lists them (its fix column once said "no" for 15 rules whose fix is unsafe)."""
    from inertia_kit.cli.rules import rule_row

    index = (RULES_DIR / "README.md").read_text()
    for rule in catalog.RULES:
        row = rule_row(rule)
        cells = f"| {row['name']} | {row['severity']} | {row['fix']} |"
        assert f"[{rule.CODE}]({rule.CODE}-{rule.NAME}.md) {cells}" in index, rule.CODE
