"""``inertia-lint`` (``inertia-kit lint``): lint files and folders, print the findings."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any

import click

from inertia_kit.cli.discovery import discovery_options
from inertia_kit.cli.guard import GuardedCommand, internal
from inertia_kit.cli.options import (
    HELP,
    UsageError,
    follow_symlinks_option,
    jobs_option,
    package_path_option,
    parse_codes,
    parse_xacro_args,
    parse_xacro_limits,
    xacro_arg_option,
    xacro_limit_option,
)
from inertia_kit.cli.printing import redact_env_option, say, show
from inertia_kit.cli.stdin import command_on_stdin, stdin_filename_option
from inertia_kit.version import __version__

if TYPE_CHECKING:
    from pathlib import Path

OUTPUT_FORMATS = ("full", "concise", "json", "github", "sarif", "junit", "gitlab")
#: formats a program reads: their findings are redacted before they are rendered, never after
MACHINE = ("json", "github", "sarif", "junit", "gitlab")
#: formats printed file by file as the files are linted (json and sarif are one document)
STREAMED = ("full", "concise", "github")


def _colour() -> bool | None:
    """``None``: colour on a terminal only (click strips it elsewhere); NO_COLOR, FORCE_COLOR."""
    if os.environ.get("NO_COLOR"):
        return False
    if os.environ.get("FORCE_COLOR"):
        return True
    return None


@click.command("lint", cls=GuardedCommand, context_settings=HELP)
@click.argument("paths", nargs=-1, type=click.Path())
@click.option(
    "--output-format",
    type=click.Choice(OUTPUT_FORMATS),
    default="full",
    show_default=True,
    help="How findings are printed (to stdout). full and concise show control characters in "
    "names, paths and values as escapes (\\n, \\x1b, \\u202e), so that a name cannot start "
    "a line (a CI workflow command); the others carry them exactly. full shows 120 characters "
    "of a longer source line, around the element.",
)
@click.option(
    "-q",
    "--quiet",
    is_flag=True,
    help="Print only the findings: no notes (skipped fragments) and no summary; errors and "
    "warnings still go to stderr.",
)
@click.option(
    "--output-file",
    "-o",
    type=click.Path(dir_okay=False),
    default=None,
    help="Write the report (findings, --statistics or --diff) to this file, atomically, "
    "instead of stdout.",
)
@jobs_option(
    "Lint in N processes, output in input order as with one [default: the usable cores "
    "when there are several files; 0: the same]. --fix always runs in one."
)
@click.option(
    "--select",
    multiple=True,
    metavar="CODES",
    help="Rules to run: codes, code prefixes or names, comma-separated (repeatable). "
    "Replaces the configured select and ignore lists.",
)
@click.option(
    "--ignore",
    multiple=True,
    metavar="CODES",
    help="Rules not to run, as --select (repeatable); added to the configured ignore list.",
)
@click.option(
    "--engine",
    "engines",
    multiple=True,
    metavar="NAMES",
    help="Predict what these simulators do with each link (loads, silently changes or "
    "refuses it, with the engine's own message): mujoco, gazebo, drake, pybullet, kdl or all, "
    "comma-separated (repeatable). Replaces the configured `engines`; none by default.",
)
@click.option(
    "--fail-on",
    type=click.Choice(["error", "warning", "info"]),
    default=None,
    help="Lowest severity that makes the exit code 1 [default: fail-on in the "
    "configuration, else warning].",
)
@click.option(
    "--exit-zero",
    is_flag=True,
    help="Exit 0 even with findings (unreadable input or bad configuration still exit 2).",
)
@click.option(
    "--fix/--no-fix",
    "fix",
    default=None,
    help="Apply the safe fixes (a recognised slip undone), lint again until none applies, and "
    "report what remains [default: fix in the configuration, else no].",
)
@click.option(
    "--unsafe-fixes/--no-unsafe-fixes",
    "unsafe_fixes",
    default=None,
    help="Also the unsafe ones (values from the geometry at an assumed uniform density): "
    "applied with --fix or --diff, else shown as available [default: unsafe-fixes in the "
    "configuration, else no].",
)
@click.option(
    "--diff",
    "show_diff",
    is_flag=True,
    help="Print the fixes as a unified diff and write nothing; exit 1 when there is a diff.",
)
@click.option(
    "--statistics", is_flag=True, help="Print how often each rule fired instead of the findings."
)
@click.option(
    "--config",
    "config_path",
    type=click.Path(dir_okay=False),
    default=None,
    help="Configuration file for every linted file (pyproject.toml or .inertia-kit.toml) "
    "instead of the nearest one.",
)
@package_path_option
@xacro_arg_option
@xacro_limit_option
@discovery_options
@stdin_filename_option
@click.option(
    "--add-noqa",
    "--add-suppressions",
    "add_noqa",
    is_flag=True,
    help="Write an `ignore[...]` comment before the element of every current finding (honouring "
    "--select, --ignore and the configuration), so that only new findings fail; a comment "
    "already there gains the codes. Prints how many were written where.",
)
@redact_env_option
@follow_symlinks_option("the report (--output-file) and the fixed files (--fix, --add-noqa)")
@click.option("--explain", metavar="CODE", default=None, help="Print a rule's document and exit.")
@click.version_option(__version__, prog_name="inertia-lint")
@click.pass_context
def lint_command(ctx: click.Context, paths: tuple[str, ...], **options: Any) -> None:
    """
    Lint the <inertial> blocks of URDF and xacro robot descriptions: files, or folders (their
    *.urdf and *.xacro files; xacro fragments that only define macros are skipped).

    \b
    Exit codes: 0 no findings at or above --fail-on (after --fix: none remaining); 1
    findings (--diff: a diff); 2 unreadable input, bad configuration or usage.
    \b
    Examples:
      inertia-lint urdf/
      inertia-lint --select IN01,IN020 --output-format concise robot.urdf.xacro
      inertia-lint --engine mujoco,gazebo robot.urdf
      inertia-lint --fix --unsafe-fixes urdf/
      inertia-lint --explain IN002
      inertia-lint --stdin-filename urdf/robot.urdf - < robot.urdf
    """
    ctx.exit(command_on_stdin(lint, paths, options, fills=False))


def lint(
    paths: tuple[str, ...] | list[str],
    *,
    output_format: str = "full",
    select: tuple[str, ...] = (),
    ignore: tuple[str, ...] = (),
    engines: tuple[str, ...] = (),
    fail_on: str | None = None,
    exit_zero: bool = False,
    statistics: bool = False,
    config_path: str | None = None,
    package_paths: tuple[str, ...] = (),
    xacro_args: tuple[str, ...] = (),
    xacro_limits: tuple[str, ...] = (),
    explain: str | None = None,
    add_noqa: bool = False,
    fix: bool | None = None,
    unsafe_fixes: bool | None = None,
    show_diff: bool = False,
    quiet: bool = False,
    output_file: str | None = None,
    jobs: int | None = None,
    redact_env: bool | None = None,
    follow_symlinks: bool = False,
    **discovery: Any,
) -> int:
    """
    ``inertia-lint``: print what it finds; return the exit code. ``discovery``: the options
    of :mod:`inertia_kit.cli.discovery` (``--exclude``, ``--show-files``, ...).
    """
    if explain is not None:
        from inertia_kit.lint.documents import explain as document

        try:
            click.echo(document(explain), nl=False)
        except LookupError as error:
            say(f"error: --explain: {error}")
            return 2
        return 0
    if not paths:
        say("error: give files or folders to lint (or --explain CODE)")
        return 2

    from inertia_kit.cli import printing
    from inertia_kit.cli.discovery import discovery as discovery_from
    from inertia_kit.cli.discovery import show_files
    from inertia_kit.errors import ConfigError, InternalError
    from inertia_kit.lint.applying import applicable
    from inertia_kit.lint.config_files import ConfigFinder
    from inertia_kit.lint.findings import Finding, Severity
    from inertia_kit.lint.merge import merge
    from inertia_kit.lint.output import render
    from inertia_kit.lint.output.summary import statistics as rule_statistics
    from inertia_kit.lint.paths import lint_paths
    from inertia_kit.lint.runner import FileResult

    if add_noqa and output_file is not None:
        say(
            "error: --output-file: --add-noqa writes comments into the files and prints no "
            "report to write; drop one of them"
        )
        return 2
    if output_file is not None and not _may_write_report(output_file, follow_symlinks):
        return 2
    try:
        finder = ConfigFinder(config_path)
        walk = discovery_from(discovery, finder)
        if discovery.get("show_files"):
            return show_files(paths, walk)
    except (ConfigError, UsageError) as error:
        message = error.format_message() if isinstance(error, UsageError) else str(error)
        say(f"error: {message}")
        return 2

    def learn(result: FileResult) -> None:
        """Keep what the environment gave ``result``'s robot out of the output, if asked."""
        if printing.redacting(redact_env, finder.for_file(result.path).redact_environment):
            printing.keep_out(result.environment_values)

    def crashed(file: Path, error: Exception) -> FileResult:
        # a bug in one file's linting: reported for it (exit 2), the other files are linted
        return FileResult(str(file), error=internal(error, file))

    from inertia_kit.cli.progress import Progress

    progress = Progress.for_terminal(quiet)
    streams = output_format in STREAMED and not (statistics or show_diff or output_file or add_noqa)
    printed: dict[tuple, None] = {}  # the findings already printed, as merge keys

    def told(result: FileResult, settled: list[Finding]) -> None:
        learn(result)
        fresh = [f for f in settled if _key(f) not in printed]
        if fresh:
            printed.update(dict.fromkeys(map(_key, fresh)))
            progress.clear()
            text = render(
                printing.redacted(fresh),
                output_format,
                style=click.style,
                unsafe_fixes=result.unsafe_fixes,
            )
            show(text, nl=False, color=_colour(), machine=output_format in MACHINE)

    def lint_all(**streaming: Any) -> list[FileResult]:
        return lint_paths(
            paths,
            config=config_path,
            select=parse_codes(select),
            ignore=parse_codes(ignore),
            engines=engines or None,
            fail_on=None if fail_on is None else Severity.parse(fail_on),
            xacro_args=parse_xacro_args(xacro_args),
            package_paths=package_paths,
            xacro_limits=parse_xacro_limits(xacro_limits),
            on_error=crashed,
            fix=fix,
            unsafe_fixes=unsafe_fixes,
            diff=show_diff,
            discovery=walk,
            jobs=jobs,
            follow_symlinks=follow_symlinks,
            **streaming,
        )

    try:
        results = lint_all(told=told if streams else None, progress=progress.update)
    except (ConfigError, UsageError) as error:
        message = error.format_message() if isinstance(error, UsageError) else str(error)
        say(f"error: {message}")
        return 2
    finally:
        progress.clear()  # also on Ctrl-C, before `interrupted`
    for result in results:
        learn(result)

    if add_noqa:
        from inertia_kit.cli.add_noqa import add_noqa as write_suppressions

        return write_suppressions(
            paths,
            results,
            lint_all,
            quiet=quiet,
            follow_symlinks=follow_symlinks,
            diff=show_diff,
        )
    run = merge(results)
    for level, text in run.messages:
        if quiet and level == "note":
            continue
        say(f"{level}: {text}")
    if not results:
        say(f"warning: no robot descriptions (*.urdf, *.xacro) in {', '.join(paths)}")
    unsafe = any(result.unsafe_fixes for result in results)
    if show_diff:
        # as ruff: the diff on stdout, instead of the findings
        output = run.diff
    elif statistics:
        output = rule_statistics(run.findings, as_json=output_format == "json")
    else:
        # a file gets no colour codes: only a terminal reads them
        style = None if output_file else click.style
        rest = [finding for finding in run.findings if _key(finding) not in printed]
        output = render(
            printing.redacted(rest),
            output_format,
            errors=printing.redacted(run.errors),
            style=style,
            unsafe_fixes=unsafe,
            linted=printing.redacted(run.linted),
        )
    # the machine-read formats were given redacted findings: a pass over their text could cut
    # their syntax (a value that is also a key); statistics hold no value from a file
    machine = output_format in MACHINE and not show_diff
    if output_file is None:
        show(output, nl=False, color=_colour(), machine=machine)
    elif not _write_report(
        output_file, output if machine else printing.report_text(output), follow_symlinks
    ):
        return 2
    crashes = sum(isinstance(error, InternalError) for error in run.errors)
    fixable = 0 if show_diff else sum(applicable(f, unsafe) for f in run.findings)
    if not quiet:
        _echo_summary(run, crashes, fixable, show_diff)
    if run.errors:
        return 2
    if show_diff:
        return 1 if run.diff else 0
    return 1 if run.failing and not exit_zero else 0


def _key(finding: Any) -> tuple:
    """A finding as :func:`~inertia_kit.lint.merge.merge` tells it once."""
    return (finding.path, finding.line, finding.column, finding.code, finding.message)


def _may_write_report(path: str, follow_symlinks: bool) -> bool:
    """Whether the report may go to ``path`` (no symbolic link on the way, unless
    ``--follow-symlinks``); if not, say why (the exit is then 2, and nothing is done)."""
    from inertia_kit.description.output_paths import refuse_links
    from inertia_kit.errors import InputError

    try:
        refuse_links(path, follow_symlinks)
    except InputError as error:
        say(f"error: --output-file: {error}")
        return False
    return True


def _write_report(path: str, output: str, follow_symlinks: bool = False) -> bool:
    """Write the report to ``path`` atomically; on failure say why (the exit is then 2)."""
    from inertia_kit.description.edits import write_atomic
    from inertia_kit.errors import InputError

    if not _may_write_report(path, follow_symlinks):
        return False
    try:
        # a file name that is no UTF-8 (github's file=) is written as its own bytes, as stdout does
        data = output.encode("utf-8", "surrogateescape")
        write_atomic(path, data, create=True, follow_symlinks=follow_symlinks)
    except InputError as error:
        say(f"error: --output-file: {error}")
        return False
    return True


def _echo_summary(run: Any, crashes: int, fixable: int, show_diff: bool) -> None:
    """The summary line on stderr (``Found ...``, ``No findings ...``)."""
    from inertia_kit.lint.output.summary import summary

    click.echo(
        summary(
            run.findings,
            run.checked,
            len(run.errors) - crashes,
            crashes,
            flagged=run.flagged,
            fixed=run.fixed,
            fixable=fixable,
            hidden=0 if show_diff else run.hidden,
        ),
        err=True,
    )
