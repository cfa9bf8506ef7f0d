"""
Linting files and folders as the command line does: each file with its configuration, fixes
applied (``--fix``) or shown (``--diff``), and a given xacro fragment linted through the robots
that include it (:mod:`.fragments`), suppression comments in shared files judged over all of
them (:mod:`.unused`).
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Generator, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from inertia_kit.analysis.geometry import MeshLoader
from inertia_kit.description.xacro_limits import XacroLimits
from inertia_kit.fixes.masses import MassChoice
from inertia_kit.lint import catalog
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.runner import (
    DEFAULT_FAIL_ON,
    FileResult,
    Selection,
    checked_selectors,
    file_settings,
    lint_file,
)

if TYPE_CHECKING:
    from inertia_kit.lint.config_files import ConfigFinder


def lint_paths(paths: Iterable[str | Path], **options: Any) -> list[FileResult]:
    """
    Lint files and folders as the command line does: the results of :func:`linting` (the same
    ``options``), once every file is linted.
    """
    with linting(paths, **options) as run:
        for _ in run:
            pass
    return run.results


def linting(
    paths: Iterable[str | Path],
    *,
    config: str | Path | ConfigFinder | None = None,
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
    follow_symlinks: bool = False,
    place_fixes: bool = True,
    release: bool = False,
) -> Linting:
    """
    Lint files and folders as the command line does: each file with its configuration (the
    nearest, or ``config``: a file, or a ``ConfigFinder`` already made), ``select``/``ignore``
    on top, ``fail_on`` over the configured one, ``engines`` (names, comma-separated or
    ``all``; ``None``: the configured ones) instead of the configured ones, ``xacro_limits``
    (``--xacro-limit``) over the configured ones and the environment's. The files are linted
    as the returned :class:`Linting` is iterated, each told as soon as it and every file before
    it are (:class:`Step`); its ``results`` are final once it is over.

    A given xacro file that robots of its repository include is also linted through them (each
    robot with its own configuration), keeping their findings located in the given files
    (:mod:`~inertia_kit.lint.fragments`); such a file that is a fragment, unreadable on its
    own, or without links and joints, gives no result of its own but a note.

    Every configuration is read before any file is linted, here: raises ``ConfigError`` for a
    bad configuration, a ``select``/``ignore`` entry that names no rule or an unknown engine.
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

    ``place_fixes`` false: the findings' fixes carry their values, safety and title but no
    edits (``[*]`` and "N fixable" need no more; placing the edits is most of a small robot's
    cost), unless ``fix`` or ``diff`` apply or show them.

    ``jobs`` (``-j``): how many processes lint (``None`` or 0: the usable cores, when there
    are several files); ``--fix`` always lints in this process (:func:`_workers` says why).

    ``release``: the caller tells each step's settled findings as it gets them (a report
    streamed to its writer); once told, they leave the results, counted in
    :attr:`Linting.told` and in each result's ``told``, so that the run's memory does not grow
    with its findings.
    """
    from inertia_kit.lint.config_files import ConfigFinder

    select, ignore, engines = checked_selectors(select, ignore, engines)
    finder = config if isinstance(config, ConfigFinder) else ConfigFinder(config)
    if discovery is not None and discovery.config is None:
        discovery.config = finder  # one configuration read for the walk and the linting

    def walked(files: list[str]) -> None:
        if _parallel_likely(len(files), jobs, fix, diff, load_mesh):
            from inertia_kit.lint import parallel

            parallel.start_early()  # it imports the linter while repositories are scanned

    chosen = _targets(paths, xacro_args, package_paths, xacro_limits, discovery, walked)
    # one selection, limits and mass choice per configuration, shared by its files: a run
    # over many files holds one task each
    settings: dict[Any, tuple[Selection, XacroLimits, MassChoice]] = {}
    tasks = []
    for target in chosen.targets:
        found = finder.for_file(target.robot)
        unsafe = bool(found.unsafe_fixes if unsafe_fixes is None else unsafe_fixes)
        if found.path not in settings:
            settings[found.path] = file_settings(found, select, ignore, engines, xacro_limits)
        selection, limits, choice = settings[found.path]
        tasks.append(
            _Task(
                target,
                selection,
                xacro_args,
                tuple(package_paths),
                load_mesh,
                limits,
                choice,
                unsafe,
                diff or bool(found.fix if fix is None else fix),
                diff,
                # not `or`: Severity.INFO is 0
                next(s for s in (fail_on, found.fail_on, DEFAULT_FAIL_ON) if s is not None),
                follow_symlinks,
                place_fixes,
            )
        )
    return Linting(tasks, chosen, _workers(tasks, jobs), on_error, release)


@dataclass(frozen=True)
class Linted:
    """
    One file linted, told in input order as soon as it and every file before it are:
    ``settled`` its findings that no other file's result can still change (:func:`settled`),
    which may be printed at once; the others are only final in :attr:`Linting.results`.
    """

    result: FileResult
    settled: list[Finding]


@dataclass(frozen=True)
class Step:
    """
    One more file linted (in any order): ``ready`` the files now linted together with every
    file before them, in input order (none, one or several); ``done`` of ``total`` files
    linted, ``current`` the first in input order not linted yet (``None`` once all are).
    """

    ready: tuple[Linted, ...]
    done: int
    total: int
    current: str | None


class Linting:
    """
    A run of :func:`linting`: iterating it lints the files, a :class:`Step` each time one more
    is linted; :attr:`results` holds the final results once it is over (suppression comments
    in shared files judged over all their robots, given fragments told through their robots).
    Use it in a ``with`` block: leaving the block early ends the worker processes.
    With ``release``, the settled findings of each step leave the results once the step is
    consumed: :attr:`told` counts them.
    """

    def __init__(
        self,
        tasks: list[_Task],
        chosen: Any,
        workers: int,
        on_error: Callable[[Path, Exception], FileResult] | None,
        release: bool = False,
    ):
        from inertia_kit.lint.merge import Tally

        self.tasks, self.chosen, self.workers, self.on_error = tasks, chosen, workers, on_error
        self.release = release
        self.told = Tally()  # the findings released (told by the caller), counted
        self._results: list[FileResult] | None = None
        self._steps = self._run()

    @property
    def results(self) -> list[FileResult]:
        """Every file's final result, in input order (``RuntimeError`` before the end)."""
        if self._results is None:
            raise RuntimeError("the files are not all linted yet: iterate the run to its end")
        return self._results

    def __iter__(self) -> Iterator[Step]:
        return self._steps

    def __enter__(self) -> Linting:
        return self

    def __exit__(self, *exception: object) -> None:
        self._steps.close()

    def _failed(self, task: _Task, error: BaseException) -> FileResult:
        if self.on_error is None or not isinstance(error, Exception):
            raise error
        result = self.on_error(Path(task.target.robot), error)
        result.fail_on = task.fail_on
        return result

    def _release(self, linted: Linted) -> None:
        """A file's settled findings, told by the caller, out of its result (counted), and
        with them what only the telling needed."""
        result = linted.result
        result.environment_values, result.reads = (), {}
        if not linted.settled:
            return
        self.told.add(linted.settled, result.unsafe_fixes)
        told = {id(finding) for finding in linted.settled}
        result.told += len(told)
        result.told_failing |= any(f.severity >= result.fail_on for f in linted.settled)
        result.findings = [f for f in result.findings if id(f) not in told]

    def _run(self) -> Generator[Step, None, None]:
        from inertia_kit.lint import parallel, unused

        tasks, chosen = self.tasks, self.chosen
        results: list[FileResult] = []
        steps = parallel.in_order(_lint_task, tasks, self.workers, failed=self._failed)
        with contextlib.closing(steps):
            for step in steps:
                ready = []
                for index, result in step.ready:
                    results.append(result)
                    ready.append(Linted(result, settled(result, tasks[index].target, chosen)))
                current = tasks[step.first].target.robot if step.first < len(tasks) else None
                yield Step(tuple(ready), step.done, len(tasks), current)
                if self.release:
                    for linted in ready:
                        self._release(linted)
        unused.judge_shared(results)
        self._results = _through_robots(results, chosen)


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
    place_fixes: bool = True


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
            place_fixes=task.place_fixes or task.fixing or task.diff,
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


def _workers(tasks: list[_Task], jobs: int | None) -> int:
    """
    How many processes lint ``tasks``. ``--fix`` runs here, one file after the other: robots
    that include the same fragment write it, and each fix pass lints the file as the previous
    pass left it, so two processes would fix a shared fragment from stale text. ``--diff``
    writes nothing and runs in parallel. A loader of meshes that cannot be sent to a worker
    (the API's ``load_mesh``) also keeps the work here.
    """
    from inertia_kit.lint import parallel

    serial = any(task.fixing and not task.diff for task in tasks) or not _picklable(tasks)
    return 1 if serial else parallel.worker_count(jobs, len(tasks))


def _parallel_likely(
    files: int, jobs: int | None, fix: bool | None, diff: bool, load_mesh: Any
) -> bool:
    """Whether a run over ``files`` files will most likely lint in worker processes
    (:func:`_workers` decides): several files, more than one core asked for, no ``--fix`` asked, no
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
    reals = {str(result.path): own}  # a file's findings name it by one path: resolved once

    def is_own(path: str) -> bool:
        if path not in reals:
            reals[path] = real(path)
        return reals[path] == own

    shared_comments = any(not is_own(path) for path, _ in (result.uses or {}))
    scoped = {rule.CODE for rule in catalog.RULES if rule.SCOPE == SCOPE}
    return [
        finding
        for finding in result.findings
        if finding.path
        and is_own(finding.path)
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
