"""
``inertia-kit scan``: lint an asset library (10³–10⁵ robot files) into a JSON Lines record, one
line per asset, written as soon as that asset is done, so that a run killed at any moment
resumes where it stopped (:mod:`.scan_record`), each asset under a time and a memory limit in
a worker process of its own (:mod:`.scan_pool`), and summarised from the record at the end
(:mod:`.scan_summary`).

Each asset is linted as ``inertia-lint`` lints a file given alone (:func:`lint_asset`): its
configuration, ``--select``/``--ignore``/``--engine`` on top; unlike ``inertia-lint``, a xacro
file is not also linted through the robots of its repository that include it (an asset library
holds robots, and that search reads the whole repository).
"""

from __future__ import annotations

import functools
import hashlib
import os
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from inertia_kit.fixes.masses import MassChoice
from inertia_kit.lint.runner import Selection, checked_selectors, file_settings
from inertia_kit.lint.scan_pool import Limits, Outcome, run_limited
from inertia_kit.reading import open_regular

if TYPE_CHECKING:
    from inertia_kit.description import model
    from inertia_kit.description.xacro_limits import XacroLimits
    from inertia_kit.lint.config_files import ConfigFinder
    from inertia_kit.lint.discovery import Discovery

#: the statuses of an asset: linted (``ok``, ``findings``), or not (the others)
STATUSES = ("ok", "findings", "unreadable", "timeout", "memory", "crashed")
#: the fields of a line that differ from run to run for the same asset
MEASURED = ("wall_seconds", "cpu_seconds", "peak_memory_mb")


@dataclass(frozen=True)
class Asset:
    """A robot file to scan: its ``path`` as given or found, and the top-level ``folder`` it
    is counted under (the first path component under the folder given)."""

    path: str
    folder: str


def walked(paths: Iterable[str | Path], discovery: Discovery | None = None) -> list[Asset]:
    """
    The assets of ``paths``: folders walked as ``inertia-lint`` walks them
    (:func:`~inertia_kit.lint.discovery.expand_paths`), each asset counted under the first
    component of its path in the folder; files given are counted under their own folder.
    """
    from inertia_kit.lint.discovery import expand_paths

    found = []
    for given in paths:
        for file in expand_paths([given], discovery):
            found.append(Asset(str(file), _folder(file, given)))
    return _once(found)


def listed(lines: Iterable[str]) -> list[Asset]:
    """The assets of ``--list``: a path a line (blank lines skipped), counted under the first
    component of the path below the folder all of them share."""
    paths = [line.rstrip("\r\n") for line in lines]
    paths = [path for path in paths if path.strip()]
    if not paths:
        return []
    try:
        root = os.path.commonpath([os.path.dirname(os.path.abspath(p)) for p in paths])
    except ValueError:  # paths on different drives
        root = ""
    return _once([Asset(path, _folder(Path(path), root)) for path in paths])


def _folder(file: Path, root: str | Path) -> str:
    try:
        parts = Path(os.path.abspath(file)).relative_to(os.path.abspath(root)).parts
    except ValueError:
        parts = ()
    return parts[0] if len(parts) > 1 else os.path.basename(os.path.dirname(os.path.abspath(file)))


def _once(assets: list[Asset]) -> list[Asset]:
    return list({asset.path: asset for asset in reversed(assets)}.values())[::-1]


@dataclass(frozen=True)
class ScanOptions:
    """
    How each asset is linted (the options of :func:`~inertia_kit.lint.paths.linting`: each
    file's configuration from ``config``, ``select``/``ignore``/``engines`` on top)
    and held: ``limits`` per asset, ``jobs`` worker processes; on the Dask scheduler at
    ``dask`` (``local``: a local cluster of ``jobs`` workers) instead, when given
    (:mod:`.scan_dask`). ``mesh_cache``: the cache folder the workers use (else their own
    default); ``no_mesh_cache``: none.
    """

    config: ConfigFinder | None = None
    select: Sequence[str] = ()
    ignore: Sequence[str] = ()
    engines: Sequence[str] | None = None
    xacro_args: dict[str, str] = field(default_factory=dict)
    package_paths: tuple[str, ...] = ()
    xacro_limits: Mapping[str, float] | None = None
    limits: Limits = field(default_factory=Limits)
    jobs: int = 1
    dask: str | None = None
    mesh_cache: str | None = None
    no_mesh_cache: bool = False


@dataclass(frozen=True)
class AssetTask:
    """One asset to lint in a worker (small, picklable)."""

    path: str
    selection: Selection
    xacro_args: dict[str, str]
    package_paths: tuple[str, ...]
    xacro_limits: XacroLimits
    mass_choice: MassChoice
    #: set in the worker's environment before the lint (the cache folder, or none)
    environment: tuple[tuple[str, str], ...] = ()


@dataclass(frozen=True)
class Step:
    """One more asset recorded: ``done`` of ``total`` (those recorded before included),
    ``current`` the asset just recorded."""

    done: int
    total: int
    current: str


def scanning(assets: Sequence[Asset], out: str | Path, options: ScanOptions) -> Iterator[Step]:
    """
    Scan ``assets`` into the JSON Lines file ``out``, each asset's line appended as soon as it
    is done; the assets ``out`` already records (same path, same content) are skipped
    (:meth:`~inertia_kit.lint.scan_record.Record.resume`). A :class:`Step` per asset
    recorded. Raises ``ConfigError`` for a bad configuration, before anything is linted;
    ``InputError`` when ``out`` cannot be written or another scan writes it; closing the iteration
    (Ctrl-C) kills the workers and leaves ``out`` ready to resume.
    """
    from inertia_kit.lint.scan_record import Record

    options = _checked(options)  # before the record is touched
    run: Callable[..., Iterator[tuple[int, Outcome]]] = run_limited
    if options.dask is not None:
        from inertia_kit.lint import scan_dask

        scan_dask.require()
        run = functools.partial(scan_dask.run_on_dask, options.dask)
    hashes = {asset.path: file_sha256(asset.path) for asset in assets}
    with Record(out) as record:
        done = record.resume(hashes)
        todo = [asset for asset in assets if asset.path not in done]
        tasks = _tasks(todo, options)
        recorded = len(assets) - len(todo)
        for index, outcome in run(lint_asset, tasks, options.jobs, options.limits):
            asset = todo[index]
            record.write(line(asset, hashes[asset.path], outcome))
            recorded += 1
            yield Step(recorded, len(assets), asset.path)


def _checked(options: ScanOptions) -> ScanOptions:
    """``options`` with ``--select``/``--ignore`` as codes and ``--engine`` as engine names, as
    :func:`~inertia_kit.lint.paths.linting` takes them; ``ConfigError`` for an entry that names
    no rule or engine."""
    import dataclasses

    select, ignore, engines = checked_selectors(options.select, options.ignore, options.engines)
    return dataclasses.replace(options, select=select, ignore=ignore, engines=engines)


def _tasks(assets: Sequence[Asset], options: ScanOptions) -> list[AssetTask]:
    """Each asset's task, its configuration read once per configuration file."""
    from inertia_kit.lint.config_files import ConfigFinder

    finder = options.config or ConfigFinder()
    environment = _environment(options)
    settings: dict[Any, tuple[Selection, XacroLimits, MassChoice]] = {}
    tasks = []
    for asset in assets:
        found = finder.for_file(asset.path)
        if found.path not in settings:
            settings[found.path] = file_settings(
                found, options.select, options.ignore, options.engines, options.xacro_limits
            )
        selection, limits, choice = settings[found.path]
        tasks.append(
            AssetTask(
                asset.path,
                selection,
                options.xacro_args,
                options.package_paths,
                limits,
                choice,
                environment,
            )
        )
    return tasks


def _environment(options: ScanOptions) -> tuple[tuple[str, str], ...]:
    """What the workers set in their environment: the cache folder, or none."""
    if not options.no_mesh_cache and options.mesh_cache is None:
        return ()
    from inertia_kit.physics.mesh_cache import ENV_DIR, ENV_DISABLE

    if options.no_mesh_cache:
        return ((ENV_DISABLE, "1"),)
    return ((ENV_DIR, os.path.abspath(options.mesh_cache)),)


def line(asset: Asset, sha256: str | None, outcome: Outcome) -> dict[str, Any]:
    """The JSON line of ``asset``: what its worker gave, or how it ended without a result."""
    linted = outcome.value if outcome.status == "done" else {}
    status = linted.get("status", outcome.status)
    return {
        "path": asset.path,
        "folder": asset.folder,
        "sha256": sha256,
        "status": status,
        "error": linted.get("error", outcome.message or None),
        "findings": linted.get("findings", []),
        "links": linted.get("links", []),
        "files": linted.get("files", {}),
        "notes": linted.get("notes", []),
        "wall_seconds": round(outcome.wall, 6),
        "cpu_seconds": None if outcome.cpu is None else round(outcome.cpu, 6),
        "peak_memory_mb": None if outcome.peak_mb is None else round(outcome.peak_mb, 3),
    }


# --- in the worker ------------------------------------------------------------------------


def lint_asset(task: AssetTask) -> dict[str, Any]:
    """
    Lint one asset as ``inertia-lint --output-format json`` does (in a worker): its status,
    its findings as that format gives each, per link the mass properties declared, and the
    sha256 of every file its load read and of its meshes.
    """
    from inertia_kit.lint.output.common import finite
    from inertia_kit.lint.runner import lint_file

    os.environ.update(task.environment)
    robots: list[model.Robot] = []  # the model the lint loaded, for the declared values
    result = lint_file(
        task.path,
        task.selection,
        xacro_args=task.xacro_args,
        package_paths=task.package_paths,
        xacro_limits=task.xacro_limits,
        mass_choice=task.mass_choice,
        fixes="all",
        place_fixes=True,  # as the json format: each fix's edits
        loaded=robots.append,
    )
    if result.error is not None:
        return {"status": "unreadable", "error": str(result.error), "files": _hashes(result.reads)}
    robot = None if result.fragment or result.disabled or not robots else robots[0]
    notes = list(result.notes)
    notes += ["a xacro fragment: nothing to lint on its own"] if result.fragment else []
    notes += ["inertia-lint: disable-file"] if result.disabled else []
    meshes = [] if robot is None else _mesh_files(robot)
    return {
        "status": "findings" if result.findings else "ok",
        "findings": [finite(finding.to_json()) for finding in result.findings],
        "links": [] if robot is None else declared_links(robot),
        "files": _hashes([*result.reads, *meshes]),
        "notes": notes,
    }


def declared_links(robot: model.Robot) -> list[dict[str, Any]]:
    """Per link, in document order, the mass properties its file declares (the link frame,
    SI units; ``null`` where absent, incomplete or not a number) and where."""
    from inertia_kit.analysis.declared import declared
    from inertia_kit.lint.output.common import finite

    rows = []
    for link in robot.links:
        values = declared(link)
        rows.append(
            finite(
                {
                    "link": link.name,
                    "inertial": "none" if link.inertial is None else "declared",
                    "mass": None if values is None else values.mass,
                    "com": None if values is None else values.com.tolist(),
                    "inertia": None if values is None else values.inertia.tolist(),
                    "file": link.source.path,
                    "line": link.source.line,
                }
            )
        )
    return rows


def _mesh_files(robot: model.Robot) -> list[str]:
    from inertia_kit.description import model

    return [
        shape.geometry.path
        for link in robot.links
        for shape in (*link.collisions, *link.visuals)
        if isinstance(shape.geometry, model.Mesh) and shape.geometry.path is not None
    ]


def _hashes(paths: Iterable[str]) -> dict[str, str | None]:
    """Real path → sha256 of every file, each once (``null``: no longer readable)."""
    return {real: file_sha256(real) for real in dict.fromkeys(map(os.path.realpath, paths))}


def file_sha256(path: str | Path) -> str | None:
    """The sha256 of a file's bytes, read in blocks; ``None`` when it cannot be read."""
    digest = hashlib.sha256()
    try:
        with open_regular(path) as file:  # a pipe in --list is an unreadable asset
            while block := file.read(1 << 20):
                digest.update(block)
    except (OSError, ValueError):  # ValueError: a path no file can have (a NUL in it)
        return None
    return digest.hexdigest()
