"""
What a simulator does with each link: the vocabulary the engine rules (IN07x) share.

An engine rule is a rule module with one more constant, ``ENGINE`` (one of :data:`ENGINES`).
It runs only when its engine is chosen: ``inertia-lint --engine mujoco,gazebo`` (or ``all``),
or ``engines = ["mujoco"]`` in the configuration; ``--select``/``select`` do not enable it (the
default ``IN0`` would otherwise run every engine), ``--ignore``/``ignore`` still disable it.

Each engine rule predicts, from our own model of the robot, one :class:`Verdict` per link:

- ``LOADS``: the engine takes the link as written: no finding;
- ``CHANGES``: the engine loads the model but silently changes the link (drops it, lumps it
  into its parent, substitutes or clamps a value): a warning;
- ``REFUSES``: the engine does not load the model: an error.

Every finding's message reads ``<Engine> <does what>: <the engine's own message>`` (see
:func:`verdict_message`) and its ``expected`` holds at least ``engine``, ``verdict`` and
``engine_message`` (see :func:`verdict_expected`), so that the five engines speak alike.
"""

from __future__ import annotations

import enum
from collections.abc import Iterable
from typing import Any

from inertia_kit.lint.findings import Severity

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

    @property
    def severity(self) -> Severity | None:
        """The finding's severity: refusal → error, silent change → warning, loads → none."""
        return {"loads": None, "changes": Severity.WARNING, "refuses": Severity.ERROR}[self.value]


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
