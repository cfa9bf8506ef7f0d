"""
The rule documents, ``rules/<CODE>-<name>.md``: where they are, and the one ``--explain``
prints. Imports no rule (the catalogue only to word an error), so ``--explain`` stays fast.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path


def documents_folder() -> Path:
    """
    Where the rule documents are: ``inertia_kit/rule_docs`` (package data in a wheel; in the
    source tree a link to ``rules/``), else ``rules/`` beside the package.
    """
    package = Path(__file__).parent.parent
    shipped = package / "rule_docs"
    return shipped if shipped.is_dir() else package.parent / "rules"


def rule_documents() -> dict[str, Path]:
    """``code -> document`` for every ``<CODE>-<name>.md``."""
    return {
        path.name.split("-", 1)[0]: path
        for path in sorted(documents_folder().glob("IN[0-9][0-9][0-9]-*.md"))
    }


def explain(selector: str) -> str:
    """
    The document of one rule, by code or name. Raises ``LookupError`` with a message for a
    selector that names no single rule or a rule without a document.
    """
    documents = rule_documents()
    documented = {code: path.stem.split("-", 1)[1] for code, path in documents.items()}
    text = selector.strip()
    code = _code(text, documented)
    if code is not None:
        return documents[code].read_text(encoding="utf-8")
    # no document names it: whether it is a rule at all, the catalogue (the rules) says
    from inertia_kit.lint import catalog

    known = {**catalog.names(), **documented}
    code = _code(text, known)
    if code is None:
        close = catalog.suggestions(text, known)
        hint = f" (did you mean {', '.join(f'`{c}`' for c in close)}?)" if close else ""
        raise LookupError(f"`{text}` is not a rule code or name{hint}")
    raise LookupError(f"{code} ({known[code]}) has no document in this version")


def _code(text: str, known: Mapping[str, str]) -> str | None:
    """The code ``text`` names in ``known`` (``code -> name``): a code in any case, or a name."""
    if text.upper() in known:
        return text.upper()
    return next((code for code, name in known.items() if name == text), None)
