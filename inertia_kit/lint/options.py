"""
Rule options: how a rule declares one (:class:`Option`), and how a value read from TOML becomes
a value of the option's type (:func:`convert`), with the type's name for error messages
(:func:`type_name`).

An option's type is one of ``float`` (an integer is taken too), ``int``, ``bool``, ``str``,
``list``/``tuple`` (a TOML array of anything), ``list[T]``/``tuple[T, ...]`` (an array of
``T``), ``Any``, or a tuple of these (the first that takes the value wins).
"""

from __future__ import annotations

import typing
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class Option:
    """
    One option of a rule: ``[tool.inertia-kit.rules.<CODE>] <name> = value``. A rule declares
    its options as ``OPTIONS = (Option(...), ...)`` and reads them with ``ctx.option(name)``.
    """

    name: str  # snake_case, as written in the configuration
    type: Any  # what a configured value must be (see the module docstring)
    default: Any  # the value when the configuration sets none
    help: str  # one line; the rule's document says more under "## Options"
    #: a number option's smallest value (no rule's number means anything below zero; a factor
    #: below 1 inverts its test, and 0 would divide by zero)
    minimum: float = 0.0
    #: and whether it must be above it (a bound compared on a log scale: 0 has no logarithm)
    above: bool = False


_TYPE_NAMES = {
    float: "a number",
    int: "an integer",
    bool: "true or false",
    str: "a string",
    list: "a list",
    tuple: "a list",  # TOML's arrays
}


def type_name(kind: Any) -> str:
    """``kind`` in words, as an error message says what it expected: ``a list of strings``."""
    origin = typing.get_origin(kind)
    if origin in (list, tuple):
        (item, *_) = typing.get_args(kind) or (Any,)
        return f"a list of {type_name(item).removeprefix('a ').removeprefix('an ')}s"
    if isinstance(kind, tuple):
        return " or ".join(type_name(k) for k in kind)
    return _TYPE_NAMES.get(kind, getattr(kind, "__name__", str(kind)))


def out_of_range(value: Any, option: Option) -> str | None:
    """Why ``value``, already of the option's type, cannot be its value; ``None`` if it can."""
    if option.type not in (float, int) or isinstance(value, bool):
        return None
    if value != value:  # TOML's nan
        return "expected a number, got nan"
    if value < option.minimum or (option.above and value == option.minimum):
        bound = f"above {option.minimum:g}" if option.above else f"from {option.minimum:g} up"
        return f"expected a number {bound}, got {value!r}"
    return None


def convert(value: Any, kind: Any) -> tuple[bool, Any]:
    """``(ok, value)``: a value read from TOML as ``kind`` (an option type)."""
    if isinstance(kind, tuple):
        for choice in kind:
            ok, converted = convert(value, choice)
            if ok:
                return True, converted
        return False, None
    origin = typing.get_origin(kind)
    if origin in (list, tuple):
        if not isinstance(value, list):
            return False, None
        args = typing.get_args(kind)
        item = args[0] if args else Any
        items = [convert(v, item) for v in value]
        if not all(ok for ok, _ in items):
            return False, None
        converted = [v for _, v in items]
        return True, tuple(converted) if origin is tuple else converted
    if kind is Any:
        return True, value
    if kind is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            return False, None
        return True, float(value)
    if kind is int:
        return (not isinstance(value, bool) and isinstance(value, int)), value
    if kind in (list, tuple):
        if not isinstance(value, list):  # `= inf` where a list belongs (fuzz s1, input 17767)
            return False, None
        return True, (tuple(value) if kind is tuple else value)
    return isinstance(value, kind), value
