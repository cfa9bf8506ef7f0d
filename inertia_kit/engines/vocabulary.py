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
(``lint.findings.severity_of``). Every finding's message is one short line, ``link `x`: <Engine>
<does what>[: <the key fact>]`` (see :func:`verdict_message`), e.g. ``link `arm`: MuJoCo refuses
the model: mass 0 kg, below mjMINVAL``; its detail says why and quotes the engine's
own message (see :func:`verdict_detail`), which its ``expected`` also holds with at least
``engine`` and ``verdict`` (see :func:`verdict_expected`), so that the five engines speak alike.
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
    engine: str,
    verdict: Verdict,
    claim: str | None = None,
    what: str | None = None,
    *,
    subject: str | None = None,
) -> str:
    """
    The finding's one-line message: ``link `arm`: MuJoCo refuses the model: <claim>``.

    ``subject`` is what the event is about (``link `arm```, ``joint `j```), left out with its
    colon when ``None``; ``what`` is the verb phrase after the engine's name (default
    ``refuses the model``, ``changes the model``, ``loads the model`` by verdict), e.g.
    ``drops it with its joint``; ``claim`` is the key fact in our words (the key number, no
    engine prose: that goes to the detail), left out with its colon when ``None``.
    """
    title = TITLES[engine]
    if what is None:
        what = {
            Verdict.REFUSES: "refuses the model",
            Verdict.CHANGES: "changes the model",
            Verdict.LOADS: "loads the model",
        }[verdict]
    text = f"{title} {what}"
    if claim:
        text = f"{text}: {claim}"
    return f"{subject}: {text}" if subject else text


def verdict_detail(engine: str, why: str | None, engine_message: str | None) -> str | None:
    """
    The finding's detail: ``why`` (our sentence: the basis, the numbers), then the engine's own
    message quoted, ``MuJoCo says: "..."``; ``None`` when there is neither.
    """
    parts = []
    if why:
        parts.append(why if why.endswith((".", "!", "?")) else f"{why}.")
    if engine_message:
        parts.append(f'{TITLES[engine]} says: "{engine_message}"')
    return " ".join(parts) or None


def subject_of(link: str | None, joint: str | None = None) -> str | None:
    """The message's subject: ``link `x``` (or ``joint `j``` for a joint alone), or ``None``."""
    if link is not None:
        return f"link `{link}`"
    if joint is not None:
        return f"joint `{joint}`"
    return None


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
      The finding's one-line message, usually :func:`verdict_message` (see :func:`event`).
    engine_message : str or None
      The engine's own words, as it prints them; ``None`` when it says nothing.
    source : Source or None
      The element the event is about.
    link, joint : str or None
      The link (and joint) the event is about.
    facts : dict
      What the finding's ``expected`` holds besides the engine, verdict and engine message.
    detail : str or None
      The finding's detail: what the one-line message leaves out (why, the numbers, the
      engine's own words), usually :func:`verdict_detail`.
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
    claim: str | None = None,
    why: str | None = None,
    subject: str | None = None,
    **facts: Any,
) -> Event:
    """
    An :class:`Event` whose message reads ``<subject>: <Engine> <what>: <claim>`` (the subject
    by default :func:`subject_of` ``link``) and whose detail is ``why`` then the engine's
    message (:func:`verdict_detail`).
    """
    if subject is None:
        subject = subject_of(link)
    message = verdict_message(engine, verdict, claim, what, subject=subject)
    detail = verdict_detail(engine, why, engine_message)
    return Event(engine, verdict, kind, message, engine_message, source, link, joint, facts, detail)
