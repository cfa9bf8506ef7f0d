"""The rule catalogue: the registry, lookups, the optional contract attributes, selectors."""

from __future__ import annotations

import re

import pytest
from kit import REPO

from inertia_kit.lint import catalog
from inertia_kit.lint.rules import (
    in002_non_positive_mass,
    in012_inertia_too_small,
    in063_inertia_unit_slip,
    in070_mujoco_verdict,
)


def test_registry_codes_and_names_are_unique_and_complete():
    rules = catalog.RULES
    modules = sorted(p.stem for p in (REPO / "inertia_kit/lint/rules").glob("in[0-9]*.py"))
    assert [r.__name__.rsplit(".", 1)[1] for r in rules] == modules, "every rule is registered"
    codes = [r.CODE for r in rules]
    names = [r.NAME for r in rules]
    assert len(set(codes)) == len(codes) and len(set(names)) == len(names)
    assert codes == sorted(codes)
    for rule in rules:
        assert re.fullmatch(r"IN\d{3}", rule.CODE)
        assert re.fullmatch(r"[a-z0-9]+(-[a-z0-9]+)*", rule.NAME)
        assert rule.SCOPE in ("link", "robot", "suppressions")
        module = rule.__name__.rsplit(".", 1)[1]
        assert module.startswith(rule.CODE.lower() + "_")


def test_names_and_find():
    assert list(catalog.names()) == [rule.CODE for rule in catalog.RULES]
    assert catalog.names()["IN012"] == "inertia-too-small"
    assert catalog.find("IN012") is in012_inertia_too_small
    assert catalog.find("in012") is in012_inertia_too_small
    assert catalog.find("inertia-too-small") is in012_inertia_too_small
    for missing in ("IN01", "IN999", "inertia-too-smal", "INERTIA-TOO-SMALL", ""):
        assert catalog.find(missing) is None


def test_optional_contract_attributes_and_their_defaults():
    assert catalog.engine(in070_mujoco_verdict) == "mujoco"
    assert catalog.engine(in002_non_positive_mass) is None
    assert catalog.supersedes(in063_inertia_unit_slip) == ("IN020", "IN023", "IN012", "IN022")
    assert catalog.supersedes(in002_non_positive_mass) == ()
    assert catalog.options(in002_non_positive_mass) == ()
    assert [o.name for o in catalog.options(in012_inertia_too_small)] == [
        "min_moment",
        "min_radius",
    ]
    assert catalog.option_values(in012_inertia_too_small, {}) == {
        "min_moment": 1e-9,
        "min_radius": 0.001,
    }
    assert catalog.option_values(in012_inertia_too_small, {"min_radius": 0.01}) == {
        "min_moment": 1e-9,
        "min_radius": 0.01,
    }


@pytest.mark.parametrize(
    ("text", "selector"),
    [
        ("IN012", "IN012"),
        (" in01 ", "IN01"),
        ("IN", "IN"),
        ("inertia-too-small", "inertia-too-small"),
        ("IN9", None),
        ("IN0123", None),
        ("Inertia-too-small", None),
    ],
)
def test_normalize_selector(text, selector):
    assert catalog.normalize_selector(text) == selector


def test_selects_codes_prefixes_and_names():
    assert catalog.selects(["IN01"], "IN012", "inertia-too-small")
    assert catalog.selects(["in012"], "IN012", "inertia-too-small")
    assert catalog.selects(["inertia-too-small"], "IN012", "inertia-too-small")
    assert not catalog.selects(["IN02", "missing-inertial"], "IN012", "inertia-too-small")
    assert not catalog.selects([], "IN012", "inertia-too-small")


def test_suggestions_and_selector_error():
    known = catalog.names()
    assert catalog.suggestions("IN12", known) == ["IN012"]
    assert catalog.suggestions("IN99", known) == []
    assert catalog.suggestions("inertia-to-small", known) == ["inertia-too-small"]
    assert catalog.selector_error("IN12", known) == (
        "`IN12` is not a rule code, code prefix or rule name (did you mean `IN012`?)"
    )
    assert catalog.selector_error("IN777", known) == (
        "`IN777` is not a rule code, code prefix or rule name"
    )
