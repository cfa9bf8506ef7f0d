"""The rule documents: where they are, and what `--explain` prints for a code or a name."""

from __future__ import annotations

import pytest
from kit import REPO

from inertia_kit.lint import documents
from inertia_kit.lint.documents import explain, rule_documents

IN002_DOC = REPO / "rules" / "IN002-non-positive-mass.md"


def test_every_document_by_code():
    found = rule_documents()
    assert found["IN002"].name == IN002_DOC.name
    assert all(path.name.startswith(f"{code}-") for code, path in found.items())


@pytest.mark.parametrize("selector", ["IN002", "in002", " non-positive-mass "])
def test_explain_by_code_or_name(selector):
    assert explain(selector) == IN002_DOC.read_text(encoding="utf-8")


@pytest.mark.parametrize(
    ("selector", "message"),
    [
        ("IN0", "`IN0` is not a rule code or name"),
        ("IN02", "`IN02` is not a rule code or name (did you mean `IN002`?)"),
        ("non-positive-mas", "`non-positive-mas` is not a rule code or name (did you mean "),
    ],
)
def test_explain_names_no_rule(selector, message):
    with pytest.raises(LookupError) as caught:
        explain(selector)
    assert str(caught.value).startswith(message)


def test_explain_a_rule_without_a_document(monkeypatch, tmp_path):
    monkeypatch.setattr(documents, "documents_folder", lambda: tmp_path)
    with pytest.raises(LookupError, match=r"^IN002 \(non-positive-mass\) has no document"):
        explain("non-positive-mass")
