"""
``inertia-kit scan``: lint an asset library into a JSON Lines record, resumable, each asset
under a time and a memory limit; a summary and a keep-list at the end
(:mod:`inertia_kit.lint.scan`).
"""

from __future__ import annotations

import os
import sys
import time
from typing import Any

import click

from inertia_kit.cli.discovery import discovery_options
from inertia_kit.cli.guard import GuardedCommand
from inertia_kit.cli.options import (
    HELP,
    UsageError,
    jobs_option,
    package_path_option,
    parse_codes,
    parse_xacro_args,
    parse_xacro_limits,
    xacro_arg_option,
    xacro_limit_option,
)
from inertia_kit.cli.printing import say


@click.command("scan", cls=GuardedCommand, context_settings=HELP)
@click.argument("paths", nargs=-1, type=click.Path())
@click.option(
    "--list",
    "list_file",
    type=click.Path(dir_okay=False, allow_dash=True),
    default=None,
    help="A file of asset paths, one a line (`-`: stdin), scanned after the PATHS.",
)
@click.option(
    "-o",
    "--output",
    required=True,
    type=click.Path(dir_okay=False),
    help="The JSON Lines record, one line per asset; an existing one is resumed: the assets it "
    "records with their current content are skipped.",
)
@click.option(
    "--timeout",
    type=click.FloatRange(min=0),
    callback=lambda ctx, param, value: _finite(value),
    default=60.0,
    show_default=True,
    metavar="SECONDS",
    help="Wall-clock time per asset; past it the asset is recorded `timeout` (0: none).",
)
@click.option(
    "--max-memory",
    type=click.IntRange(min=0),
    default=2048,
    show_default=True,
    metavar="MB",
    help="Memory an asset may allocate; past it the asset is recorded `memory` (0: none).",
)
@jobs_option("Worker processes [default: the usable cores]; with --dask local: Dask workers.")
@click.option(
    "--dask",
    metavar="ADDRESS",
    default=None,
    help="Lint on the Dask cluster whose scheduler is at ADDRESS (tcp://HOST:8786), or on a "
    "local one of -j workers (`local`); the record is written here. Needs the dask extra.",
)
@click.option(
    "--mesh-cache",
    type=click.Path(file_okay=False),
    default=None,
    metavar="DIR",
    help="The cache folder the workers use (with --dask: one every worker sees) "
    "[default: each worker's own].",
)
@click.option("--no-mesh-cache", is_flag=True, help="The workers use no cache.")
@click.option(
    "--summary",
    "summary_file",
    type=click.Path(dir_okay=False),
    default=None,
    help="Also write the summary as JSON to this file.",
)
@click.option(
    "--keep",
    "keep_file",
    type=click.Path(dir_okay=False),
    default=None,
    help="Write the paths of the assets to keep (linted, worst finding at most --keep-at), "
    "one a line.",
)
@click.option(
    "--keep-at",
    type=click.Choice(["none", "info", "warning", "error"]),
    default="warning",
    show_default=True,
    help="The worst finding a kept asset may have (none: no findings).",
)
@click.option(
    "--fail-on",
    type=click.Choice(["error", "warning", "info"]),
    default="error",
    show_default=True,
    help="Lowest severity that makes the exit code 1 (an asset not linted counts as error).",
)
@click.option("-q", "--quiet", is_flag=True, help="No progress bar and no summary on stderr.")
@click.option("--select", multiple=True, metavar="CODES", help="Rules to run, as inertia-lint.")
@click.option("--ignore", multiple=True, metavar="CODES", help="Rules not to run, as inertia-lint.")
@click.option(
    "--engine", "engines", multiple=True, metavar="NAMES", help="Engine rules, as inertia-lint."
)
@click.option(
    "--config",
    "config_path",
    type=click.Path(dir_okay=False),
    default=None,
    help="Configuration file for every asset instead of the nearest one.",
)
@package_path_option
@xacro_arg_option
@xacro_limit_option
@discovery_options
@click.pass_context
def scan_command(ctx: click.Context, paths: tuple[str, ...], **options: Any) -> None:
    """
    Lint an asset library (files and folders, walked as inertia-lint walks them, or --list)
    into a JSON Lines record: one line per asset, written as soon as it is done, with its
    status, findings, declared mass properties, times, peak memory and sha256 hashes.
    Re-running with the same -o resumes. Each asset runs in a worker process under --timeout
    and --max-memory, locally or on a Dask cluster (--dask). A summary follows on stderr.

    \b
    Exit codes: 0 no finding at or above --fail-on; 1 findings (or assets not linted); 2
    usage, an unreadable --list or an unwritable record; 130 Ctrl-C (the record resumes).
    \b
    Examples:
      inertia-kit scan -o scan.jsonl assets/
      inertia-kit scan --list assets.txt -o scan.jsonl -j 8 --timeout 30 --keep keep.txt
      inertia-kit scan --dask tcp://scheduler:8786 -o scan.jsonl /shared/assets
    """
    ctx.exit(scan(paths, options))


def scan(paths: tuple[str, ...], options: dict[str, Any]) -> int:
    """The scan the options ask for; its exit code."""
    from inertia_kit.cli.discovery import show_files
    from inertia_kit.cli.progress import Progress
    from inertia_kit.errors import ConfigError, InputError
    from inertia_kit.lint import scan_summary
    from inertia_kit.lint.findings import Severity
    from inertia_kit.lint.scan import scanning, walked
    from inertia_kit.lint.scan_record import lines

    if options["dask"] is not None:
        from inertia_kit.lint import scan_dask  # only now: a local scan imports no Dask

        try:
            scan_dask.require()
        except InputError as error:
            say(f"error: {error}")
            return 2
    scan_options, walk = _scan_options(options)
    written = (options["output"], options["keep_file"], options["summary_file"])
    given = [path for path in written if path is not None]
    problem = _links_on_the_way(given) or _missing_folder(given)
    if problem is not None:  # said before a scan of hours, not after it
        say(f"error: {problem}")
        return 2
    if options["show_files"]:
        return show_files(paths, walk)
    if not paths and options["list_file"] is None:
        raise UsageError("give files or folders to scan, or --list FILE")
    assets = walked(paths, walk) + _listed(options["list_file"])
    if not assets:
        where = ", ".join(paths) or options["list_file"]
        say(f"warning: no robot descriptions (*.urdf, *.xacro, MJCF *.xml) in {where}")
    progress = Progress.for_terminal(options["quiet"], rate=True)
    started = time.monotonic()
    fresh = 0
    try:
        for step in scanning(assets, options["output"], scan_options):
            if fresh == 0:
                progress.done_before = step.done - 1
            fresh += 1
            progress.update(step.done, step.total, step.current)
    except (ConfigError, InputError) as error:
        say(f"error: {error}")
        return 2
    finally:
        progress.clear()  # also on Ctrl-C
    seconds = time.monotonic() - started
    fail_on = Severity.parse(options["fail_on"])
    summary = scan_summary.summarise(lines(options["output"]), fail_on)
    summary["run"] = {
        "assets": fresh,
        "seconds": round(seconds, 3),
        "assets_per_second": round(fresh / seconds, 3) if seconds > 0 else 0.0,
        "jobs": scan_options.jobs,
    }
    try:
        if options["summary_file"] is not None:
            _write_json(options["summary_file"], summary)
        if options["keep_file"] is not None:
            scan_summary.write_keep_list(
                lines(options["output"]), options["keep_at"], options["keep_file"]
            )
    except InputError as error:  # its folder gone since the start, no room: the record holds
        say(f"error: {error}")
        return 2
    if not options["quiet"]:
        click.echo(scan_summary.render(summary), err=True, nl=False)
    return 1 if summary["failing"] else 0


def _scan_options(options: dict[str, Any]) -> tuple[Any, Any]:
    """What each asset is linted with, and the folder walk."""
    from inertia_kit.cli.discovery import discovery
    from inertia_kit.errors import ConfigError
    from inertia_kit.lint import parallel
    from inertia_kit.lint.config_files import ConfigFinder
    from inertia_kit.lint.scan import ScanOptions
    from inertia_kit.lint.scan_pool import Limits

    if options["mesh_cache"] is not None and options["no_mesh_cache"]:
        raise UsageError("--mesh-cache and --no-mesh-cache: give one")
    try:
        finder = ConfigFinder(options["config_path"])
    except ConfigError as error:
        raise UsageError(str(error)) from None
    scan_options = ScanOptions(
        config=finder,
        select=parse_codes(options["select"]),
        ignore=parse_codes(options["ignore"]),
        engines=tuple(options["engines"]) or None,
        xacro_args=parse_xacro_args(options["xacro_args"]),
        package_paths=tuple(options["package_paths"]),
        xacro_limits=parse_xacro_limits(options["xacro_limits"]),
        limits=Limits(options["timeout"], options["max_memory"]),
        jobs=options["jobs"] or parallel.usable_cores(),
        dask=options["dask"],
        mesh_cache=options["mesh_cache"],
        no_mesh_cache=options["no_mesh_cache"],
    )
    return scan_options, discovery(options, finder)


def _finite(seconds: float) -> float:
    """``--timeout`` as given, unless it is not a number (click's range lets ``nan`` and
    ``inf`` through)."""
    import math

    if not math.isfinite(seconds):
        raise click.BadParameter(f"a number of seconds (0: none), got {seconds}")
    return seconds


def _listed(list_file: str | None) -> list[Any]:
    """The assets of ``--list`` (``-``: stdin); ``UsageError`` when it cannot be read."""
    from inertia_kit.lint.scan import listed

    if list_file is None:
        return []
    if list_file == "-":
        return listed(sys.stdin)
    try:
        with open(list_file, encoding="utf-8", errors="surrogateescape") as file:
            return listed(file)
    except OSError as error:
        raise UsageError(f"--list: {list_file}: {error.strerror}") from None


def _missing_folder(paths: list[str]) -> str | None:
    """Why a file the scan writes cannot be written at all: its folder does not exist."""
    for path in paths:
        folder = os.path.dirname(os.path.abspath(path))
        if not os.path.isdir(folder):
            return f"{path}: cannot write: no folder {folder}"
    return None


def _links_on_the_way(paths: list[str]) -> str | None:
    """Why a file the scan writes may not be written: it is, or passes through, a symbolic
    link (a planted link must not redirect a record, a keep-list or a summary)."""
    from inertia_kit.description.output_paths import link_on_the_way

    for path in paths:
        found = link_on_the_way(path)
        if found is not None:
            link, target, itself = found
            where = "is" if itself else f"passes through {link},"
            return f"{path}: {where} a symbolic link to {target}: not written; give the real path"
    return None


def _write_json(path: str, value: Any) -> None:
    import json

    from inertia_kit.description.edits import write_atomic

    text = json.dumps(value, indent=2, ensure_ascii=False) + "\n"
    write_atomic(path, text.encode("utf-8"), create=True)
