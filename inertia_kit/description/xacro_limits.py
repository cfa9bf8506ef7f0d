"""
Limits on a xacro expansion, so that one mistaken or hostile file cannot take down the machine
that lints it: ``${'x'*10**10}`` asks for 10 GB, ``${10**10**10}`` is a C-level power no signal
interrupts, a macro that calls the next one twice, 22 levels deep, makes 2²² links.

Three limits, each ``0`` for none (:class:`XacroLimits`):

- ``timeout``: seconds of wall-clock time for the whole expansion;
- ``memory``: MB the expansion may allocate on top of what the process already holds;
- ``elements``: elements xacro may read (every file, every include) or copy (every macro call,
  every ``insert_block``); this bounds the work of macros that multiply their output.

How they are enforced is :mod:`.xacro_sandbox` (a forked child process under ``RLIMIT_AS`` and
``RLIMIT_CPU``, watched by a wall-clock deadline) and, inside the expansion, a :class:`Meter`
(elements counted as they are parsed or cloned, the deadline checked on the way) and a guard on
xacro's expressions (:func:`guarded_code`): an integer power, product or shift that would have
more than :data:`MAX_INT_BITS` bits, and a sequence repeated past the memory limit, are refused
before Python computes them, with the values at fault.

The defaults are 100 to 300 times what the largest xacro robot installed here needs (README:
"Bounded xacro expansion"). They come from, in increasing precedence: the defaults,
``[tool.inertia-kit.xacro]``, the environment variable ``INERTIA_KIT_XACRO_LIMITS``
(``timeout=60,memory=2048``) and ``--xacro-limit NAME=VALUE`` on the command line.
"""

from __future__ import annotations

import ast
import contextlib
import dataclasses
import functools
import math
import os
import time
from collections.abc import Mapping
from dataclasses import dataclass
from types import CodeType
from typing import Any

from inertia_kit.errors import ConfigError

#: The environment variable: ``NAME=VALUE`` pairs separated by commas.
ENV = "INERTIA_KIT_XACRO_LIMITS"

#: Integers with more bits than this are refused in xacro expressions: 301 030 decimal digits,
#: computed in milliseconds; Python will not even print an integer of more than 4300 digits.
MAX_INT_BITS = 1_000_000

_UNITS = {"timeout": "s", "memory": "MB", "elements": "elements"}
_WHAT = {"timeout": "SECONDS", "memory": "MB", "elements": "COUNT"}


@dataclass(frozen=True)
class XacroLimits:
    """
    The limits of one xacro expansion; ``0`` turns a limit off.

    Attributes
    ----------
    timeout : float
      Seconds of wall-clock time.
    memory : int
      MB of memory the expansion may allocate beyond what the process holds when it starts.
    elements : int
      Elements read from files or copied by macro calls and ``insert_block``.
    """

    timeout: float = 30.0
    memory: int = 1024
    elements: int = 50_000

    def __post_init__(self) -> None:
        for field in dataclasses.fields(self):
            object.__setattr__(self, field.name, check_limit(field.name, getattr(self, field.name)))

    @classmethod
    def resolve(
        cls,
        configured: Mapping[str, float] | None = None,
        given: Mapping[str, float] | None = None,
        env: Mapping[str, str] | None = None,
    ) -> XacroLimits:
        """
        The defaults, overridden by ``configured`` (``[tool.inertia-kit.xacro]``), then by the
        environment's ``INERTIA_KIT_XACRO_LIMITS``, then by ``given`` (the command line).
        ``ConfigError`` for a bad environment value.
        """
        env = os.environ if env is None else env
        values: dict[str, float] = dict(configured or {})
        text = env.get(ENV, "").strip()
        if text:
            try:
                values.update(parse_limits(text))
            except ValueError as error:
                raise ConfigError(f"{ENV}={text!r}: {error}") from None
        values.update(given or {})
        return dataclasses.replace(cls(), **values)

    def describe(self, name: str) -> str:
        """``the xacro time limit (30 s)``."""
        value = getattr(self, name)
        kind = {"timeout": "time", "memory": "memory", "elements": "element"}[name]
        return f"the xacro {kind} limit ({value:g} {_UNITS[name]})"

    def timed_out(self) -> LimitExceeded:
        """The expansion was stopped from outside at the time limit."""
        return LimitExceeded(
            f"the expansion was stopped after {self.timeout:g} s, {self.describe('timeout')}: "
            "an expression or macro in it runs too long",
            raise_hint("timeout"),
        )

    def out_of_memory(self, room_mb: float | None = None) -> LimitExceeded:
        """What a ``MemoryError`` in the expansion means: the memory limit, or, when the process
        may take less than that (``room_mb``: what its address-space limit leaves it, a
        ``ulimit -v`` or scan's ``--max-memory``), that limit."""
        if room_mb is not None and (not self.memory or room_mb < self.memory):
            return LimitExceeded(
                f"the expansion needed more memory than the {room_mb:.0f} MB this process may "
                "still take (its address-space limit: a `ulimit -v`, or scan's --max-memory)"
            )
        if not self.memory:
            return LimitExceeded("the expansion ran out of memory")
        return LimitExceeded(
            f"the expansion needed more memory than {self.describe('memory')}",
            raise_hint("memory"),
        )


def check_limit(name: str, value: Any) -> float | int:
    """``value`` as the limit ``name`` takes it; ``ValueError`` saying what is expected."""
    if name not in _UNITS:
        raise ValueError(f"unknown limit `{name}`; known: timeout, memory, elements")
    if isinstance(value, str):
        with contextlib.suppress(ValueError):
            value = float(value.strip())
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ValueError(f"`{name}` takes a number of {_UNITS[name]}, got {value!r}")
    if not math.isfinite(value) or value < 0:
        raise ValueError(f"`{name}` takes a number of {_UNITS[name]} ≥ 0 (0: none), got {value!r}")
    if name == "timeout":
        return float(value)
    if value != int(value):
        raise ValueError(f"`{name}` takes a whole number of {_UNITS[name]}, got {value!r}")
    return int(value)


def parse_limits(text: str) -> dict[str, float]:
    """``timeout=60,memory=2048`` as ``{"timeout": 60.0, "memory": 2048}``; ``ValueError``."""
    values: dict[str, float] = {}
    for item in text.split(","):
        item = item.strip()
        if not item:
            continue
        name, sep, value = item.partition("=")
        if not sep:
            raise ValueError(f"expected NAME=VALUE ({usage()}), got {item!r}")
        values[name.strip()] = check_limit(name.strip(), value)
    return values


def usage() -> str:
    """``timeout=SECONDS, memory=MB, elements=COUNT; 0: no limit``."""
    return ", ".join(f"{name}={what}" for name, what in _WHAT.items()) + "; 0: no limit"


def raise_hint(name: str) -> str:
    """How to raise the limit ``name``."""
    return (
        f"if the robot really needs more, raise it: --xacro-limit {name}={_WHAT[name]}, "
        f"{ENV} or `{name}` in [tool.inertia-kit.xacro]"
    )


class LimitExceeded(Exception):
    """
    An expansion went past one of its limits; raised inside xacro, at the work at fault.
    ``str()`` says what went past which limit; ``hint`` how to raise the limit, told last.
    """

    def __init__(self, message: str, hint: str = ""):
        super().__init__(message)
        self.hint = hint

    def told(self) -> str:
        """The message and the hint."""
        return f"{self}; {self.hint}" if self.hint else str(self)


# --- counting and the deadline ----------------------------------------------------------------


class Meter:
    """
    One expansion's use of its limits: elements counted as they are read or copied, and the
    deadline, ``time.monotonic()`` seconds (``math.inf``: none).
    """

    def __init__(self, limits: XacroLimits, start: float | None = None):
        self.limits = limits
        self.elements = 0
        start = time.monotonic() if start is None else start
        self.deadline = start + limits.timeout if limits.timeout else math.inf

    def add(self, count: int = 1) -> None:
        """``count`` more elements; ``LimitExceeded`` past the element limit or the deadline."""
        self.elements += count
        if self.limits.elements and self.elements > self.limits.elements:
            raise LimitExceeded(
                f"the expansion made more than {self.limits.elements} elements, "
                f"{self.limits.describe('elements')}: a macro that calls itself, or another "
                "macro more than once, multiplies its output at every level",
                raise_hint("elements"),
            )
        self.check_time()

    def check_time(self) -> None:
        if time.monotonic() > self.deadline:
            raise LimitExceeded(
                f"the expansion ran longer than {self.limits.describe('timeout')}",
                raise_hint("timeout"),
            )

    def builtins(self) -> dict[str, Any]:
        """The ``__builtins__`` of guarded expressions: the operators' checked versions."""
        memory = self.limits.memory * (1 << 20)
        return {
            "__inertia_kit_pow": _pow,
            "__inertia_kit_lshift": _lshift,
            "__inertia_kit_mul": functools.partial(_mul, memory=memory, limits=self.limits),
        }


# --- guarded expressions ----------------------------------------------------------------------

_GUARDED = {
    ast.Pow: "__inertia_kit_pow",
    ast.Mult: "__inertia_kit_mul",
    ast.LShift: "__inertia_kit_lshift",
}


class _Guard(ast.NodeTransformer):
    def visit_BinOp(self, node: ast.BinOp) -> ast.AST:
        self.generic_visit(node)
        name = _GUARDED.get(type(node.op))
        if name is None:
            return node
        call = ast.Call(ast.Name(name, ast.Load()), [node.left, node.right], [])
        return ast.copy_location(call, node)


@functools.lru_cache(maxsize=4096)
def guarded_code(expr: str) -> CodeType:
    """
    ``expr`` compiled as xacro's ``safe_eval`` compiles it (same errors, same refusal of
    ``__`` names), with ``**``, ``*`` and ``<<`` turned into calls of their checked versions
    (:meth:`Meter.builtins`), which refuse a result too large to compute before computing it.
    """
    import xacro

    code = compile(expr, "<expression>", "eval")
    invalid_names = [n for n in code.co_names if n.startswith("__")]
    if invalid_names:
        raise xacro.XacroException("Use of invalid name(s): ", ", ".join(invalid_names))
    if "*" not in expr and "<<" not in expr:
        return code
    tree = _Guard().visit(ast.parse(expr, mode="eval"))
    return compile(ast.fix_missing_locations(tree), "<expression>", "eval")


def _shown(value: Any) -> str:
    """An operand as a message shows it: short, whatever its size."""
    if isinstance(value, int) and not isinstance(value, bool):
        if value.bit_length() > 100:  # 31 digits or more
            return f"an integer of {_digits(math.log10(abs(value)))}"
        return str(value)
    text = repr(value)
    return text if len(text) <= 24 else f"{text[:20]}...{text[-1]} (length {len(value)})"


def _digits(log10: float) -> str:
    """``10000000001 digits``: of the integer whose decimal logarithm is ``log10``."""
    if log10 < 1e15:
        return f"{math.floor(log10) + 1} digits"
    if math.isfinite(log10):
        return f"about {log10:.3g} digits"
    return "more digits than a float can count"


def _too_many_bits(expression: str, log10: float) -> LimitExceeded:
    return LimitExceeded(
        f"{expression} would be an integer of {_digits(log10)}, more than the "
        f"{MAX_INT_BITS} bits ({_digits(MAX_INT_BITS * math.log10(2))}) a xacro expression may "
        "make: computing it takes minutes or more, and no robot description needs such a number"
    )


def _pow(base: Any, exponent: Any) -> Any:
    if (
        isinstance(base, int)
        and isinstance(exponent, int)
        and exponent > 0
        and abs(base) > 1
        and (exponent > MAX_INT_BITS or exponent * math.log2(abs(base)) > MAX_INT_BITS)
    ):
        log10 = exponent * math.log10(abs(base)) if exponent < 1e300 else math.inf
        raise _too_many_bits(f"{_shown(base)} ** {_shown(exponent)}", log10)
    return base**exponent


def _lshift(value: Any, shift: Any) -> Any:
    if (
        isinstance(value, int)
        and isinstance(shift, int)
        and value != 0
        and shift > MAX_INT_BITS - value.bit_length()
    ):
        log2 = math.log2(abs(value)) + shift if shift < 1e300 else math.inf
        raise _too_many_bits(f"{_shown(value)} << {_shown(shift)}", log2 * math.log10(2))
    return value << shift


def _mul(left: Any, right: Any, *, memory: int, limits: XacroLimits) -> Any:
    if isinstance(left, int) and isinstance(right, int):
        if left.bit_length() + right.bit_length() > MAX_INT_BITS:
            log10 = math.log10(abs(left)) + math.log10(abs(right))
            raise _too_many_bits(f"{_shown(left)} * {_shown(right)}", log10)
    elif memory:
        sequence, count = (left, right) if isinstance(right, int) else (right, left)
        if isinstance(sequence, str | bytes | list | tuple) and isinstance(count, int):
            items = len(sequence) * count
            size = items * (1 if isinstance(sequence, str | bytes) else 8)
            if size > memory:
                kind = {str: "a string", bytes: "bytes"}.get(type(sequence), "a sequence")
                unit = "characters" if isinstance(sequence, str) else "items"
                raise LimitExceeded(
                    f"{_shown(left)} * {_shown(right)} would be {kind} of {items} {unit} "
                    f"({size / (1 << 20):.0f} MB or more), over {limits.describe('memory')}",
                    raise_hint("memory"),
                )
    return left * right
