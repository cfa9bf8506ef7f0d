"""``inertia-fill`` (``inertia-kit fill``): write the ``<inertial>`` blocks links need."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import click

from inertia_kit.cli.discovery import discovery_options
from inertia_kit.cli.guard import GuardedCommand, internal, processing
from inertia_kit.cli.options import (
    HELP,
    SCALE,
    UsageError,
    follow_symlinks_option,
    jobs_option,
    package_path_option,
    parse_xacro_args,
    parse_xacro_limits,
    xacro_arg_option,
    xacro_limit_option,
)
from inertia_kit.cli.printing import keep_out, redact_env_option, redacting, say, show
from inertia_kit.cli.stdin import command_on_stdin, stdin_filename_option
from inertia_kit.fill.materials import materials_text
from inertia_kit.version import __version__


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
    ctx.exit(command_on_stdin(fill, paths, options, fills=True))


def _masses(values: tuple[str, ...]) -> dict[str, float]:
    from inertia_kit.physics.numbers import usable

    masses = {}
    for value in values:
        name, sep, text = value.partition("=")
        try:
            kg = float(text)
        except ValueError:
            kg = float("nan")
        if not sep or not name or not (kg > 0 and usable(kg, scale=True)):
            raise UsageError(
                f"--mass takes LINK=KG with a positive mass from 1e-50 to 1e50 kg, got {value!r}"
            )
        masses[name] = kg
    return masses


def fill(
    paths: tuple[str, ...] | list[str],
    *,
    density: float | None = None,
    material: str | None = None,
    mass_options: tuple[str, ...] = (),
    link_options: tuple[str, ...] = (),
    total_mass: float | None = None,
    config_path: str | None = None,
    fix: str = "missing",
    show_diff: bool = False,
    check: bool = False,
    output: str | None = None,
    package_paths: tuple[str, ...] = (),
    xacro_args: tuple[str, ...] = (),
    xacro_limits: tuple[str, ...] = (),
    jobs: int | None = None,  # accepted, unused: see the option's help
    redact_env: bool | None = None,
    follow_symlinks: bool = False,
    **discovery: Any,
) -> int:
    """
    ``inertia-fill``: plan every file, then write (not for ``--diff``/``--check``).
    ``discovery``: the options of :mod:`inertia_kit.cli.discovery`.
    """
    from inertia_kit.cli.discovery import discovery as discovery_from
    from inertia_kit.cli.discovery import show_files
    from inertia_kit.description.edits import ChangedWhileEditing
    from inertia_kit.description.output_paths import refuse_links
    from inertia_kit.description.xacro_limits import XacroLimits
    from inertia_kit.errors import ConfigError, InputError
    from inertia_kit.fill.fragments import cut, fill_targets
    from inertia_kit.fill.plan import plan_fill, written_files
    from inertia_kit.fill.policy import density_option, per_link, unknown_links
    from inertia_kit.fill.shared import disagreements, without
    from inertia_kit.lint.config_files import ConfigFinder

    try:
        if not paths:
            raise UsageError("give URDF files or folders to fill")
        if output is not None and (len(paths) != 1 or os.path.isdir(paths[0])):
            raise UsageError(f"-o takes exactly one file PATH, got {', '.join(paths)}")
        if output is not None and not (show_diff or check):
            try:
                refuse_links(output, follow_symlinks)
            except InputError as error:
                raise UsageError(f"-o: {error}") from None
        arguments = parse_xacro_args(xacro_args)
        limits = parse_xacro_limits(xacro_limits)
        try:
            density = density_option(density, material, total_mass)
        except ValueError as error:
            raise UsageError(str(error)) from None
        masses = _masses(mass_options)
        finder = ConfigFinder(config_path)
        walk = discovery_from(discovery, finder)
        if discovery.get("show_files"):
            return show_files(paths, walk)
    except UsageError as error:
        say(f"error: {error.format_message()}")
        return 2
    except ConfigError as error:
        say(f"error: {error}")
        return 2

    failed = False
    options = {
        "density": density,
        "fix": fix,
        "package_paths": package_paths,
        "xacro_args": arguments,
        "total_mass": total_mass,
    }
    try:
        chosen = fill_targets(paths, output, arguments, package_paths, limits, walk)
    except ConfigError as error:  # a bad configuration found by the walk
        say(f"error: {error}")
        return 2

    def plan_target(target: Any) -> Any:
        """The plan of one robot (``None`` when it cannot be planned: told); exit 2 on a bad
        configuration (``ConfigError`` raised)."""
        nonlocal failed
        path = target.robot
        with processing(path):
            try:
                found = finder.for_file(path)
                redacts = redacting(redact_env, found.redact_environment)
                per_file = per_link(found.links, masses)
                bounds = XacroLimits.resolve(found.xacro, limits)
                plan = plan_fill(
                    path,
                    output=output,
                    xacro_limits=bounds,
                    links=link_options,
                    **options,
                    **per_file,
                )
                if redacts:
                    keep_out(plan.environment_values)
                return cut(plan, target, chosen, arguments, package_paths, bounds)
            except ConfigError:
                raise
            except InputError as error:
                meanwhile = isinstance(error, ChangedWhileEditing)  # told, whoever reads it
                if meanwhile or not chosen.read_by_robots(target):  # else: through its robots
                    if redacts:
                        keep_out(error.environment_values)
                    say(f"error: {error}")
                    failed = True
            except Exception as error:  # a bug: reported for this file, the others go on
                say(f"error: {internal(error, path)}")
                failed = True
        return None

    planned = []
    try:
        for target in chosen.targets:
            plan = plan_target(target)
            if plan is not None:
                planned.append((target, plan))
    except ConfigError as error:
        say(f"error: {error}")
        return 2
    # robots that include one fragment and want other values there: none writes it (fill.shared)
    disagree = disagreements([(target.robot, plan) for target, plan in planned])
    planned = [(target, without(plan, target.robot, disagree)) for target, plan in planned]
    plans = [plan for _, plan in planned]
    unknown = unknown_links([*masses, *link_options], plans)
    if unknown:
        say(f"error: --mass/--link name no link in the files: {', '.join(unknown)}")
        return 2

    write = not (show_diff or check)
    changed = refused = False
    written: set[Path] = set()
    for target, plan in planned:
        if write and written & {Path(name).resolve() for name in written_files(plan)}:
            # a fragment several robots include: an earlier robot's fill wrote there, so this
            # one is planned again on the new text (else its edits would not apply)
            plan = plan_target(target)
            if plan is None:
                continue
            plan = without(plan, target.robot, disagree)
        with processing(plan.path):
            try:
                outcome = _finish(
                    plan, write, show_diff, chosen.through(plan.path), follow_symlinks
                )
            except Exception as error:  # a bug: reported for this file, the others go on
                say(f"error: {internal(error, plan.path)}")
                outcome = (False, False, True)
        if write and outcome[0]:
            written.update(Path(name).resolve() for name in written_files(plan))
        changed, refused, failed = (
            changed or outcome[0],
            refused or outcome[1],
            failed or outcome[2],
        )
    if not changed and not refused:
        checked = len(plans)
        files = f"{checked} file{'s' if checked != 1 else ''} checked"
        # after an error the files not read may well need a change: say what was done
        done = "nothing written (errors above)" if failed else "nothing to change"
        say(f"inertia-fill: {files}, {done}")
    if failed:
        return 2
    return 1 if changed or refused else 0


def _finish(
    plan: Any,
    write: bool,
    show_diff: bool,
    through: tuple[str, ...] = (),
    follow_symlinks: bool = False,
) -> tuple[bool, bool, bool]:
    """
    Tell (``--diff``) or write one planned file: whether it changed, refused a link, failed.
    A file that is a symbolic link out of its repository is not written, unless
    ``follow_symlinks`` (:mod:`~inertia_kit.lint.repository_links`).
    """
    from inertia_kit.errors import InputError
    from inertia_kit.fill.output import write_output
    from inertia_kit.fill.plan import apply, links_followed, remove_stale, written_files
    from inertia_kit.lint.repository_links import refuse_links_out

    changed = failed = False
    for note in plan.notes:
        say(f"note: {plan.path}: {note}")
    if write:
        for stale in remove_stale(plan):
            say(
                f"note: removed {stale}, a temporary file left by an inertia-fill that "
                "was killed while writing"
            )
    if show_diff and plan.changed:
        show(plan.diff(), nl=False)  # the file names in its headers escaped
    filled = plan.changed_links
    if filled or (plan.input_path is not None and write):
        followed = links_followed(plan) if write else []
        try:
            if write and plan.input_path is None:
                refuse_links_out(written_files(plan), follow_symlinks)
                apply(plan)
            elif write:
                write_output(plan, follow_symlinks)
        except InputError as error:
            say(f"error: {error}")
            failed = True
        else:
            changed = bool(filled)
            say(_fill_line(plan, write, through))
            for name, real in followed:
                say(
                    f"note: {name} is a symbolic link: the file it points to, {real}, "
                    "was written and the link kept"
                )
    for refusal in plan.refused:
        say(f"{plan.path}: link `{refusal.link}` not filled: {refusal.reason}")
        for line in (refusal.block or "").splitlines():  # the block to paste, line by line
            say(f"    {line}")
    return changed, bool(plan.refused), failed


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
