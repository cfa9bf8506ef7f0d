"""
The last resort of every command, so that a crash never reads as findings.

Exit codes are only 0, 1 (findings, changes), 2 (bad input, usage, or an internal error) and
130 (Ctrl-C). Every command's class is :class:`GuardedCommand` (groups :class:`GuardedGroup`):

- an exception inertia-kit did not foresee becomes ``error: FILE: internal error: ...`` with
  the file being processed (:func:`processing`) and a request to report it, and exit 2;
- Ctrl-C (``KeyboardInterrupt``) becomes ``interrupted`` and exit 130, without a traceback;
- click's own exits, usage errors and a closed pipe pass through unchanged;
- a full disk under stdout is ``error: cannot write: No space left on device``, exit 2 (no
  bug report asked for).

Commands that work file by file (lint, fill) go on with the other files after an internal
error in one (:func:`internal`), and still exit 2. ``INERTIA_KIT_TRACEBACK=1`` prints the
traceback of each internal error, for the bug report.
"""

from __future__ import annotations

import contextlib
import contextvars
import errno
import os
import signal
import sys
from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

import click

if TYPE_CHECKING:
    from pathlib import Path

    from inertia_kit.errors import InternalError

#: the exit code of an interrupted command: 128 + SIGINT, as shells report it
INTERRUPTED = 130

_processing: contextvars.ContextVar[str | None] = contextvars.ContextVar(
    "inertia_kit_processing", default=None
)


@contextlib.contextmanager
def processing(path: str | Path) -> Iterator[None]:
    """Name ``path`` in an internal error raised while the block runs."""
    token = _processing.set(str(path))
    yield
    # not on an exception: the command's guard still has to name the file
    _processing.reset(token)


def internal(error: BaseException, path: str | Path | None = None) -> InternalError:
    """``error``, unforeseen while processing ``path``, as an :class:`InternalError`."""
    from inertia_kit.errors import InternalError

    if os.environ.get("INERTIA_KIT_TRACEBACK"):
        import traceback

        traceback.print_exception(type(error), error, error.__traceback__, file=sys.stderr)
    return InternalError(error, path)


def _tolerant_streams() -> None:
    """
    A terminal whose encoding lacks a character of a message (``ᵀ`` on latin-1 or cp1252) shows
    it escaped (``\\u1d40``) instead of failing the command: every message and report goes
    through these two streams.
    """
    for stream in (sys.stdout, sys.stderr):
        if getattr(stream, "errors", None) == "strict" and hasattr(stream, "reconfigure"):
            stream.reconfigure(errors="backslashreplace")


#: write errors that say the disk is full, not that inertia-kit went wrong
_FULL = frozenset(getattr(errno, name) for name in ("ENOSPC", "EDQUOT") if hasattr(errno, name))


def _echo_if_possible(message: str) -> None:
    from inertia_kit.cli.printing import say

    with contextlib.suppress(OSError):
        say(message)


class _Guard:
    """The mixin: :meth:`invoke` turns the unforeseen into exit 2 and Ctrl-C into exit 130."""

    def invoke(self, ctx: click.Context) -> Any:
        from inertia_kit.cli import printing

        if signal.getsignal(signal.SIGINT) is not signal.SIG_IGN:
            signal.signal(signal.SIGINT, signal.default_int_handler)  # KeyboardInterrupt below
        _processing.set(None)
        printing.start()
        _tolerant_streams()
        try:
            return super().invoke(ctx)  # type: ignore[misc]
        except (click.exceptions.Exit, click.ClickException, click.Abort):
            raise
        except KeyboardInterrupt:
            click.echo("interrupted", err=True)
            raise click.exceptions.Exit(INTERRUPTED) from None
        except BrokenPipeError:
            raise  # the reader went away (`| head`): click exits quietly
        except Exception as error:
            if isinstance(error, OSError) and error.errno in _FULL:
                # the disk stdout (or a report) is written to is full: the machine's state
                _echo_if_possible(f"error: cannot write: {error.strerror}")
            else:
                printing.say(f"error: {internal(error, _processing.get())}")
            raise click.exceptions.Exit(2) from None


class GuardedCommand(_Guard, click.Command):
    """A command with the last-resort handler."""


class GuardedGroup(_Guard, click.Group):
    """A group of commands with the last-resort handler; its sub-commands are guarded too."""

    command_class = GuardedCommand
