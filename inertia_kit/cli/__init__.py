"""
Command-line entry points: ``inertia-kit`` (this group of commands), and ``inertia-lint`` and
``inertia-fill``, its ``lint`` and ``fill`` commands as scripts of their own. One module per
command, each thin: parse the options, call the layer below, map the outcome to an exit code.
The CLI is the only layer that knows exit codes: 0 success, 1 findings (lint) or changes (fill),
2 bad input, usage or an internal error, 130 Ctrl-C (:mod:`.guard`, the last resort of every
command). Whatever a command prints goes through :mod:`.printing` (escaped, and redacted under
``--redact-env``).
"""

from __future__ import annotations

import os

# the CLI runs on every commit: one BLAS thread starts faster and our products are small;
# set before numpy is first imported, unless the user chose
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import importlib
from typing import Any

import click

from inertia_kit.cli.guard import GuardedGroup
from inertia_kit.cli.options import HELP
from inertia_kit.version import __version__

#: command name -> "module:attribute", imported only when that command runs (or --help lists
#: it): ``inertia-lint`` on every commit pays for the lint command alone
COMMANDS = {
    "fill": "inertia_kit.cli.fill:fill_command",
    "lint": "inertia_kit.cli.lint:lint_command",
    "mass": "inertia_kit.cli.mass:mass_group",
    "report": "inertia_kit.cli.report:report_command",
    "rules": "inertia_kit.cli.rules:rules_command",
    "scan": "inertia_kit.cli.scan:scan_command",
    "view": "inertia_kit.cli.view:view_command",
}


def _command(name: str) -> click.Command:
    module, attribute = COMMANDS[name].split(":")
    return getattr(importlib.import_module(module), attribute)


class _LazyGroup(GuardedGroup):
    """A group whose sub-commands are imported when used (click's lazy-loading pattern)."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted(COMMANDS)

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        return _command(cmd_name) if cmd_name in COMMANDS else None


@click.group(cls=_LazyGroup, context_settings=HELP)
@click.version_option(__version__, prog_name="inertia-kit")
def main() -> None:
    """inertia-kit: physically right <inertial> blocks for URDF and xacro robot descriptions."""


def __getattr__(name: str) -> Any:
    """The console scripts of pyproject.toml's [project.scripts]: each imports its command only."""
    if name == "lint_main":
        return _command("lint")
    if name == "fill_main":
        return _command("fill")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
