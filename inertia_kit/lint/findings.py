"""What the linter reports: ``Finding`` records, their severities, and fixes as text edits."""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import Any

from inertia_kit.description.edits import Edit
from inertia_kit.engines.vocabulary import Verdict


class Severity(enum.IntEnum):
    """Ordered, so ``--fail-on warning`` means warning and above."""

    INFO = 0
    WARNING = 1
    ERROR = 2

    def __str__(self) -> str:
        return self.name.lower()

    @classmethod
    def parse(cls, text: str) -> Severity:
        try:
            return cls[text.strip().upper()]
        except KeyError:
            raise ValueError(f"severity must be error, warning or info, got {text!r}") from None


class Safety(enum.Enum):
    """How far a fix may be trusted (ruff's applicability)."""

    SAFE = "safe"  # changes representation only
    UNSAFE = "unsafe"  # changes physical values on an assumption (density, solid mesh)
    DISPLAY_ONLY = "display-only"  # shown, never applied

    def __str__(self) -> str:
        return self.value


class Repairs(enum.Enum):
    """
    What a rule's fix repairs, which ``inertia-fill --fix MODE`` selects by: ``missing`` (a
    link that needs a mass), ``impossible`` (values no rigid body has), ``slip`` (a recognised
    slip, undone), ``doubtful`` (values that may be wrong; only ``--fix all`` takes these),
    ``likely`` (a real part's likely slip, undone: ``inertia-lint --unsafe-fixes`` offers it, no
    fill mode takes it; ``--fix all`` recomputes the link from its geometry as any other).
    """

    MISSING = "missing"
    IMPOSSIBLE = "impossible"
    SLIP = "slip"
    DOUBTFUL = "doubtful"
    LIKELY = "likely"

    def __str__(self) -> str:
        return self.value


@dataclass(frozen=True)
class FixRule:
    """
    A rule's fix (its module's ``FIX``): ``how`` the values are found (``geometry``: the
    geometry's at uniform density, a declared finite positive mass kept; ``slip``: the
    declared values with the slip undone; ``com``: the geometry's centre of mass;
    ``com-slip``: the declared values with the centre of mass's slip undone), its
    ``safety``, what it ``repairs``, and its ``title``.
    """

    how: str
    safety: Safety
    repairs: Repairs
    title: str


@dataclass(frozen=True)
class EditPlace:
    """Where an edit stands in its file: 1-based lines and columns, and byte offsets."""

    start_line: int
    start_column: int
    end_line: int
    end_column: int
    start_byte: int
    end_byte: int


@dataclass(frozen=True)
class Fix:
    """
    A finding's fix: its ``title``, the ``edits`` that make it, how far it may be trusted
    (``safety``), and where each edit stands (``places``). ``placed`` false: the values and
    safety are known but no edit was placed (a run that neither applies, shows nor writes
    fixes out: ``[*]`` and "N fixable" need no more); ``--fix`` places them.
    """

    title: str
    edits: tuple[Edit, ...]
    safety: Safety = Safety.UNSAFE
    places: tuple[EditPlace | None, ...] = ()  # one per edit, when known
    placed: bool = True

    def to_json(self) -> dict[str, Any]:
        places = self.places or (None,) * len(self.edits)
        return {
            "title": self.title,
            "safety": str(self.safety),
            "applicability": str(self.safety),
            "edits": [_edit_json(e, p) for e, p in zip(self.edits, places, strict=True)],
        }


def _edit_json(edit: Edit, place: EditPlace | None) -> dict[str, Any]:
    found = {"file": edit.path, "path": edit.path, "start": edit.start, "end": edit.end}
    if place is not None:
        found |= {
            "location": {"row": place.start_line, "column": place.start_column},
            "end_location": {"row": place.end_line, "column": place.end_column},
            "byte_range": [place.start_byte, place.end_byte],
        }
    return found | {"content": edit.content}


@dataclass(frozen=True, order=True)
class Finding:
    """
    One problem at one place. Sorts by file, line, column, code, then message.

    ``expected`` holds the computed values a rule has (JSON-ready, SI units), e.g.
    ``{"ixx": 0.0163}``; ``message`` is the one-line claim with its key numbers, ``detail`` the
    basis and arithmetic behind it, ``help`` says what to do.
    """

    path: str
    line: int | None
    column: int | None
    code: str
    name: str = field(compare=False)
    severity: Severity = field(compare=False)
    # identity includes the message and link: one macro call can yield several findings of one
    # rule at one location (one per link it produced), and none may be lost
    message: str = field(compare=True)
    link: str | None = field(default=None, compare=True)
    joint: str | None = field(default=None, compare=True)
    expected: dict[str, Any] | None = field(default=None, compare=False)
    help: str | None = field(default=None, compare=False)
    # what the one-line message leaves out: the basis, the arithmetic, what each engine does,
    # quotes (``full``, JSON, SARIF and JUnit show it; ``concise`` does not)
    detail: str | None = field(default=None, compare=False)
    fix: Fix | None = field(default=None, compare=False)
    # for xacro: where the element stands in the macro body, when path/line is the macro call
    # that produced it
    macro_path: str | None = field(default=None, compare=False)
    macro_line: int | None = field(default=None, compare=False)
    # the robots that produced it, when it is reported for a given file they include (a xacro
    # fragment handed over by a hook): the robot files, as told
    via: tuple[str, ...] = field(default=(), compare=False)
    # the fix the rule offers (its values are found and placed for the whole robot at once,
    # :mod:`inertia_kit.lint.fixing`, which sets ``fix``, or ``unfixable`` with the reason)
    wants: FixRule | None = field(default=None, compare=False)
    unfixable: str | None = field(default=None, compare=False)
    # judged by the values of ``link`` alone, which engines integrate as part of the body its
    # fixed joints weld it into: the runner lowers it when that share is negligible
    # (:mod:`inertia_kit.lint.weighing`)
    weighed: bool = field(default=False, compare=False)

    def to_json(self) -> dict[str, Any]:
        data = {
            "code": self.code,
            "name": self.name,
            "severity": str(self.severity),
            "message": self.message,
            "detail": self.detail,
            "file": self.path,
            "line": self.line,
            "column": self.column,
            "link": self.link,
            "joint": self.joint,
            "expected": self.expected,
            "help": self.help,
            "fix": None if self.fix is None else self.fix.to_json(),
            "unfixable": self.unfixable,
            "macro": None
            if self.macro_path is None
            else {"file": self.macro_path, "line": self.macro_line},
        }
        if self.via:  # only then: a finding of a file linted as itself has none
            data["via"] = list(self.via)
        return data


def severity_of(verdict: Verdict) -> Severity | None:
    """An engine event's severity: refusal → error, silent change → warning, loads → none."""
    return {
        Verdict.LOADS: None,
        Verdict.CHANGES: Severity.WARNING,
        Verdict.REFUSES: Severity.ERROR,
    }[verdict]
