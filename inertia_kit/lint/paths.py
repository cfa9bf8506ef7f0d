"""
Linting files and folders as the command line does: each file with its configuration, fixes
applied (``--fix``) or shown (``--diff``), and a given xacro fragment linted through the robots
that include it (:mod:`.fragments`), suppression comments in shared files judged over all of
them (:mod:`.unused`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from inertia_kit.analysis.geometry import MeshLoader
from inertia_kit.description.xacro_limits import XacroLimits
from inertia_kit.fixes.masses import DEFAULT_DENSITY, MassChoice
from inertia_kit.lint import catalog
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.runner import (
    DEFAULT_FAIL_ON,
    FileResult,
    Selection,
    lint_file,
    selection_for,
)


def lint_paths(
    paths: Iterable[str | Path],
    *,
    config: str | Path | None = None,
    select: Sequence[str] = (),
    ignore: Sequence[str] = (),
    fail_on: Severity | None = None,
    xacro_args: dict[str, str] | None = None,
    package_paths: Sequence[str | Path] = (),
    load_mesh: MeshLoader | None = None,
    engines: Sequence[str] | None = None,
    xacro_limits: Mapping[str, float] | None = None,
    on_error: Callable[[Path, Exception], FileResult] | None = None,
    fix: bool | None = None,
    unsafe_fixes: bool | None = None,
    diff: bool = False,
    discovery: Any = None,
    jobs: int | None = 1,
    told: Callable[[FileResult, list[Finding]], None] | None = None,
    progress: Callable[[int, int, str | None], None] | None = None,
    follow_symlinks: bool = False,
) -> list[FileResult]:
    """
    Lint files and folders as the command line does: each file with its configuration (the
    nearest, or ``config``), ``select``/``ignore`` on top, ``fail_on`` over the configured one,
    ``engines`` (names, comma-separated or ``all``; ``None``: the configured ones) instead of
    the configured ones, ``xacro_limits`` (``--xacro-limit``) over the configured ones and the
    environment's.

    A given xacro file that robots of its repository include is also linted through them (each
    robot with its own configuration), keeping their findings located in the given files
    (:mod:`~inertia_kit.lint.fragments`); such a file that is a fragment, unreadable on its
    own, or without links and joints, gives no result of its own but a note.

    Every configuration is read before any file is linted. Raises ``ConfigError`` for a bad
    configuration, a ``select``/``ignore`` entry that names no rule or an unknown engine.
    ``on_error(file, exception)`` gives the result of a file whose linting raised an exception
    (a bug: the command line reports it for that file and lints the others); without it, the
    exception propagates.

    ``fix`` (``--fix``; ``None``: the configured ``fix``) applies the fixes
    (:mod:`~inertia_kit.lint.applying`), safe ones, and unsafe ones with ``unsafe_fixes``
    (``None``: the configured ``unsafe-fixes``); ``diff`` computes them without writing.
    ``discovery`` (a :class:`~inertia_kit.lint.discovery.Discovery`; default: as configured)
    says what the folder walk leaves out. A file to fix that is a symbolic link out of its
    repository is not written (an error for it), unless ``follow_symlinks``
    (:mod:`~inertia_kit.lint.repository_links`).

    ``jobs`` (``-j``): how many processes lint (``None`` or 0: the usable cores, when there
    are several files); ``--fix`` always lints in this process (:func:`_run` says why).
    ``told(result, settled)`` is called, in input order, as soon as a file and every file
    before it are linted: ``settled`` its findings that no other file's result can still change
    (:func:`settled`), the others are only final in the returned results.
    ``progress(done, total, current)`` is called as files are done (``current``: the first
    file in input order not done yet).
    """
    from inertia_kit.errors import ConfigError
    from inertia_kit.lint import unused
    from inertia_kit.lint.config_files import ConfigFinder

    known = catalog.names()

    def checked(option: str, values: Sequence[str]) -> tuple[str, ...]:
        selectors = tuple(catalog.normalize_selector(value, known) for value in values)
        for value, selector in zip(values, selectors, strict=True):
            if selector is None:
                raise ConfigError(f"{option}: {catalog.selector_error(value, known)}")
        return selectors  # type: ignore[return-value]

    select, ignore = checked("--select", select), checked("--ignore", ignore)
    if engines is not None:
        from inertia_kit.engines.vocabulary import parse_engines

        try:
            engines = parse_engines(engines)
        except ValueError as error:
            raise ConfigError(f"--engine: {error}") from None
    finder = ConfigFinder(config)
    if discovery is not None and discovery.config is None:
        discovery.config = finder  # one configuration read for the walk and the linting

    def walked(files: list[str]) -> None:
        if _parallel_likely(len(files), jobs, fix, diff, load_mesh):
            from inertia_kit.lint import parallel

            parallel.start_early()  # it imports the linter while repositories are scanned

    chosen = _targets(paths, xacro_args, package_paths, xacro_limits, discovery, walked)
    plan = [(target, finder.for_file(target.robot)) for target in chosen.targets]
    limits = {found.path: XacroLimits.resolve(found.xacro, xacro_limits) for _, found in plan}
    tasks = []
    for target, found in plan:
        unsafe = bool(found.unsafe_fixes if unsafe_fixes is None else unsafe_fixes)
        choice = MassChoice.checked(
            DEFAULT_DENSITY,
            {n: v.mass for n, v in found.links.items() if v.mass is not None},
            {n: v.density for n, v in found.links.items() if v.density is not None},
        )
        tasks.append(
            _Task(
                target,
                selection_for(found, select, ignore, engines),
                xacro_args,
                tuple(package_paths),
                load_mesh,
                limits[found.path],
                choice,
                unsafe,
                diff or bool(found.fix if fix is None else fix),
                diff,
                # not `or`: Severity.INFO is 0
                next(s for s in (fail_on, found.fail_on, DEFAULT_FAIL_ON) if s is not None),
                follow_symlinks,
            )
        )
    results = _run(tasks, chosen, jobs, on_error, told, progress)
    unused.judge_shared(results)
    return _through_robots(results, chosen)


@dataclass(frozen=True)
class _Task:
    """One file to lint, with everything a worker process needs (small, picklable)."""

    target: Any  # fragments.Target
    selection: Selection
    xacro_args: dict[str, str] | None
    package_paths: tuple[str | Path, ...]
    load_mesh: MeshLoader | None
    xacro_limits: XacroLimits
    mass_choice: MassChoice
    unsafe: bool
    fixing: bool
    diff: bool
    fail_on: Severity
    follow_symlinks: bool = False


def _lint_task(task: _Task) -> FileResult:
    """Lint one file as :func:`lint_paths` does (in this process or a worker)."""
    target = task.target

    def once() -> FileResult:
        result = lint_file(
            target.robot,
            task.selection,
            xacro_args=task.xacro_args,
            package_paths=task.package_paths,
            load_mesh=task.load_mesh,
            xacro_limits=task.xacro_limits,
            mass_choice=task.mass_choice,
            fixes="safe" if task.fixing and not task.unsafe else "all",
        )
        if target.changed:  # a given fragment: only what lands in it is fixed and told
            from inertia_kit.lint.fragments import located

            result.findings = located(result.findings, target.robot, target.changed)
        return result

    if task.fixing:
        from inertia_kit.lint.applying import fix_file
        from inertia_kit.lint.repository_links import refuse_links_out

        def check(paths: Sequence[str]) -> None:
            refuse_links_out(paths, task.follow_symlinks)

        outcome = fix_file(once, task.unsafe, write=not task.diff, check=check)
        result = outcome.result
        result.fixed, result.diff = outcome.fixed, outcome.diff
    else:
        result = once()
    result.unsafe_fixes = task.unsafe
    result.fail_on = task.fail_on
    return result


def _run(
    tasks: list[_Task],
    chosen: Any,
    jobs: int | None,
    on_error: Callable[[Path, Exception], FileResult] | None,
    told: Callable[[FileResult, list[Finding]], None] | None,
    progress: Callable[[int, int, str | None], None] | None,
) -> list[FileResult]:
    """
    Every task's result, in ``jobs`` processes. ``--fix`` runs here, one file after the
    other: robots that include the same fragment write it, and each fix pass lints the file
    as the previous pass left it, so two processes would fix a shared fragment from stale
    text. ``--diff`` writes nothing and runs in parallel. A loader of meshes that cannot be
    sent to a worker (the API's ``load_mesh``) also keeps the work here.
    """
    from inertia_kit.lint import parallel

    def failed(task: _Task, error: BaseException) -> FileResult:
        if on_error is None or not isinstance(error, Exception):
            raise error
        result = on_error(Path(task.target.robot), error)
        result.fail_on = task.fail_on
        return result

    def tell(index: int, result: FileResult) -> None:
        if told is not None:
            told(result, settled(result, tasks[index].target, chosen))

    def done(count: int, first: int) -> None:
        if progress is not None:
            current = tasks[first].target.robot if first < len(tasks) else None
            progress(count, len(tasks), current)

    serial = any(task.fixing and not task.diff for task in tasks) or not _picklable(tasks)
    workers = 1 if serial else parallel.worker_count(jobs, len(tasks))
    return parallel.run_ordered(_lint_task, tasks, workers, failed=failed, told=tell, done=done)


def _parallel_likely(
    files: int, jobs: int | None, fix: bool | None, diff: bool, load_mesh: Any
) -> bool:
    """Whether a run over ``files`` files will most likely lint in worker processes
    (:func:`_run` decides): several files, more than one core asked for, no ``--fix`` asked, no
    loader of meshes given (the API's, which may not reach a worker)."""
    from inertia_kit.lint import parallel

    if (fix and not diff) or load_mesh is not None:
        return False
    return parallel.worker_count(jobs, files) > 1


def _picklable(tasks: list[_Task]) -> bool:
    import pickle

    try:
        pickle.dumps(tasks[:1])
    except Exception:
        return False
    return True


def settled(result: FileResult, target: Any, chosen: Any) -> list[Finding]:
    """
    The findings of ``result`` that no other file's result can change, so they can be printed
    at once: those in the linted file itself, when no given robot reads that file (it is no
    fragment of theirs), less the suppression rule's (IN090) when the file's comments shared
    with other files are judged over all of them. Findings of a file linted for a given
    fragment (``via`` a robot) wait: another robot may find the same, and both are named.
    """
    from inertia_kit.lint.include_graph import real
    from inertia_kit.lint.unused import SCOPE

    if target.changed or result.error is not None or not result.findings:
        return []
    own = real(result.path)
    if own in chosen.fragments:
        return []
    shared_comments = any(real(path) != own for path, _ in (result.uses or {}))
    scoped = {rule.CODE for rule in catalog.RULES if rule.SCOPE == SCOPE}
    return [
        finding
        for finding in result.findings
        if finding.path
        and real(finding.path) == own
        and not (shared_comments and finding.code in scoped)
    ]


def _targets(
    paths: Iterable[str | Path],
    xacro_args: Mapping[str, str] | None,
    package_paths: Sequence[str | Path],
    xacro_limits: Mapping[str, float] | None,
    discovery: Any = None,
    found: Callable[[list[str]], None] | None = None,
) -> Any:
    """The files to lint for ``paths``: :func:`~inertia_kit.lint.fragments.targets`."""
    from inertia_kit.lint.fragments import targets

    return targets(
        paths,
        xacro_args=xacro_args,
        package_paths=package_paths,
        xacro_limits=XacroLimits.resolve(None, xacro_limits),
        discovery=discovery,
        found=found,
    )


def _through_robots(results: list[FileResult], chosen: Any) -> list[FileResult]:
    """
    The results with the given files robots include linted through them: a robot's findings
    kept where they land in those files (saying `via` which robot), the given file's own
    result dropped when it is a fragment, unreadable on its own, or has no link and no joint (a
    placeholder; its robots read it), and a note for each given file, saying which robots were
    linted for it or that none includes it.
    """
    from inertia_kit.lint.fragments import located

    kept = []
    for result, target in zip(results, chosen.targets, strict=True):
        if target.changed:
            result.findings = located(result.findings, target.robot, target.changed)
        elif chosen.read_by_robots(target) and (result.fragment or result.error or result.empty):
            result = FileResult(result.path, fragment=True, fail_on=result.fail_on)
        if not target.changed:
            note = chosen.note(result.path, result.fragment)
            result.remarks.extend([f"{result.path}: {note}"] if note else [])
        kept.append(result)
    return kept
