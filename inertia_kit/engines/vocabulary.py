"""
What a simulator does with each link: the words the engine models and the engine rules (IN07x)
share.

An engine rule is a rule module with one more constant, ``ENGINE`` (one of :data:`ENGINES`).
It runs only when its engine is chosen: ``inertia-lint --engine mujoco,gazebo`` (or ``all``),
or ``engines = ["mujoco"]`` in the configuration; ``--select``/``select`` do not enable it (the
default ``IN0`` would otherwise run every engine), ``--ignore``/``ignore`` still disable it.

Each engine model (``engines/<engine>.py``) predicts, from our own model of the robot, what the
engine does with each link as :class:`Event` values, each with a :class:`Verdict`:

- ``LOADS``: the engine takes the link as written (no event is made for it);
- ``CHANGES``: the engine loads the model but silently changes the link (drops it, lumps it
  into its parent, substitutes or clamps a value);
- ``REFUSES``: the engine does not load the model.

The rule turns each event into a finding; the lint layer gives a verdict its severity
(``lint.findings.severity_of``). Every finding's message reads ``<Engine> <does what>: <the
engine's own message>`` (see :func:`verdict_message`) and its ``expected`` holds at least
``engine``, ``verdict`` and ``engine_message`` (see :func:`verdict_expected`), so that the five
engines speak alike.
"""

from __future__ import annotations

import enum
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

from inertia_kit.description.model import Source

ENGINES: tuple[str, ...] = ("mujoco", "gazebo", "drake", "pybullet", "kdl")
TITLES: dict[str, str] = {
    "mujoco": "MuJoCo",
    "gazebo": "Gazebo",
    "drake": "Drake",
    "pybullet": "PyBullet",
    "kdl": "KDL",
}
ALL = "all"


class Verdict(enum.Enum):
    """What an engine does with a link (ordered by how bad: ``LOADS < CHANGES < REFUSES``)."""

    LOADS = "loads"
    CHANGES = "changes"
    REFUSES = "refuses"

    def __str__(self) -> str:
        return self.value

    @property
    def rank(self) -> int:
        return ("loads", "changes", "refuses").index(self.value)


def parse_engines(values: Iterable[str]) -> tuple[str, ...]:
    """
    Engine names from the command line or configuration: each value may be comma-separated;
    ``all`` stands for every engine. Case-insensitive; the result is in :data:`ENGINES` order,
    each once.

    Raises
    ------
    ValueError
        For an unknown name, with the known ones in the message.
    """
    chosen: set[str] = set()
    for value in values:
        for name in value.split(","):
            name = name.strip().lower()
            if not name:
                continue
            if name == ALL:
                chosen.update(ENGINES)
            elif name in ENGINES:
                chosen.add(name)
            else:
                raise ValueError(
                    f"unknown engine `{name}`; known: {', '.join(ENGINES)} (or `{ALL}`)"
                )
    return tuple(engine for engine in ENGINES if engine in chosen)


def verdict_message(
    engine: str, verdict: Verdict, engine_message: str | None, what: str | None = None
) -> str:
    """
    The finding's message: ``MuJoCo refuses the model: <engine's own message>``.

    ``what`` is the verb phrase after the engine's name (default ``refuses the model``,
    ``changes the model``, ``loads the model`` by verdict), e.g. ``lumps link `imu` into
    `base```; ``engine_message`` is quoted as the engine prints it, or left out (with its
    colon) when the engine says nothing.
    """
    title = TITLES[engine]
    if what is None:
        what = {
            Verdict.REFUSES: "refuses the model",
            Verdict.CHANGES: "changes the model",
            Verdict.LOADS: "loads the model",
        }[verdict]
    text = f"{title} {what}"
    return f"{text}: {engine_message}" if engine_message else text


def verdict_expected(
    engine: str, verdict: Verdict, engine_message: str | None, **more: Any
) -> dict[str, Any]:
    """The finding's ``expected``: ``engine``, ``verdict``, ``engine_message`` and ``more``."""
    return {"engine": engine, "verdict": str(verdict), "engine_message": engine_message, **more}


@dataclass(frozen=True)
class Event:
    """
    One thing an engine does to the model, as a finding tells it.

    Attributes
    ----------
    engine : str
      One of :data:`ENGINES`.
    verdict : Verdict
      ``CHANGES`` or ``REFUSES``.
    kind : str
      What happens, a short stable name within the engine (``dropped``, ``sphere``, MuJoCo's
      compiler stage): the rule chooses its advice by it.
    message : str
      The finding's sentence, usually :func:`verdict_message` (see :func:`event`).
    engine_message : str or None
      The engine's own words, as it prints them; ``None`` when it says nothing.
    source : Source or None
      The element the event is about.
    link, joint : str or None
      The link (and joint) the event is about.
    facts : dict
      What the finding's ``expected`` holds besides the engine, verdict and engine message.
    detail : str or None
      The finding's detail: what the one-line message leaves out (the engine's own words, what
      follows from the event).
    """

    engine: str
    verdict: Verdict
    kind: str
    message: str
    engine_message: str | None
    source: Source | None
    link: str | None = None
    joint: str | None = None
    facts: dict[str, Any] = field(default_factory=dict)
    detail: str | None = None

    @property
    def expected(self) -> dict[str, Any]:
        """The finding's ``expected`` (see :func:`verdict_expected`)."""
        return verdict_expected(self.engine, self.verdict, self.engine_message, **self.facts)


def event(
    engine: str,
    verdict: Verdict,
    kind: str,
    what: str,
    engine_message: str | None,
    source: Source | None,
    *,
    link: str | None = None,
    joint: str | None = None,
    **facts: Any,
) -> Event:
    """An :class:`Event` whose message reads ``<Engine> <what>: <engine_message>``."""
    message = verdict_message(engine, verdict, engine_message, what)
    return Event(engine, verdict, kind, message, engine_message, source, link, joint, facts)
