"""
Values from the environment, kept out of what inertia-kit prints (``--redact-env``,
``redact-environment = true``).

A xacro expansion reads the environment: ``$(env VAR)``, ``$(optenv VAR default)`` (when VAR is
set) and YAML files through ``xacro.load_yaml``. Those values become names, mesh paths and
numbers, and so findings, CI logs, SARIF and review pages. That is xacro's semantics, and the
files inertia-kit writes keep it; what it prints need not. The expansion records them
(:mod:`.xacro_session`, in the forked child, handed back in the expansion), and a
:class:`Redaction` replaces each with :data:`MARK` in a text, or in JSON-ready values and
findings before any format writes them.

Which values
  Every value ``$(env)`` and ``$(optenv)`` read from the environment (an ``optenv`` default is
  the file's, not the environment's), and every scalar value of every YAML file xacro loads:
  a YAML file is how CI hands parameters to xacro, and may be written from a secret at CI time,
  inside the checkout or outside it, so neither its place nor its name tells a secret from a
  constant. Keys are not values: they are the names a xacro author writes (``${cfg.mass}``).
Short values
  A value is matched as text wherever it occurs. Text shorter than :data:`MIN_LENGTH`
  characters is never redacted, and neither are booleans (``true``, ``no``, ...): a ``1``, a
  ``0.5`` or a ``true`` occurs in every line number, value and message, so hiding it would
  leave nothing readable, and it hides no secret (a three-character value is guessed from the
  numbers around it anyway).
Numbers
  A value that reads as a number is also redacted in the forms inertia-kit prints numbers in
  (``fmt`` to 3-6 significant digits, ``repr``, the form written to files), and a JSON number
  equal to it becomes ``null``. Numbers computed from it (a density from a secret mass), and
  text an expression made from it (``${'$(env X)'.upper()}``), are not recognised.
"""

from __future__ import annotations

import contextlib
import dataclasses
import math
import re
from collections.abc import Iterable
from functools import cached_property
from typing import Any

#: what stands where a value was
MARK = "***"
#: text shorter than this is never redacted (see the module's docstring)
MIN_LENGTH = 4
_BOOLEANS = frozenset({"true", "false", "yes", "no", "on", "off", "none", "null"})


def recordable(value: Any) -> str | None:
    """``value`` (a string or a number from the environment or YAML) as the text to keep out,
    or ``None`` when it is not worth recording (a boolean, ``None``, empty, too short)."""
    if isinstance(value, bool) or value is None:
        return None
    if isinstance(value, int | float):
        value = repr(value)
    if not isinstance(value, str) or len(value.strip()) < MIN_LENGTH:
        return None
    return None if value.strip().lower() in _BOOLEANS else value


@dataclasses.dataclass(frozen=True)
class Redaction:
    """
    The values to keep out of what is printed: :meth:`text` for a text (a name, a message, a
    whole report), :meth:`apply` for values (findings, errors, JSON-ready data) before a
    format writes them. An empty redaction changes nothing (and costs nothing).
    """

    values: frozenset[str] = frozenset()

    def __bool__(self) -> bool:
        return bool(self.values)

    def with_values(self, values: Iterable[str]) -> Redaction:
        """This redaction and ``values`` too."""
        added = {value for value in values if recordable(value) is not None}
        return self if added <= self.values else Redaction(self.values | added)

    @cached_property
    def _forms(self) -> tuple[str, ...]:
        """Every text to replace, longest first (a value holding another goes whole)."""
        from inertia_kit.printable import printable

        forms: set[str] = set()
        for value in self.values:
            pieces = {value, value.strip(), *(line.strip() for line in value.splitlines())}
            pieces |= _number_forms(value)
            forms |= pieces | {printable(piece) for piece in pieces}
        kept = (f for f in forms if len(f) >= MIN_LENGTH and f.lower() not in _BOOLEANS)
        return tuple(sorted(kept, key=lambda form: (-len(form), form)))

    @cached_property
    def _buckets(self) -> dict[str, tuple[str, ...]]:
        """The forms by their first :data:`MIN_LENGTH` characters, longest first."""
        buckets: dict[str, list[str]] = {}
        for form in self._forms:
            buckets.setdefault(form[:MIN_LENGTH], []).append(form)
        return {prefix: tuple(forms) for prefix, forms in buckets.items()}

    @cached_property
    def _starts(self) -> re.Pattern[str] | None:
        """Where a form may start: a lookahead for the buckets' prefixes, as a trie (an
        alternation of thousands of YAML values would cost thousands of tries per character;
        the trie is :data:`MIN_LENGTH` deep)."""
        if not self._buckets:
            return None
        trie: dict[str, dict] = {}
        for prefix in self._buckets:
            node = trie
            for char in prefix:
                node = node.setdefault(char, {})

        def pattern(node: dict[str, dict]) -> str:
            branches = [re.escape(char) + pattern(child) for char, child in sorted(node.items())]
            if len(branches) <= 1:
                return "".join(branches)
            return "(?:" + "|".join(branches) + ")"

        return re.compile(f"(?={pattern(trie)})")

    @cached_property
    def _numbers(self) -> frozenset[float]:
        numbers = set()
        for value in self.values:
            number = _number(value)
            if number is not None:
                numbers.add(number)
        return frozenset(numbers)

    def text(self, text: str) -> str:
        """``text`` with every value (and its printed forms) replaced by :data:`MARK`."""
        starts = self._starts
        if starts is None or len(text) < MIN_LENGTH:
            return text
        pieces, done = [], 0
        for match in starts.finditer(text):
            at = match.start()
            if at < done:  # inside a value already replaced
                continue
            for form in self._buckets[text[at : at + MIN_LENGTH]]:
                if text.startswith(form, at):  # the longest at the leftmost place
                    pieces += [text[done:at], MARK]
                    done = at + len(form)
                    break
        return "".join(pieces) + text[done:] if pieces else text

    def apply(self, value: Any) -> Any:
        """
        ``value`` with the values kept out: every string in it (and in its lists, tuples, dict
        values, dataclass fields, and an error's ``message`` and ``path``) through
        :meth:`text`; a float equal to a numeric value: ``None``. Dict keys are kept: they
        are a format's own names. A copy; ``value`` itself is not changed.
        """
        if not self.values:
            return value
        return self._apply(value)

    def _apply(self, value: Any) -> Any:
        if isinstance(value, str):
            return self.text(value)
        if isinstance(value, bool) or value is None or isinstance(value, int):
            return value
        if isinstance(value, float):
            return None if value in self._numbers else value
        if isinstance(value, dict):
            return {key: self._apply(item) for key, item in value.items()}
        if isinstance(value, list):
            return [self._apply(item) for item in value]
        if isinstance(value, tuple) and not hasattr(value, "_fields"):
            return tuple(self._apply(item) for item in value)
        if dataclasses.is_dataclass(value) and not isinstance(value, type):
            changes = {
                field.name: self._apply(getattr(value, field.name))
                for field in dataclasses.fields(value)
                if field.init
            }
            return dataclasses.replace(value, **changes)
        if isinstance(value, BaseException):
            # not copy.copy: a library may register a reducer for exceptions (tblib's, which
            # Dask's distributed installs) that hands the copy the original's own __dict__
            redacted = type(value).__new__(type(value))
            redacted.__dict__.update(vars(value))
            for name in ("message", "path"):
                if isinstance(getattr(value, name, None), str):
                    setattr(redacted, name, self.text(getattr(value, name)))
            redacted.args = tuple(self._apply(arg) for arg in value.args)
            return redacted
        return value


def _number(value: str) -> float | None:
    try:
        number = float(value)
    except ValueError:
        return None
    return number if math.isfinite(number) else None


def _number_forms(value: str) -> set[str]:
    """The texts inertia-kit prints a numeric ``value`` as (none for other values)."""
    from inertia_kit.physics.formatting import fmt, xml_number

    number = _number(value)
    if number is None:
        return set()
    forms = {repr(number), f"{number:g}", *(fmt(number, digits) for digits in range(3, 7))}
    with contextlib.suppress(ValueError):  # beyond what a file holds: printed by fmt only
        forms.add(xml_number(number))
    return forms
