"""
What a command prints goes through here: every line it says on stderr (errors, warnings, notes,
what fill did) and every report it writes to stdout or a file.

- Names, paths and values from the files are escaped (:func:`~inertia_kit.printable.printable`):
  a link name holding a newline cannot start a line of its own (a GitHub workflow command, a
  line read as inertia-lint's), nor a C1 control or a bidirectional override rewrite the line.
  :func:`say` escapes the whole line it is given (a message is one line); the formats escape
  the pieces of their own lines, and :func:`show` prints what they rendered.
- Under ``--redact-env`` (or ``redact-environment = true``), the values the environment gave
  the xacro expansions (:mod:`~inertia_kit.description.redaction`) are kept out of all of it:
  a command adds them as it learns them (:func:`keep_out`), and everything printed after is
  redacted; the machine-read formats redact the findings themselves (:func:`redacted`), before
  they are written, so that they stay valid.

The values kept out belong to the command being run: :func:`start` (called by the commands'
guard) begins with none.
"""

from __future__ import annotations

import contextvars
from collections.abc import Iterable
from typing import Any, TypeVar

import click

from inertia_kit.description.redaction import Redaction
from inertia_kit.printable import printable

_T = TypeVar("_T")

_redaction: contextvars.ContextVar[Redaction] = contextvars.ContextVar(
    "inertia_kit_redaction",
    default=Redaction(),  # noqa: B039 - frozen: never changed, only replaced
)

#: the option every command that loads robots takes
redact_env_option = click.option(
    "--redact-env/--no-redact-env",
    "redact_env",
    default=None,
    help="Keep the values xacro read from the environment ($(env VAR), $(optenv VAR), YAML "
    "files it loads) out of every output: findings, messages, reports and pages show *** "
    "instead (values under 4 characters and booleans excepted). The expansion and the files "
    "written are unchanged [default: redact-environment in the configuration, else no].",
)


def start() -> None:
    """A command begins: nothing to keep out yet."""
    _redaction.set(Redaction())


def keep_out(values: Iterable[str]) -> None:
    """Keep ``values`` out of everything printed from now on."""
    _redaction.set(_redaction.get().with_values(values))


def redacting(option: bool | None, configured: bool) -> bool:
    """Whether to keep a file's environment values out: ``--[no-]redact-env``, else as its
    configuration says."""
    return configured if option is None else option


def redaction() -> Redaction:
    """The values kept out so far."""
    return _redaction.get()


def redacted(value: _T) -> _T:
    """``value`` (findings, errors, JSON-ready data) with the values kept out."""
    return _redaction.get().apply(value)


def clean(text: str) -> str:
    """A line as :func:`say` prints it: redacted, then escaped."""
    return printable(_redaction.get().text(text))


def say(text: str, *, err: bool = True) -> None:
    """One line (``error: FILE: ...``, ``note: ...``) on stderr, redacted and escaped."""
    click.echo(clean(text), err=err)


def show(
    text: str, *, err: bool = False, nl: bool = True, machine: bool = False, **options: Any
) -> None:
    """
    A report the formats rendered (and escaped), redacted; ``machine``: a machine-read format,
    whose values were redacted before it was rendered (a pass over its text could cut its
    syntax: a value that is also one of its keys), written byte for byte (click would strip
    what reads as a colour code from a file name in ``github``'s ``file=``, which then names
    another file).
    """
    if machine:
        click.echo(text, err=err, nl=nl, **{**options, "color": True})
    else:
        click.echo(_redaction.get().text(text), err=err, nl=nl, **options)


def report_text(text: str) -> str:
    """A rendered report, redacted, for a file (``--output-file``)."""
    return _redaction.get().text(text)
