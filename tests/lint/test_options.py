"""Rule options: a value read from TOML as an option's type, and the type in words."""

from __future__ import annotations

from typing import Any

import pytest

from inertia_kit.lint.options import convert, type_name


@pytest.mark.parametrize(
    ("value", "kind", "converted"),
    [
        (2, float, 2.0),  # TOML's integers are numbers
        (2.5, float, 2.5),
        (3, int, 3),
        (True, bool, True),
        ("a", str, "a"),
        (["a", "b"], list[str], ["a", "b"]),
        (["a", 1], list, ["a", 1]),
        (["a", 1], tuple, ("a", 1)),
        ([1, 2], tuple[float, ...], (1.0, 2.0)),
        ({"x": 1}, Any, {"x": 1}),
        ("a", (int, str), "a"),
        (4, (int, str), 4),
    ],
)
def test_convert_takes(value, kind, converted):
    ok, result = convert(value, kind)
    assert ok and result == converted and type(result) is type(converted)


@pytest.mark.parametrize(
    ("value", "kind"),
    [
        (True, float),  # a boolean is no number here
        ("1", float),
        (1.5, int),
        (False, int),
        (1, bool),
        (["a", 1], list[str]),
        ("ab", list[str]),
        ((1, 2), tuple),  # TOML has arrays, never Python tuples
        (float("inf"), tuple),  # `= inf` where a list belongs (fuzz s1, input 17767)
        (1.5, list),
        (1.5, (int, str)),
    ],
)
def test_convert_refuses(value, kind):
    ok, _ = convert(value, kind)
    assert not ok


@pytest.mark.parametrize(
    ("kind", "words"),
    [
        (float, "a number"),
        (int, "an integer"),
        (bool, "true or false"),
        (str, "a string"),
        (list[str], "a list of strings"),
        (tuple[float, ...], "a list of numbers"),
        ((int, str), "an integer or a string"),
        (tuple, "a list"),  # TOML has arrays: what a user writes
    ],
)
def test_type_name(kind, words):
    assert type_name(kind) == words
