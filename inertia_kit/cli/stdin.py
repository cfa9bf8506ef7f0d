"""
``-`` as the one path of ``inertia-lint`` and ``inertia-fill``: the robot read from stdin and
processed as if it stood at ``--stdin-filename`` (:mod:`inertia_kit.lint.stand_in`), every
location told as that name (``-`` without it). ``inertia-fill -`` and ``inertia-lint --fix -``
print the resulting text on stdout (as formatters do; the report then goes to stderr).
"""

from __future__ import annotations

import contextlib
import io
import os
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any, Protocol, TypeVar

import click

from inertia_kit.cli.printing import say

stdin_filename_option = click.option(
    "--stdin-filename",
    default=None,
    metavar="PATH",
    help="With `-` (the robot read from stdin): the path it is told as, and where its "
    "configuration, relative includes, $(find) and meshes are looked for [default: `-`, "
    "in the current folder].",
)


def on_stdin(
    run: Callable[[str], int],
    filename: str | None,
    *,
    prints_text: bool,
    output_file: str | None = None,
    follow_symlinks: bool = False,
) -> int:
    """
    Read stdin, stand it in at ``filename`` and ``run`` the command on the stand-in's path; its
    stdout and stderr told, in the order it wrote them, with that path replaced by ``filename``
    (or ``-``). ``prints_text``: the stand-in's final text goes to stdout, the command's own
    stdout to stderr (or to ``output_file``).
    """
    from inertia_kit.lint.stand_in import stand_in

    data = _stdin()
    if data is None:
        return 2
    shown = filename if filename is not None else "-"
    written: list[tuple[bool, str]] = []  # (to stdout, text) in the order the command wrote
    try:
        with stand_in(data, filename) as path:
            out, err = _Captured(True, written), _Captured(False, written)
            with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
                code = run(path)
            text = _read(path) if prints_text else None
    except OSError as error:
        folder = os.path.dirname(filename or "") or "."
        say(
            f"error: -: cannot place the robot read from stdin in {folder} (where "
            f"--stdin-filename says it stands): {error.strerror or error}"
        )
        return 2
    report = []
    for to_stdout, chunk in _runs(written):
        told = _told(chunk, path, shown)
        if to_stdout and output_file is not None:
            report.append(told)  # written once the command's messages are told
        else:
            click.echo(told, nl=False, err=prints_text or not to_stdout)
    if output_file is not None:
        from inertia_kit.cli.lint import _write_report

        if not _write_report(output_file, report, follow_symlinks):
            return 2
    if text is not None:
        _write_bytes(text)
    return code


class _Captured(io.StringIO):
    """The command's stdout or stderr, each write kept in order with the other's."""

    def __init__(self, stdout: bool, written: list[tuple[bool, str]]):
        super().__init__()
        self.stdout, self.written = stdout, written

    def write(self, text: str) -> int:
        count = super().write(text)  # first: click probes with bytes, which it refuses
        self.written.append((self.stdout, text))
        return count


def _runs(written: list[tuple[bool, str]]) -> list[tuple[bool, str]]:
    """The writes with consecutive ones to the same stream joined (a name is never cut)."""
    joined: list[tuple[bool, str]] = []
    for to_stdout, text in written:
        if joined and joined[-1][0] == to_stdout:
            joined[-1] = (to_stdout, joined[-1][1] + text)
        else:
            joined.append((to_stdout, text))
    return joined


def _stdin() -> bytes | None:
    """The bytes of stdin, as read; ``None`` when it cannot be read (told)."""
    stream = getattr(sys.stdin, "buffer", None)
    why = "stdin is closed"  # Python sets sys.stdin to None when descriptor 0 is not open
    if stream is not None:
        from inertia_kit.description.safexml import MAX_BYTES
        from inertia_kit.reading import read_at_most, size_text

        try:
            data = read_at_most(stream, MAX_BYTES)
        except OSError as error:
            why = error.strerror or str(error)
        else:
            if len(data) <= MAX_BYTES:
                return data
            why = f"it is larger than {size_text(MAX_BYTES)}; no robot description is that big"
    say(f"error: -: cannot read stdin: {why}")
    return None


def _write_bytes(data: bytes) -> None:
    """``data`` on stdout as it is (after what was echoed there)."""
    sys.stdout.flush()
    sys.stdout.buffer.write(data)
    sys.stdout.buffer.flush()


def _read(path: str) -> bytes | None:
    try:
        with open(path, "rb") as stream:
            return stream.read()
    except OSError:
        return None


def _told(text: str, path: str, shown: str) -> str:
    """
    ``text`` with the stand-in told as ``shown``: its unique name replaced by the name it
    stands for (in any spelling of its folder), or, for ``-``, its whole path.
    """
    from inertia_kit.printable import printable

    name = os.path.basename(path)
    if shown != "-":
        # as the text formats escape it too (a name given with a newline)
        text = text.replace(printable(name), printable(os.path.basename(shown)))
        return text.replace(name, os.path.basename(shown))
    import json  # only for a run that reads stdin

    for raw in (os.path.abspath(path), path):
        text = text.replace(json.dumps(raw)[1:-1], "-").replace(raw, "-")
    return text.replace(name, "-")


class StdinRun(Protocol):
    """What :func:`command_on_stdin` reads of a run value (:mod:`inertia_kit.cli.runs`)."""

    paths: tuple[str, ...]
    stdin_filename: str | None
    finder: Any  # ConfigFinder
    walk: Any  # Discovery
    show_files: bool
    follow_symlinks: bool

    @property
    def reads_stdin(self) -> bool: ...
    @property
    def output_file(self) -> str | None: ...
    @property
    def echoes_excluded(self) -> bool: ...
    def prints_text(self, configured: Any) -> bool: ...
    def on(self, path: str) -> Any: ...


Run = TypeVar("Run", bound=StdinRun)


def command_on_stdin(run: Run, command: Callable[[Run], int]) -> int:
    """
    ``command(run)``, or, for ``-`` (or ``--stdin-filename`` alone), ``command`` on the robot
    read from stdin (``run.on(path)``: the run on its stand-in).
    """
    from inertia_kit.errors import ConfigError

    if not run.reads_stdin:
        return command(run)
    filename = run.stdin_filename
    try:
        configured = run.finder.for_file(filename or "-")
    except ConfigError as error:
        say(f"error: {error}")
        return 2
    if filename is not None and run.walk.for_path(Path(filename)).excludes_given(filename):
        # --force-exclude: nothing linted; fill prints the robot back unchanged (formatters do)
        data = _stdin()
        if data is None:
            return 2
        if run.echoes_excluded:
            _write_bytes(data)
        return 0
    if run.show_files:
        say(filename or "-", err=False)
        return 0
    output_file = run.output_file
    if output_file is not None:
        from inertia_kit.cli.lint import _may_write_report

        if not _may_write_report(output_file, run.follow_symlinks):
            return 2  # before stdin is read: nothing is done
    return on_stdin(
        lambda path: command(run.on(path)),
        filename,
        prints_text=run.prints_text(configured),
        output_file=output_file,
        follow_symlinks=run.follow_symlinks,
    )
