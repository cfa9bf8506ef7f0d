"""
Command-line entry points: ``inertia-kit`` (this group of commands), and ``inertia-lint`` and
``inertia-fill``, its ``lint`` and ``fill`` commands as scripts of their own. One module per
command, each thin: parse the options, call the layer below, map the outcome to an exit code.
The CLI is the only layer that knows exit codes: 0 success, 1 findings (lint) or changes (fill),
2 bad input or usage.
"""

from __future__ import annotations

import os

# the CLI runs on every commit: one BLAS thread starts faster and our products are small;
# set before numpy is first imported, unless the user chose
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import click

from inertia_kit.cli.fill import fill_command
from inertia_kit.cli.lint import lint_command
from inertia_kit.cli.mass import mass_group
from inertia_kit.cli.options import HELP
from inertia_kit.cli.report import report_command
from inertia_kit.version import __version__


@click.group(context_settings=HELP)
@click.version_option(__version__, prog_name="inertia-kit")
def main() -> None:
    """inertia-kit: physically right <inertial> blocks for URDF and xacro robot descriptions."""


for _command in (mass_group, report_command, lint_command, fill_command):
    main.add_command(_command)

# the console scripts of pyproject.toml's [project.scripts]
lint_main = lint_command
fill_main = fill_command
