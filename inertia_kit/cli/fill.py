"""``inertia-fill`` (``inertia-kit fill``): write the ``<inertial>`` blocks links need."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import click

from inertia_kit.cli.discovery import discovery_options
from inertia_kit.cli.guard import GuardedCommand
from inertia_kit.cli.options import (
    HELP,
    SCALE,
    follow_symlinks_option,
    jobs_option,
    package_path_option,
    xacro_arg_option,
    xacro_limit_option,
)
from inertia_kit.cli.printing import keep_out, redact_env_option, say, show
from inertia_kit.cli.runs import FillRun
from inertia_kit.cli.stdin import command_on_stdin, stdin_filename_option
from inertia_kit.fill.materials import materials_text
from inertia_kit.version import __version__

if TYPE_CHECKING:
    from inertia_kit.cli.filling import Finished


@click.command("fill", cls=GuardedCommand, context_settings=HELP)
@click.argument("paths", nargs=-1, type=click.Path())
@click.option(
    "--density",
    type=SCALE,
    default=None,
    metavar="KG_PER_M3",
    help="Uniform density for links without a known mass, kg/m³ [default: 1000].",
)
@click.option(
    "--material",
    default=None,
    metavar="NAME",
    help=f"Density from a material (any case; aluminum, stainless_steel too): {materials_text()}.",
)
@click.option(
    "--mass",
    "mass_options",
    multiple=True,
    metavar="LINK=KG",
    help="A link's mass, kg; its tensor is scaled to it (repeatable).",
)
@click.option(
    "--link",
    "link_options",
    multiple=True,
    metavar="NAME",
    help="Fix this link from its geometry whatever --fix says, e.g. a helper link welded to a "
    "body with mass, which no mode fills (repeatable).",
)
@click.option(
    "--total-mass",
    type=SCALE,
    default=None,
    metavar="KG",
    help="The robot's total mass, kg: the links without a known mass share what the others "
    "leave, in proportion to their volume (instead of --density).",
)
@click.option(
    "--config",
    "config_path",
    default=None,
    type=click.Path(dir_okay=False),
    metavar="FILE",
    help="Configuration file whose [links.NAME] tables give a link's density or mass "
    "[default: the nearest pyproject.toml with [tool.inertia-kit], or .inertia-kit.toml].",
)
@click.option(
    "--fix",
    type=click.Choice(["missing", "invalid", "all"]),
    default="missing",
    show_default=True,
    help="missing: links that need a mass (moving links, bodies that would be massless); "
    "invalid: also impossible <inertial>s and recognised slips (a valid declared mass is "
    "kept); all: also recompute every link that has an <inertial> and geometry. Frames and "
    "helper links welded to a body with mass are only filled when named (--link, --mass).",
)
@click.option("--diff", "show_diff", is_flag=True, help="Print a unified diff; write nothing.")
@click.option("--check", is_flag=True, help="Write nothing; exit 1 if a file would change.")
@click.option(
    "-o",
    "--output",
    default=None,
    type=click.Path(dir_okay=False),
    metavar="OUT",
    help="Write the filled robot to OUT and leave PATH (exactly one) untouched: a URDF's own "
    "text, edited; for xacro, the fully expanded URDF, where links made by macros are filled "
    "too. OUT is always written; exit 1 if links were filled or refused, 0 if none needed it.",
)
@jobs_option(
    "Accepted as inertia-lint takes it; fill runs in one process, since it writes files "
    "and robots that include one fragment must agree on what is written there."
)
@package_path_option
@xacro_arg_option
@xacro_limit_option
@discovery_options
@stdin_filename_option
@redact_env_option
@follow_symlinks_option("the filled files (and -o OUT)")
@click.version_option(__version__, prog_name="inertia-fill")
@click.pass_context
def fill_command(ctx: click.Context, paths: tuple[str, ...], **options: Any) -> None:
    """
    Write <inertial> blocks computed from each link's geometry (collision shapes, else visual
    ones, at uniform density) into URDF files, as small text edits: comments, layout, quoting
    and line endings are kept.

    \b
    PATHS are files or folders (their *.urdf and *.xacro files, as inertia-lint walks them).

    \b
    Exit codes: 0 nothing to do; 1 a file was (or would be) changed, or a link asked for
    (by --fix or by name) was not fixed (listed with the reason);
    2 unreadable input or bad usage. With -o: 1 when links were (or would be) filled into OUT
    or refused, 0 when none needed filling (OUT is written all the same).
    \b
    Examples:
      inertia-fill robot.urdf
      inertia-fill --material aluminium --mass gripper=0.35 --diff robot.urdf
      inertia-fill --fix invalid --check urdf/*.urdf
      inertia-fill --density 1200 -o robot_filled.urdf robot.urdf.xacro
      inertia-fill --total-mass 12.5 --fix all robot.urdf.xacro
    """
    run = FillRun.parse(paths, options)  # a bad option or configuration: exit 2, said
    ctx.exit(command_on_stdin(run, fill))


def fill(run: FillRun) -> int:
    """
    ``inertia-fill`` as ``run`` asks: every robot planned, then each file written (not for
    ``--diff``/``--check``), what was done printed as it is; the exit code.
    """
    from inertia_kit.cli.discovery import show_files
    from inertia_kit.cli.filling import Finished, Planned, filling
    from inertia_kit.errors import ConfigError

    if not _may_write_output(run):
        return 2
    checked, changed, refused, failed = 0, False, False, False
    try:
        if run.show_files:
            return show_files(run.paths, run.walk)
        for told in filling(run):
            if isinstance(told, Planned):
                keep_out(told.secrets)
                if told.error is not None:
                    say(f"error: {told.error}")
                failed = failed or told.error is not None
                checked += told.plan is not None and not told.again
            elif isinstance(told, Finished):
                _tell(told, run.writes)
                changed, refused = changed or told.changed, refused or told.refused
                failed = failed or told.failed
            else:
                say(f"error: --mass/--link name no link in the files: {', '.join(told.names)}")
                return 2
    except ConfigError as error:
        say(f"error: {error}")
        return 2
    if not changed and not refused:
        files = f"{checked} file{'s' if checked != 1 else ''} checked"
        # after an error the files not read may well need a change: say what was done
        done = "nothing written (errors above)" if failed else "nothing to change"
        say(f"inertia-fill: {files}, {done}")
    if failed:
        return 2
    return 1 if changed or refused else 0


def _may_write_output(run: FillRun) -> bool:
    """Whether ``-o OUT`` may be written (no symbolic link on the way, unless
    ``--follow-symlinks``); if not, say why (the exit is then 2, and nothing is done)."""
    from inertia_kit.description.output_paths import refuse_links
    from inertia_kit.errors import InputError

    if run.output is None or not run.writes:
        return True
    try:
        refuse_links(run.output, run.follow_symlinks)
    except InputError as error:
        say(f"error: -o: {error}")
        return False
    return True


def _tell(told: Finished, write: bool) -> None:
    """What was done with one planned file: its notes, the diff, what was filled, what not."""
    plan = told.plan
    for note in plan.notes:
        say(f"note: {plan.path}: {note}")
    for stale in told.removed:
        say(
            f"note: removed {stale}, a temporary file left by an inertia-fill that "
            "was killed while writing"
        )
    if told.diff:
        show(told.diff, nl=False)  # the file names in its headers escaped
    if told.error is not None:
        say(f"error: {told.error}")
    if told.done:
        say(_fill_line(plan, write, told.through))
    for name, real in told.followed:
        say(
            f"note: {name} is a symbolic link: the file it points to, {real}, "
            "was written and the link kept"
        )
    if told.crash is not None:
        say(f"error: {told.crash}")
        return
    for refusal in plan.refused:
        say(f"{plan.path}: link `{refusal.link}` not filled: {refusal.reason}")
        for line in (refusal.block or "").splitlines():  # the block to paste, line by line
            say(f"    {line}")


def _fill_line(plan: Any, write: bool, through: tuple[str, ...] = ()) -> str:
    """
    ``Filled 2 links in robot.urdf: arm 1.2 kg, ...`` (``of IN into OUT`` for ``-o``; ``in
    wheels.xacro via robot.xacro`` for a robot filled for files it includes).
    """
    filled = plan.changed_links
    where = (
        f"in {plan.path}" if plan.input_path is None else f"of {plan.input_path} into {plan.path}"
    )
    if through:
        where = f"in {', '.join(through)} via {plan.path}"
    if not filled:
        return f"Wrote {plan.path}: nothing to fill in {plan.input_path}"
    verb = "Filled" if write else "Would fill"
    count = f"{len(filled)} link{'s' if len(filled) != 1 else ''}"
    what = ", ".join(f"{f.link} {f.mass_text} kg" for f in filled)
    return f"{verb} {count} {where}: {what}"
