"""
What the commands share: usage errors (exit 2), ``-h``, and the options that say how to load a
robot (``--package-path``, ``--xacro-arg``).
"""

from __future__ import annotations

from typing import Any

import click

#: every command answers ``-h`` as well as ``--help``
HELP = {"help_option_names": ["-h", "--help"]}


class UsageError(click.ClickException):
    """Bad input, usage or configuration: exit 2 (click's default of 1 would read as findings)."""

    exit_code = 2

    def show(self, file: Any = None) -> None:
        click.echo(f"error: {self.format_message()}", err=True)


package_path_option = click.option(
    "--package-path",
    "package_paths",
    multiple=True,
    type=click.Path(file_okay=False),
    help="Folder searched first for $(find pkg) and package://pkg, and for relative mesh paths "
    "after the file's own folder (PyBullet's search path); repeatable.",
)
xacro_arg_option = click.option(
    "--xacro-arg",
    "xacro_args",
    multiple=True,
    metavar="NAME:=VALUE",
    help="A xacro argument (repeatable).",
)


def parse_xacro_args(values: tuple[str, ...]) -> dict[str, str]:
    """``--xacro-arg NAME:=VALUE`` options as ``{NAME: VALUE}``; ``UsageError`` otherwise."""
    args = {}
    for value in values:
        name, sep, text = value.partition(":=")
        if not sep or not name:
            raise UsageError(f"--xacro-arg takes NAME:=VALUE, got {value!r}")
        args[name] = text
    return args
