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
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

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


def reads_stdin(paths: Sequence[str]) -> bool:
    """Whether the paths ask for stdin (``-``); ``UsageError`` when mixed with others."""
    from inertia_kit.cli.options import UsageError

    if "-" not in paths:
        return False
    if len(paths) != 1:
        raise UsageError("`-` (stdin) is the only path of a run: give no other files or folders")
    return True


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
    stdout and stderr told with that path replaced by ``filename`` (or ``-``). ``prints_text``:
    the stand-in's final text goes to stdout, the command's own stdout to stderr (or to
    ``output_file``).
    """
    from inertia_kit.lint.stand_in import stand_in

    data = _stdin()
    if data is None:
        return 2
    shown = filename if filename is not None else "-"
    try:
        with stand_in(data, filename) as path:
            out, err = io.StringIO(), io.StringIO()
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
    report, messages = (_told(s.getvalue(), path, shown) for s in (out, err))
    click.echo(messages, nl=False, err=True)
    if output_file is not None:
        from inertia_kit.cli.lint import _write_report

        if not _write_report(output_file, report, follow_symlinks):
            return 2
    else:
        click.echo(report, nl=False, err=prints_text)
    if text is not None:
        _write_bytes(text)
    return code


def _stdin() -> bytes | None:
    """The bytes of stdin, as read; ``None`` when it cannot be read (told)."""
    stream = getattr(sys.stdin, "buffer", None)
    why = "stdin is closed"  # Python sets sys.stdin to None when descriptor 0 is not open
    if stream is not None:
        from inertia_kit.description.safexml import MAX_BYTES
        from inertia_kit.reading import size_text

        try:
            data = stream.read(MAX_BYTES + 1)
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


def command_on_stdin(
    command: Callable[..., int], paths: tuple[str, ...], options: dict[str, Any], fills: bool
) -> int:
    """
    Run ``command`` (``lint`` or ``fill`` of the command line, ``fills``: the latter) on
    ``paths`` with ``options``, or, for ``-`` (or ``--stdin-filename`` alone), on stdin.
    """
    from inertia_kit.cli.discovery import discovery
    from inertia_kit.cli.options import UsageError
    from inertia_kit.errors import ConfigError
    from inertia_kit.lint.config_files import ConfigFinder

    filename = options.pop("stdin_filename", None)
    if not paths and filename is not None:
        paths = ("-",)
    if not reads_stdin(paths):
        return command(paths, **options)
    if options.get("add_noqa"):
        raise UsageError("--add-noqa writes comments into files: not with `-` (stdin)")
    try:
        finder = ConfigFinder(options.get("config_path"))
        walk = discovery(options, finder)
        configured = finder.for_file(filename or "-")
    except ConfigError as error:
        say(f"error: {error}")
        return 2
    if filename is not None and walk.for_path(Path(filename)).excludes_given(filename):
        # --force-exclude: nothing linted; fill prints the robot back unchanged (formatters do)
        data = _stdin()
        if data is None:
            return 2
        if fills and not options.get("check") and not options.get("show_diff"):
            _write_bytes(data)
        return 0
    if options.get("show_files"):
        say(filename or "-", err=False)
        return 0
    if fills:
        prints_text = not (options.get("show_diff") or options.get("check") or options["output"])
    else:
        fix = options.get("fix")
        prints_text = not options.get("show_diff") and bool(configured.fix if fix is None else fix)
    output_file = options.get("output_file")
    if output_file is not None:
        from inertia_kit.cli.lint import _may_write_report

        if not _may_write_report(output_file, bool(options.get("follow_symlinks"))):
            return 2  # before stdin is read: nothing is done
        options["output_file"] = None
    return on_stdin(
        lambda path: command((path,), **options),
        filename,
        prints_text=prints_text,
        output_file=output_file,
        follow_symlinks=bool(options.get("follow_symlinks")),
    )
