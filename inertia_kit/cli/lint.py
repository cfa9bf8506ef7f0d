"""``inertia-lint`` (``inertia-kit lint``): lint files and folders, print the findings."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any

import click

from inertia_kit.cli.discovery import discovery_options
from inertia_kit.cli.guard import GuardedCommand, internal
from inertia_kit.cli.options import (
    HELP,
    follow_symlinks_option,
    jobs_option,
    package_path_option,
    xacro_arg_option,
    xacro_limit_option,
)
from inertia_kit.cli.printing import redact_env_option, say, show
from inertia_kit.cli.runs import LintRun
from inertia_kit.cli.stdin import command_on_stdin, stdin_filename_option
from inertia_kit.version import __version__

if TYPE_CHECKING:
    from collections.abc import Iterable
    from pathlib import Path

    from inertia_kit.lint.merge import Merged
    from inertia_kit.lint.paths import Linted
    from inertia_kit.lint.runner import FileResult

OUTPUT_FORMATS = ("full", "concise", "json", "github", "sarif", "junit", "gitlab")


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
    help="Print only the findings: no notes (the robots a fragment was linted through, a "
    "fragment no robot includes) and no summary; errors and warnings still go to stderr.",
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
    *.urdf and *.xacro files). A xacro file (or a file without links) that robots of its
    repository include is linted through them too: their findings located in it are reported,
    each saying `via` which robot (a robot also given reports them as its own). A fragment
    (macros and properties, no links) has no findings of its own: one no robot includes gets
    a note, nothing to lint.

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
    if options["explain"] is not None:
        ctx.exit(_explain(options["explain"]))
    run = LintRun.parse(paths, options)  # a bad option or configuration: exit 2, said
    ctx.exit(command_on_stdin(run, lint))


def lint(run: LintRun) -> int:
    """
    ``inertia-lint`` as ``run`` asks: the findings printed as the files are linted (the
    streamed formats), the rest at the end, then the summary; the exit code.

    The findings told (printed, or kept on disk for a report written at the end) leave the
    run's results as they are told: its memory does not grow with the number of files.
    """
    from inertia_kit.cli.discovery import show_files
    from inertia_kit.cli.progress import Progress
    from inertia_kit.errors import ConfigError
    from inertia_kit.lint.merge import merge
    from inertia_kit.lint.paths import linting

    if run.output_file is not None and not _may_write_report(run.output_file, run.follow_symlinks):
        return 2
    progress = Progress.for_terminal(run.quiet)
    # --add-noqa writes a comment for every finding: it keeps them all
    release = not run.add_noqa
    with _Told(run) as told:
        try:
            if run.show_files:
                return show_files(run.paths, run.walk)
            with linting(run.paths, on_error=_crashed, release=release, **run.linting()) as files:
                for step in files:
                    for linted in step.ready:
                        told.linted(linted, progress)
                    progress.update(step.done, step.total, step.current)
        except ConfigError as error:
            say(f"error: {error}")
            return 2
        finally:
            progress.clear()  # also on Ctrl-C, before `interrupted`
        if run.add_noqa:
            from inertia_kit.cli.add_noqa import add_noqa
            from inertia_kit.lint.paths import lint_paths

            def again() -> list[FileResult]:
                return lint_paths(run.paths, on_error=_crashed, **run.linting())

            return add_noqa(
                run.paths, files.results, again, run.quiet, run.follow_symlinks, run.diff
            )
        merged = merge(files.results, files.told)
        for level, text in merged.messages:
            if not (run.quiet and level == "note"):
                say(f"{level}: {text}")
        if not files.results:
            say(f"warning: no robot descriptions (*.urdf, *.xacro) in {', '.join(run.paths)}")
        if not told.report(merged, files.results):
            return 2
    if not run.quiet:
        _echo_summary(run, merged, files.results)
    if merged.errors:
        return 2
    if run.diff:
        return 1 if merged.diff else 0
    return 1 if merged.failing and not run.exit_zero else 0


def _explain(code: str) -> int:
    """``--explain CODE``: print the rule's document."""
    from inertia_kit.lint.documents import explain

    try:
        click.echo(explain(code), nl=False)
    except LookupError as error:
        say(f"error: --explain: {error}")
        return 2
    return 0


def _crashed(file: Path, error: Exception) -> FileResult:
    """A bug in one file's linting: reported for it (exit 2), the other files are linted."""
    from inertia_kit.lint.runner import FileResult

    return FileResult(str(file), error=internal(error, file))


class _Told:
    """
    Where a run's findings go as they are told: printed file by file (the streamed formats),
    or kept on disk (:class:`~inertia_kit.lint.output.spool.Spool`) for the report written at
    the end (the documents, ``--output-file``), which is then written piece by piece; a run
    that prints statistics or a diff keeps only their counts (``Linting.told``).
    """

    def __init__(self, run: LintRun):
        self.run = run
        self.spool: Any = None
        if not (run.streams or run.statistics or run.diff or run.add_noqa):
            from inertia_kit.cli import printing
            from inertia_kit.lint.output.spool import Spool

            # redacted as they are read back: by then every file's values are known
            self.spool = Spool(printing.redacted)

    def __enter__(self) -> _Told:
        return self

    def __exit__(self, *exception: object) -> None:
        if self.spool is not None:
            self.spool.close()

    def linted(self, linted: Linted, progress: Any) -> None:
        """
        One file linted, with every file before it: what the environment gave its robot kept
        out of the output (if asked), and its settled findings printed (the streamed formats)
        or kept for the report. After the first, the heap start-up made is settled (once).
        """
        from inertia_kit.cli import printing
        from inertia_kit.lint.output import render
        from inertia_kit.lint.parallel import settle_start_up

        settle_start_up()

        run, result = self.run, linted.result
        if run.redacts(result.path):
            printing.keep_out(result.environment_values)
        if self.spool is not None:
            self.spool.extend(linted.settled)
        elif run.streams and linted.settled:
            progress.clear()
            text = render(
                printing.redacted(linted.settled),
                run.output_format,
                style=click.style,
                unsafe_fixes=result.unsafe_fixes,
            )
            show(text, nl=False, color=_colour(), machine=run.machine)

    def report(self, merged: Merged, results: list[FileResult]) -> bool:
        """
        The report at the end, on stdout or to ``--output-file``: the diff, the statistics, or
        the findings not printed yet; ``False`` when it could not be written (said: exit 2).
        """
        from inertia_kit.cli import printing
        from inertia_kit.lint.output import pieces
        from inertia_kit.lint.output.summary import statistics

        run = self.run
        if run.diff:
            # as ruff: the diff on stdout, instead of the findings
            output: Iterable[str] = [merged.diff]
        elif run.statistics:
            output = [statistics(merged.tally, as_json=run.output_format == "json")]
        else:
            if self.spool is not None:
                self.spool.extend(merged.findings)
                findings = self.spool
            else:
                findings = printing.redacted(merged.findings)
            output = pieces(
                findings,
                run.output_format,
                errors=printing.redacted(merged.errors),
                # a file gets no colour codes: only a terminal reads them
                style=None if run.output_file else click.style,
                unsafe_fixes=any(result.unsafe_fixes for result in results),
                linted=printing.redacted(merged.linted),
            )
        # the machine-read formats were given redacted findings: a pass over their text could
        # cut their syntax (a value that is also a key); statistics hold no value from a file
        machine = run.machine and not run.diff
        if run.output_file is None:
            for piece in output:
                show(piece, nl=False, color=_colour(), machine=machine)
            return True
        texts = output if machine else map(printing.report_text, output)
        return _write_report(run.output_file, texts, run.follow_symlinks)


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


def _write_report(path: str, output: Iterable[str], follow_symlinks: bool = False) -> bool:
    """Write the report (its text in pieces) to ``path`` atomically; on failure say why (the
    exit is then 2)."""
    from inertia_kit.description.edits import write_atomic
    from inertia_kit.errors import InputError

    if not _may_write_report(path, follow_symlinks):
        return False
    try:
        # a file name that is no UTF-8 (github's file=) is written as its own bytes, as stdout does
        data = (piece.encode("utf-8", "surrogateescape") for piece in output)
        write_atomic(path, data, create=True, follow_symlinks=follow_symlinks)
    except InputError as error:
        say(f"error: --output-file: {error}")
        return False
    return True


def _echo_summary(run: LintRun, merged: Merged, results: list[FileResult]) -> None:
    """The summary line on stderr (``Found ...``, ``No findings ...``)."""
    from inertia_kit.errors import InternalError
    from inertia_kit.lint.output.summary import summary

    crashes = sum(isinstance(error, InternalError) for error in merged.errors)
    unsafe = any(result.unsafe_fixes for result in results)
    tally = merged.tally
    fixable = 0 if run.diff else tally.fixable_unsafe if unsafe else tally.fixable
    click.echo(
        summary(
            tally,
            merged.checked,
            len(merged.errors) - crashes,
            crashes,
            flagged=merged.flagged,
            fixed=merged.fixed,
            fixable=fixable,
            hidden=0 if run.diff else tally.hidden,
        ),
        err=True,
    )
