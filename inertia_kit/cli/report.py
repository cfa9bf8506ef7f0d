"""``inertia-kit report``: the robot's link table, or the bodies each engine simulates."""

from __future__ import annotations

import click

from inertia_kit.cli.guard import GuardedCommand, processing
from inertia_kit.cli.options import (
    UsageError,
    package_path_option,
    parse_xacro_args,
    parse_xacro_limits,
    xacro_arg_option,
    xacro_limit_option,
)
from inertia_kit.cli.printing import redact_env_option


@click.command("report", cls=GuardedCommand)
@click.argument("path", type=click.Path(dir_okay=False))
@click.option(
    "--format",
    "output_format",
    type=click.Choice(["text", "markdown", "json"]),
    default="text",
    show_default=True,
)
@click.option(
    "--lumped",
    is_flag=True,
    help="Instead, the bodies each engine simulates after fixed-joint lumping: their links, "
    "combined mass, COM and tensor, and the links the engine drops.",
)
@click.option(
    "--engine",
    "engines",
    multiple=True,
    metavar="NAMES",
    help="With --lumped: mujoco, gazebo, drake, pybullet, kdl or all, comma-separated "
    "(repeatable) [default: all].",
)
@package_path_option
@xacro_arg_option
@xacro_limit_option
@redact_env_option
def report_command(
    path: str,
    output_format: str,
    lumped: bool,
    engines: tuple[str, ...],
    package_paths: tuple[str, ...],
    xacro_args: tuple[str, ...],
    xacro_limits: tuple[str, ...],
    redact_env: bool | None,
) -> None:
    """A table of the robot's links: parent joint, declared mass, COM, principal moments,
    geometry and the source line to edit; and the robot's total mass. With --lumped, the
    bodies each engine simulates."""
    from inertia_kit.cli import printing
    from inertia_kit.description.loader import load
    from inertia_kit.description.xacro_limits import XacroLimits
    from inertia_kit.engines.vocabulary import ENGINES, parse_engines
    from inertia_kit.errors import ConfigError, InputError
    from inertia_kit.lint.config_files import ConfigFinder
    from inertia_kit.report.robot import render, render_lumped

    if engines and not lumped:
        raise UsageError("--engine needs --lumped")
    try:
        chosen = parse_engines(engines) if engines else ENGINES
    except ValueError as error:
        raise UsageError(f"--engine: {error}") from None

    redacts = bool(redact_env)
    with processing(path):
        try:
            # the xacro limits of the nearest configuration, as inertia-lint takes them
            configured = ConfigFinder().for_file(path)
            redacts = printing.redacting(redact_env, configured.redact_environment)
            limits = XacroLimits.resolve(configured.xacro, parse_xacro_limits(xacro_limits))
            robot = load(
                path,
                xacro_args=parse_xacro_args(xacro_args),
                package_paths=package_paths,
                xacro_limits=limits,
            )
        except (InputError, ConfigError) as error:
            if redacts and isinstance(error, InputError):
                printing.keep_out(error.environment_values)
            raise UsageError(str(error)) from None
        if robot.fragment:
            printing.say(
                f"{path}: a xacro fragment (macros and properties only, to be included): no links"
            )
            return
        if redacts:
            printing.keep_out(robot.environment_values)
        redaction = printing.redaction()  # JSON values before they are written; text as text
        if lumped:
            text = render_lumped(robot, chosen, output_format, redaction)
        else:
            text = render(robot, output_format, redaction)
    printing.show(text, machine=output_format == "json")
