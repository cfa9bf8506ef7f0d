"""
What the commands share: usage errors (exit 2), ``-h``, the options that say how to load a
robot (``--package-path``, ``--xacro-arg``, ``--xacro-limit``), and ``--follow-symlinks``.
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
        from inertia_kit.cli.printing import say

        say(f"error: {self.format_message()}")


class Number(click.ParamType):
    """
    A float option that mass properties can be computed from: finite, at most 1e50 in
    magnitude and not subnormal (:mod:`inertia_kit.physics.numbers`); click says what is wrong.
    """

    name = "number"

    def __init__(self, scale: bool = False):
        self.scale = scale  # a density or a mass: non-zero below 1e-50 is refused too

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None):
        from inertia_kit.physics.numbers import unusable

        try:
            number = float(value)
        except (TypeError, ValueError):
            self.fail(f"{value!r} is not a number", param, ctx)
        why = unusable(number, self.scale)
        if why is not None:
            self.fail(f"{value!r} is {why}", param, ctx)
        return number


#: the type of every numeric option; SCALE for a density or a mass
NUMBER = Number()
SCALE = Number(scale=True)


def jobs_option(help: str) -> Any:
    """``-j/--jobs N`` (N ≥ 0), with the command's own help."""
    return click.option(
        "-j", "--jobs", type=click.IntRange(min=0), default=None, metavar="N", help=help
    )


def follow_symlinks_option(writes: str) -> Any:
    """``--follow-symlinks``: write through symbolic links; ``writes`` says what is written."""
    return click.option(
        "--follow-symlinks",
        is_flag=True,
        help=f"Write {writes} through a symbolic link: without it, an output path that is (or "
        "passes through) a link, and a robot file that links out of its repository, are "
        "refused (exit 2, nothing written), so that a link planted in a pull request cannot "
        "redirect a write.",
    )


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


xacro_limit_option = click.option(
    "--xacro-limit",
    "xacro_limits",
    multiple=True,
    metavar="NAME=VALUE",
    help="A limit of each xacro expansion: timeout=SECONDS (default 30), memory=MB (1024) "
    "or elements=COUNT (50000); 0: no limit; comma-separated or repeatable. Over "
    "INERTIA_KIT_XACRO_LIMITS and [tool.inertia-kit.xacro].",
)


def parse_codes(values: tuple[str, ...]) -> tuple[str, ...]:
    """``--select IN01,IN020 --select IN002`` → ``("IN01", "IN020", "IN002")``."""
    return tuple(code.strip() for value in values for code in value.split(",") if code.strip())


def parse_xacro_limits(values: tuple[str, ...]) -> dict[str, float]:
    """``--xacro-limit timeout=60,memory=2048`` as ``{"timeout": 60.0, "memory": 2048}``."""
    from inertia_kit.description.xacro_limits import parse_limits

    limits: dict[str, float] = {}
    for value in values:
        try:
            limits.update(parse_limits(value))
        except ValueError as error:
            raise UsageError(f"--xacro-limit: {error}") from None
    return limits


def parse_xacro_args(values: tuple[str, ...]) -> dict[str, str]:
    """``--xacro-arg NAME:=VALUE`` options as ``{NAME: VALUE}``; ``UsageError`` otherwise."""
    args = {}
    for value in values:
        name, sep, text = value.partition(":=")
        if not sep or not name:
            raise UsageError(f"--xacro-arg takes NAME:=VALUE, got {value!r}")
        args[name] = text
    return args
