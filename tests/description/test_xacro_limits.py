"""The xacro limits: their values and sources, the element meter, and the guarded expressions."""

from __future__ import annotations

import math
import time

import pytest
import xacro

from inertia_kit.description.xacro_limits import (
    ENV,
    MAX_INT_BITS,
    LimitExceeded,
    Meter,
    XacroLimits,
    check_limit,
    guarded_code,
    parse_limits,
)
from inertia_kit.errors import ConfigError

# --- values and where they come from ----------------------------------------------------------


def test_defaults():
    assert XacroLimits() == XacroLimits(timeout=30.0, memory=1024, elements=50_000)


def test_precedence_defaults_configuration_environment_command_line():
    configured = {"timeout": 60.0, "memory": 2048}
    assert XacroLimits.resolve(env={}) == XacroLimits()
    assert XacroLimits.resolve(configured, env={}) == XacroLimits(60.0, 2048, 50_000)
    env = {ENV: "memory=4096, elements=0"}
    assert XacroLimits.resolve(configured, env=env) == XacroLimits(60.0, 4096, 0)
    given = {"elements": 7, "timeout": 0.5}
    assert XacroLimits.resolve(configured, given, env=env) == XacroLimits(0.5, 4096, 7)


def test_the_environment_is_read_by_default(monkeypatch):
    monkeypatch.setenv(ENV, "timeout=5")
    assert XacroLimits.resolve().timeout == 5.0
    monkeypatch.setenv(ENV, "  ")
    assert XacroLimits.resolve() == XacroLimits()


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("timeout", "expected NAME=VALUE (timeout=SECONDS, memory=MB, elements=COUNT; 0: no"),
        ("time=3", "unknown limit `time`; known: timeout, memory, elements"),
        ("memory=lots", "`memory` takes a number of MB, got 'lots'"),
        ("timeout=-1", "`timeout` takes a number of s ≥ 0 (0: none), got -1.0"),
        ("elements=1.5", "`elements` takes a whole number of elements, got 1.5"),
        ("timeout=nan", "`timeout` takes a number of s ≥ 0 (0: none), got nan"),
    ],
)
def test_bad_limits_are_refused_saying_what_is_expected(text, message):
    with pytest.raises(ValueError) as caught:
        parse_limits(text)
    assert message in str(caught.value)
    with pytest.raises(ConfigError) as caught:
        XacroLimits.resolve(env={ENV: text})
    assert str(caught.value).startswith(f"{ENV}={text!r}: ")


def test_limits_made_in_python_are_checked():
    assert XacroLimits(timeout=2, memory=512.0) == XacroLimits(2.0, 512, 50_000)
    with pytest.raises(ValueError, match="`elements` takes a number of elements ≥ 0"):
        XacroLimits(elements=-1)


def test_limit_values():
    assert parse_limits("timeout=2.5,memory=512 ,, elements=1e3") == {
        "timeout": 2.5,
        "memory": 512,
        "elements": 1000,
    }
    assert check_limit("memory", 0) == 0
    with pytest.raises(ValueError, match="takes a number"):
        check_limit("timeout", True)


def test_describe():
    limits = XacroLimits(2.5, 100, 10)
    assert limits.describe("timeout") == "the xacro time limit (2.5 s)"
    assert limits.describe("memory") == "the xacro memory limit (100 MB)"
    assert limits.describe("elements") == "the xacro element limit (10 elements)"


# --- the meter ------------------------------------------------------------------------------


def test_the_meter_counts_elements_up_to_the_limit():
    meter = Meter(XacroLimits(elements=3))
    meter.add(3)
    with pytest.raises(LimitExceeded) as caught:
        meter.add()
    assert str(caught.value).startswith("the expansion made more than 3 elements, the xacro ")
    assert "--xacro-limit elements=COUNT" in caught.value.hint
    assert caught.value.told() == f"{caught.value}; {caught.value.hint}"
    Meter(XacroLimits(elements=0)).add(10**9)  # 0: no limit


def test_the_meter_checks_the_deadline():
    meter = Meter(XacroLimits(timeout=1), start=time.monotonic() - 2)
    with pytest.raises(LimitExceeded, match=r"ran longer than the xacro time limit \(1 s\)"):
        meter.add()
    assert Meter(XacroLimits(timeout=0)).deadline == math.inf


# --- guarded expressions --------------------------------------------------------------------


def evaluate(expr: str, limits: XacroLimits | None = None):
    builtins = Meter(limits or XacroLimits()).builtins()
    return eval(guarded_code(expr), {"__builtins__": builtins, "n": 3})


@pytest.mark.parametrize(
    "expr",
    [
        "2**10",
        "-2**2",
        "2**3**2",
        "(-3)**3",
        "2**-1",
        "2.0**0.5",
        "0**0",
        "(-1)**(10**12)",
        "1**(10**100)",
        "3*4*5",
        "2*n**2",
        "'ab'*3",
        "3*'ab'",
        "[1, 2]*2",
        "(0,)*n",
        "True*'x'",
        "1<<10",
        "-1<<3",
        "[x*2 for x in (1, 2, 3)]",
        "(lambda y: y**2)(4)",
        "1.5*2 + 3/4 - 7//2 % 3",
        "10**300 * 10**300",
    ],
)
def test_guarded_expressions_give_what_python_gives(expr):
    assert evaluate(expr) == eval(expr, {"n": 3})


@pytest.mark.parametrize(
    ("expr", "message"),
    [
        ("10**10**10", "10 ** 10000000000 would be an integer of 10000000001 digits"),
        ("2**(10**400)", "2 ** an integer of 401 digits would be an integer of more digits than"),
        ("3**(10**20)", "3 ** 100000000000000000000 would be an integer of about 4.77e+19 digits"),
        ("7**1000000", "7 ** 1000000 would be an integer of 845099 digits"),
        ("1<<(10**7)", "1 << 10000000 would be an integer of 3010300 digits"),
        ("1<<(10**400)", "1 << an integer of 401 digits would be an integer of more digits"),
        ("(2**600000)*(2**600000)", "an integer of 180618 digits * an integer of 180618 digits"),
    ],
)
def test_integers_past_the_bound_are_refused_before_they_are_computed(expr, message):
    began = time.monotonic()
    with pytest.raises(LimitExceeded) as caught:
        evaluate(expr)
    assert time.monotonic() - began < 1
    assert message in str(caught.value)
    assert f"more than the {MAX_INT_BITS} bits (301030 digits)" in str(caught.value)


@pytest.mark.parametrize(
    ("expr", "message"),
    [
        ("'x'*10**10", "'x' * 10000000000 would be a string of 10000000000 characters (9537 MB"),
        ("10**10*'ab'", "10000000000 * 'ab' would be a string of 20000000000 characters"),
        ("[0]*10**9", "[0] * 1000000000 would be a sequence of 1000000000 items (7629 MB"),
    ],
)
def test_repetition_past_the_memory_limit_is_refused(expr, message):
    with pytest.raises(LimitExceeded) as caught:
        evaluate(expr)
    assert message in str(caught.value)
    assert "over the xacro memory limit (1024 MB)" in str(caught.value)
    assert "--xacro-limit memory=MB" in caught.value.hint
    # without a memory limit the repetition is not refused here (only sized by the caller)
    assert evaluate("'x'*10**6", XacroLimits(memory=0)) == "x" * 10**6


def test_names_and_syntax_are_refused_as_xacro_refuses_them():
    with pytest.raises(xacro.XacroException) as ours:
        guarded_code("x.__class__ * 2")
    with pytest.raises(xacro.XacroException) as theirs:
        xacro.safe_eval("x.__class__ * 2", {})
    assert str(ours.value) == str(theirs.value)
    with pytest.raises(SyntaxError) as ours:
        guarded_code("1 +* 2")
    with pytest.raises(SyntaxError) as theirs:
        xacro.safe_eval("1 +* 2", {})
    assert (ours.value.msg, ours.value.offset) == (theirs.value.msg, theirs.value.offset)
