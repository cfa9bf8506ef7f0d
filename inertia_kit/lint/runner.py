"""
The lint engine: load each file, analyse it once, run every enabled rule over its scope, drop
what is suppressed or ignored, and return the findings sorted. No output, no exit codes: the
CLI owns those.

What is reported is decided in three places, in this order: the :class:`Selection` (which rules
run, with which options and severities: from the configuration and the command line), the
configuration's per-file ignores, and the suppression comments in the files (see
:mod:`inertia_kit.lint.suppress`).
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING, Any

from inertia_kit.analysis.geometry import MeshLoader
from inertia_kit.analysis.links import RobotAnalysis, analyse
from inertia_kit.description import model
from inertia_kit.description.xacro_limits import XacroLimits
from inertia_kit.errors import InputError, InternalError
from inertia_kit.fixes.masses import DEFAULT_DENSITY, MassChoice
from inertia_kit.lint import catalog
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.rules import RuleContext

if TYPE_CHECKING:
    from inertia_kit.lint.config import Config, PerFileIgnore

DEFAULT_SELECT = ("IN0",)
DEFAULT_FAIL_ON = Severity.WARNING
# folders expansion never enters: hidden ones (.git, .venv) and Python caches
_SKIPPED_FOLDERS = ("__pycache__",)


@dataclass(frozen=True)
class Selection:
    """
    Which rules run, with what options and severities, and which findings are ignored in which
    files. ``select``/``ignore`` entries are codes (``IN012``), code prefixes (``IN01``,
    ``IN0``) or names (``inertia-too-small``).
    """

    select: tuple[str, ...] = DEFAULT_SELECT
    ignore: tuple[str, ...] = ()
    options: dict[str, dict[str, Any]] = field(default_factory=dict)  # code -> option -> value
    severities: dict[str, Severity] = field(default_factory=dict)  # code -> severity
    per_file_ignores: tuple[PerFileIgnore, ...] = ()
    # engines whose rules (IN07x, modules with an ENGINE) run: they never run by ``select``
    engines: tuple[str, ...] = ()
    # rules whose fixes are offered (configuration's ``fixable``/``unfixable``)
    fixable: tuple[str, ...] = DEFAULT_SELECT
    unfixable: tuple[str, ...] = ()

    def offers_fix(self, finding: Finding) -> bool:
        return catalog.selects(self.fixable, finding.code, finding.name) and not catalog.selects(
            self.unfixable, finding.code, finding.name
        )

    @staticmethod
    def matches(rule: ModuleType, patterns: Iterable[str]) -> bool:
        return catalog.selects(patterns, rule.CODE, rule.NAME)

    def enabled(self, rules: Sequence[ModuleType]) -> list[ModuleType]:
        return [rule for rule in rules if self._runs(rule)]

    def _runs(self, rule: ModuleType) -> bool:
        engine = catalog.engine(rule)
        chosen = engine in self.engines if engine is not None else self.matches(rule, self.select)
        return chosen and not self.matches(rule, self.ignore)

    def ignored(self, finding: Finding, linted: str | Path) -> bool:
        """
        Whether a per-file ignore covers ``finding``: one matching the linted file, the file the
        finding is reported in, or (xacro) the file of the macro body that produced it.
        """
        if not self.per_file_ignores:
            return False
        files = {os.fspath(linted), finding.path, finding.macro_path} - {None, ""}
        return any(
            catalog.selects(entry.codes, finding.code, finding.name) and entry.matches(file)
            for entry in self.per_file_ignores
            for file in files
        )


def selection_for(
    config: Config,
    select: Sequence[str] = (),
    ignore: Sequence[str] = (),
    engines: Sequence[str] | None = None,
) -> Selection:
    """
    The selection for files under ``config``, with the command line's ``--select`` and
    ``--ignore`` on top (as ruff: ``--select`` replaces the configured select and ignore lists;
    ``--ignore`` adds to them). Options, severities and per-file ignores always apply.
    ``engines`` (``--engine``), when given, replaces the configured ``engines``.
    """
    if select:
        chosen, dropped = tuple(select), tuple(ignore)
    else:
        chosen = (DEFAULT_SELECT if config.select is None else config.select) + config.extend_select
        dropped = config.ignore + tuple(ignore)
    return Selection(
        chosen,
        dropped,
        config.options,
        config.severities,
        config.per_file_ignores,
        config.engines if engines is None else tuple(engines),
        DEFAULT_SELECT if config.fixable is None else config.fixable,
        config.unfixable,
    )


def run_rules(
    analysis: RobotAnalysis,
    selection: Selection = Selection(),
    rules: Sequence[ModuleType] | None = None,
) -> list[Finding]:
    """Every finding of the enabled rules on one analysed robot, sorted, duplicates once."""
    findings: dict[tuple, Finding] = {}
    enabled = selection.enabled(catalog.RULES if rules is None else rules)
    # code -> the codes whose findings on the same link it replaces (IN06x explains an IN020)
    supersedes = {rule.CODE: catalog.supersedes(rule) for rule in enabled}
    for rule in enabled:
        options = catalog.option_values(rule, selection.options.get(rule.CODE, {}))
        ctx = RuleContext(rule, options, selection.severities.get(rule.CODE))
        targets: Iterable[Any] = analysis.links if rule.SCOPE == "link" else (analysis,)
        configured = selection.severities.get(rule.CODE)
        for target in targets:
            for finding in rule.check(target, ctx):
                if configured is not None and finding.severity is not configured:
                    # the configured severity always wins (a rule may escalate its own default)
                    finding = dataclasses.replace(finding, severity=configured)
                # Finding compares by place and code only: two messages at one place are two
                findings.setdefault(_order(finding), finding)
    replaced = {
        (code, f.link) for f in findings.values() if f.link for code in supersedes.get(f.code, ())
    }
    kept = [findings[key] for key in sorted(findings)]
    return [f for f in kept if (f.code, f.link) not in replaced]


def _order(finding: Finding) -> tuple:
    return (finding.path, finding.line or 0, finding.column or 0, finding.code, finding.message)


def lint_robot(
    robot: model.Robot,
    selection: Selection = Selection(),
    load_mesh: MeshLoader | None = None,
) -> list[Finding]:
    """The findings of a loaded robot (suppression comments and per-file ignores not applied)."""
    analysis = analyse(robot) if load_mesh is None else analyse(robot, load_mesh)
    return run_rules(analysis, selection)


@dataclass
class FileResult:
    """
    What linting one file gave: its findings, or the error that kept it from being read (or
    an internal error, a bug, in the command line's results), or that it is a xacro fragment
    (nothing to lint on its own). ``notes`` are things to tell the
    user that are not findings (a suppression comment we do not understand); ``fail_on`` is the
    lowest severity that counts for the exit code.
    """

    path: str
    findings: list[Finding] = field(default_factory=list)
    error: InputError | InternalError | None = None
    fragment: bool = False
    notes: list[str] = field(default_factory=list)
    fail_on: Severity = DEFAULT_FAIL_ON
    disabled: bool = False  # by `<!-- inertia-lint: disable-file -->`
    fixed: int = 0  # findings whose fix ``--fix`` applied
    diff: str = ""  # ``--diff``: the unified diff of the fixes
    unsafe_fixes: bool = False  # whether unsafe fixes are applicable here

    @property
    def failing(self) -> list[Finding]:
        return [f for f in self.findings if f.severity >= self.fail_on]


def lint_file(
    path: str | Path,
    selection: Selection = Selection(),
    *,
    xacro_args: dict[str, str] | None = None,
    package_paths: Sequence[str | Path] = (),
    load_mesh: MeshLoader | None = None,
    xacro_limits: XacroLimits | None = None,
    mass_choice: MassChoice | None = None,
    fixes: str = "all",
) -> FileResult:
    """
    Lint one file; an unreadable one gives a result with ``error`` set, not an exception.
    Suppression comments (in the file and every xacro file it includes) and the selection's
    per-file ignores are applied. The findings that remain carry their fixes
    (:mod:`~inertia_kit.lint.fixing`; ``fixes``: ``all``, ``safe`` only, or ``none``), the
    values from the geometry with ``mass_choice`` (default: 1000 kg/m³, declared masses kept).
    """
    from inertia_kit.description.loader import load
    from inertia_kit.lint.suppress import directives, suppressed

    if directives(path).disabled:
        return FileResult(str(path), disabled=True)
    try:
        robot = load(
            path, xacro_args=xacro_args, package_paths=package_paths, xacro_limits=xacro_limits
        )
    except InputError as error:
        return FileResult(str(path), error=error)
    if robot.fragment:
        return FileResult(str(path), fragment=True)
    notes = [
        f"{found.path}{'' if line is None else f':{line}'}: inertia-lint comment ignored: {text}"
        for found in map(directives, robot.files or (str(path),))
        for line, text in found.problems
    ]
    analysis = analyse(robot) if load_mesh is None else analyse(robot, load_mesh)
    findings = [
        finding if finding.path else dataclasses.replace(finding, path=str(path))
        for finding in run_rules(analysis, selection)
    ]
    kept = [
        f if f.wants is None or selection.offers_fix(f) else dataclasses.replace(f, wants=None)
        for f in findings
        if not selection.ignored(f, path) and not suppressed(f)
    ]
    if fixes != "none" and any(f.wants is not None for f in kept):
        kept = _with_fixes(path, analysis, kept, mass_choice or MassChoice(), fixes == "safe")
    return FileResult(str(path), kept, notes=notes)


def _with_fixes(
    path: str | Path,
    analysis: RobotAnalysis,
    findings: list[Finding],
    choice: MassChoice,
    safe_only: bool,
) -> list[Finding]:
    """The findings with their fixes, planned on the text of ``path`` as it is now."""
    from inertia_kit.description.edits import read_source
    from inertia_kit.fixes.files import Files
    from inertia_kit.lint.fixing import attach, plan_fixes

    files = Files.for_input(path)
    try:
        files.add(read_source(path))
    except InputError:
        return findings  # not editable as text (an odd encoding): findings without fixes
    planned = plan_fixes(analysis, findings, choice, files, safe_only=safe_only)
    return attach(findings, planned, files)


def expand_paths(paths: Iterable[str | Path]) -> Iterator[Path]:
    """
    Files as given; folders searched for ``*.urdf``, ``*.xacro`` (``*.urdf.xacro`` too), in
    sorted order, hidden folders (``.git``) not entered. Each file once.
    """
    seen: set[str] = set()
    for entry in paths:
        path = Path(entry)
        found = _robot_files(path) if path.is_dir() else [path]
        for file in found:
            key = os.path.normcase(os.path.abspath(file))
            if key not in seen:
                seen.add(key)
                yield file


def _robot_files(folder: Path) -> list[Path]:
    files = []
    for top, folders, names in os.walk(folder):
        folders[:] = sorted(
            f for f in folders if not f.startswith(".") and f not in _SKIPPED_FOLDERS
        )
        files.extend(Path(top, name) for name in names if name.endswith((".urdf", ".xacro")))
    return sorted(f for f in files if f.is_file())


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
) -> list[FileResult]:
    """
    Lint files and folders as the command line does: each file with its configuration (the
    nearest, or ``config``), ``select``/``ignore`` on top, ``fail_on`` over the configured one,
    ``engines`` (names, comma-separated or ``all``; ``None``: the configured ones) instead of
    the configured ones, ``xacro_limits`` (``--xacro-limit``) over the configured ones and the
    environment's.

    Every configuration is read before any file is linted. Raises ``ConfigError`` for a bad
    configuration, a ``select``/``ignore`` entry that names no rule or an unknown engine.
    ``on_error(file, exception)`` gives the result of a file whose linting raised an exception
    (a bug: the command line reports it for that file and lints the others); without it, the
    exception propagates.

    ``fix`` (``--fix``; ``None``: the configured ``fix``) applies the fixes
    (:mod:`~inertia_kit.lint.applying`), safe ones, and unsafe ones with ``unsafe_fixes``
    (``None``: the configured ``unsafe-fixes``); ``diff`` computes them without writing.
    """
    from inertia_kit.errors import ConfigError
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
    plan = [(file, finder.for_file(file)) for file in expand_paths(paths)]
    limits = {found.path: XacroLimits.resolve(found.xacro, xacro_limits) for _, found in plan}
    results = []
    for file, found in plan:
        unsafe = bool(found.unsafe_fixes if unsafe_fixes is None else unsafe_fixes)
        fixing = diff or bool(found.fix if fix is None else fix)
        choice = MassChoice.checked(
            DEFAULT_DENSITY,
            {n: v.mass for n, v in found.links.items() if v.mass is not None},
            {n: v.density for n, v in found.links.items() if v.density is not None},
        )

        def once(file=file, found=found, choice=choice, unsafe=unsafe, fixing=fixing):
            return lint_file(
                file,
                selection_for(found, select, ignore, engines),
                xacro_args=xacro_args,
                package_paths=package_paths,
                load_mesh=load_mesh,
                xacro_limits=limits[found.path],
                mass_choice=choice,
                fixes="safe" if fixing and not unsafe else "all",
            )

        try:
            if fixing:
                from inertia_kit.lint.applying import fix_file

                outcome = fix_file(once, unsafe, write=not diff)
                result = outcome.result
                result.fixed, result.diff = outcome.fixed, outcome.diff
            else:
                result = once()
            result.unsafe_fixes = unsafe
        except Exception as error:
            if on_error is None:
                raise
            result = on_error(file, error)
        # not `or`: Severity.INFO is 0
        result.fail_on = next(s for s in (fail_on, found.fail_on, DEFAULT_FAIL_ON) if s is not None)
        results.append(result)
    return results
