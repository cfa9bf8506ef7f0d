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
import functools
import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING, Any

from inertia_kit.analysis.geometry import MeshLoader
from inertia_kit.analysis.links import RobotAnalysis, analyse
from inertia_kit.description import model
from inertia_kit.description.edits import ChangedWhileEditing
from inertia_kit.description.xacro_limits import XacroLimits
from inertia_kit.errors import InputError, InternalError
from inertia_kit.fixes.masses import DEFAULT_DENSITY, MassChoice
from inertia_kit.lint import catalog
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.rules import RuleContext
from inertia_kit.lint.weighing import weigh

if TYPE_CHECKING:
    from inertia_kit.lint.config import Config, PerFileIgnore

DEFAULT_SELECT = ("IN0",)
DEFAULT_FAIL_ON = Severity.WARNING


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

    def enabled(self, rules: Sequence[ModuleType]) -> list[ModuleType]:
        chosen = (tuple(self.select), tuple(self.ignore), tuple(self.engines))
        return [rule for rule in rules if _runs(rule, *chosen)]

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


@functools.lru_cache(maxsize=4096)
def _runs(
    rule: ModuleType, select: tuple[str, ...], ignore: tuple[str, ...], engines: tuple[str, ...]
) -> bool:
    """Whether ``rule`` runs under a selection's ``select``, ``ignore`` and ``engines``: asked
    for every rule of every file, answered once (a run has a selection or a few)."""
    engine = catalog.engine(rule)
    chosen = (
        engine in engines if engine is not None else catalog.selects(select, rule.CODE, rule.NAME)
    )
    return chosen and not catalog.selects(ignore, rule.CODE, rule.NAME)


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


def checked_selectors(
    select: Sequence[str], ignore: Sequence[str], engines: Sequence[str] | None
) -> tuple[tuple[str, ...], tuple[str, ...], tuple[str, ...] | None]:
    """
    The command line's ``--select`` and ``--ignore`` as codes (or prefixes) and ``--engine`` as
    engine names, as :func:`selection_for` takes them; ``ConfigError`` for an entry that names
    no rule or engine.
    """
    from inertia_kit.errors import ConfigError

    known = catalog.names()

    def checked(option: str, values: Sequence[str]) -> tuple[str, ...]:
        selectors = tuple(catalog.normalize_selector(value, known) for value in values)
        for value, selector in zip(values, selectors, strict=True):
            if selector is None:
                raise ConfigError(f"{option}: {catalog.selector_error(value, known)}")
        return selectors  # type: ignore[return-value]

    if engines is not None:
        from inertia_kit.engines.vocabulary import parse_engines

        try:
            engines = parse_engines(engines)
        except ValueError as error:
            raise ConfigError(f"--engine: {error}") from None
    return checked("--select", select), checked("--ignore", ignore), engines


def file_settings(
    config: Config,
    select: Sequence[str],
    ignore: Sequence[str],
    engines: Sequence[str] | None,
    xacro_limits: Mapping[str, float] | None,
) -> tuple[Selection, XacroLimits, MassChoice]:
    """
    What linting a file under ``config`` takes from it, with the command line's selectors
    (:func:`selection_for`) and ``--xacro-limit`` on top: its selection, xacro limits and mass
    choice. The same for every file of a configuration: a run makes them once for all.
    """
    return (
        selection_for(config, select, ignore, engines),
        XacroLimits.resolve(config.xacro, xacro_limits),
        mass_choice_for(config),
    )


def mass_choice_for(config: Config) -> MassChoice:
    """The masses and densities ``config`` gives its links (``[links.NAME]``), the others at
    the default density."""
    return MassChoice.checked(
        DEFAULT_DENSITY,
        {n: v.mass for n, v in config.links.items() if v.mass is not None},
        {n: v.density for n, v in config.links.items() if v.density is not None},
    )


def run_rules(
    analysis: RobotAnalysis,
    selection: Selection = Selection(),
    rules: Sequence[ModuleType] | None = None,
    superseded: list[Finding] | None = None,
) -> list[Finding]:
    """
    Every finding of the enabled rules on one analysed robot, sorted, duplicates once; the
    findings another rule's replaced are added to ``superseded`` when it is given.
    """
    findings: dict[tuple, Finding] = {}
    # rules of scope "suppressions" (IN090) judge the comments after the others: lint.unused
    enabled = selection.enabled(catalog.RULES if rules is None else rules)
    form = analysis.robot.format
    enabled = [
        rule
        for rule in enabled
        if rule.SCOPE in ("link", "robot") and form in catalog.formats(rule)
    ]
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
                elif configured is None:
                    # a helper frame's defect weighs what it adds to its lumped body
                    weighed = weigh(analysis, finding)
                    if weighed is None:
                        continue
                    finding = weighed
                # Finding compares by place and code only: two messages at one place are two
                findings.setdefault(_order(finding), finding)
    replaced = {
        (code, f.link) for f in findings.values() if f.link for code in supersedes.get(f.code, ())
    }
    kept = [_worded(findings[key], form) for key in sorted(findings)]
    if superseded is not None:
        superseded.extend(f for f in kept if (f.code, f.link) in replaced)
    return [f for f in kept if (f.code, f.link) not in replaced]


def _worded(finding: Finding, form: str) -> Finding:
    """
    A finding in its format's words: the rules write URDF's ``link `x`: ...``; an MJCF model
    has bodies, so its findings read ``body `x`: ...``.
    """
    if form == "mjcf" and finding.message.startswith("link `"):
        return dataclasses.replace(finding, message="body `" + finding.message[len("link `") :])
    return finding


def _order(finding: Finding) -> tuple:
    return (finding.path, finding.line or 0, finding.column or 0, finding.code, finding.message)


def lint_robot(
    robot: model.Robot,
    selection: Selection = Selection(),
    load_mesh: MeshLoader | None = None,
    superseded: list[Finding] | None = None,
) -> list[Finding]:
    """The findings of a loaded robot (suppression comments and per-file ignores not applied)."""
    analysis = analyse(robot) if load_mesh is None else analyse(robot, load_mesh)
    return run_rules(analysis, selection, superseded=superseded)


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
    # the suppression comments' use (lint.unused), to judge a fragment over all its robots
    uses: Any = None
    selection: Selection | None = None
    remarks: list[str] = field(default_factory=list)  # told as notes (a fragment's robots)
    fixed: int = 0  # findings whose fix ``--fix`` applied
    diff: str = ""  # ``--diff``: the unified diff of the fixes
    unsafe_fixes: bool = False  # whether unsafe fixes are applicable here
    empty: bool = False  # no link and no joint: a placeholder, or a piece of other robots
    # what the environment gave its xacro expansion, for --redact-env (description.redaction)
    environment_values: tuple[str, ...] = ()
    # real path -> digest of the bytes the load read (description.reads): what fixes and
    # suppression comments are placed in
    reads: dict[str, str | None] = field(default_factory=dict)
    # findings already told and dropped from ``findings`` (a run that streams its report:
    # lint.paths.Linting with ``release``): how many, and whether one fails the run
    told: int = 0
    told_failing: bool = False

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
    place_fixes: bool = True,
    loaded: Callable[[model.Robot], object] | None = None,
) -> FileResult:
    """
    Lint one file; an unreadable one gives a result with ``error`` set, not an exception.
    Suppression comments (in the file and every xacro file it includes) and the selection's
    per-file ignores are applied. The findings that remain carry their fixes
    (:mod:`~inertia_kit.lint.fixing`; ``fixes``: ``all``, ``safe`` only, or ``none``), the
    values from the geometry with ``mass_choice`` (default: 1000 kg/m³, declared masses kept);
    with their edits placed in the files, unless ``place_fixes`` is false (a run that neither
    applies, shows nor writes out the edits: each fix's values, safety and title only).
    ``loaded(robot)`` is told the robot as loaded, before it is linted (what the caller reads of
    it besides the findings needs no second load: the dataset mode's declared values).
    """
    from inertia_kit.description.loader import load
    from inertia_kit.lint import unused
    from inertia_kit.lint.suppress import directives, suppressed

    if directives(path).disabled:
        return FileResult(str(path), disabled=True)
    try:
        robot = load(
            path, xacro_args=xacro_args, package_paths=package_paths, xacro_limits=xacro_limits
        )
    except InputError as error:
        return FileResult(str(path), error=error, environment_values=error.environment_values)
    if robot.fragment:
        return FileResult(str(path), fragment=True)
    if loaded is not None:
        loaded(robot)
    notes = [
        f"{found.path}{'' if line is None else f':{line}'}: inertia-lint comment ignored: {text}"
        for found in map(directives, robot.files or (str(path),))
        for line, text in found.problems
    ]
    replaced: list[Finding] = []  # a comment that covers one of these is not unused
    analysis = analyse(robot) if load_mesh is None else analyse(robot, load_mesh)
    found = run_rules(analysis, selection, superseded=replaced)
    findings, replaced = (
        [f if f.path else dataclasses.replace(f, path=str(path)) for f in each]
        for each in (found, replaced)
    )
    kept = [
        f if f.wants is None or selection.offers_fix(f) else dataclasses.replace(f, wants=None)
        for f in findings
        if not selection.ignored(f, path) and not suppressed(f)
    ]
    ran = selection.enabled(catalog.RULES)
    reads = dict(robot.reads)
    uses = unused.track(robot.files or (str(path),), findings + replaced, ran, reads)
    kept += unused.report(uses, selection, path)
    if fixes != "none" and any(f.wants is not None for f in kept):
        try:
            reload = functools.partial(
                load,
                path,
                xacro_args=xacro_args,
                package_paths=package_paths,
                xacro_limits=xacro_limits,
            )
            choice = mass_choice or MassChoice()
            kept = _with_fixes(path, analysis, kept, choice, fixes == "safe", reload, place_fixes)
        except ChangedWhileEditing as error:  # the robot's lines point into another text now
            return FileResult(str(path), error=error, reads=reads)
    empty = not robot.links and not robot.joints
    return FileResult(
        str(path),
        kept,
        notes=notes,
        uses=uses,
        selection=selection,
        empty=empty,
        environment_values=robot.environment_values,
        reads=reads,
    )


def _with_fixes(
    path: str | Path,
    analysis: RobotAnalysis,
    findings: list[Finding],
    choice: MassChoice,
    safe_only: bool,
    reload: Callable[[], model.Robot] | None = None,
    place: bool = True,
) -> list[Finding]:
    """
    The findings with their fixes, planned on the text of ``path`` as the load read it
    (``ChangedWhileEditing`` when a file the fixes edit holds other bytes now); not ``place``:
    their values, safety and titles without their edits (no file is read).
    """
    from inertia_kit.description.editing import Files
    from inertia_kit.lint.fixing import attach, plan_fixes
    from inertia_kit.lint.stand_in import is_stand_in

    if not place:
        planned = plan_fixes(analysis, findings, choice, None, safe_only=safe_only)
        return attach(findings, planned, None)

    files = Files.for_input(
        path, dict(analysis.robot.reads), only_itself=is_stand_in(os.path.basename(path))
    )
    files.reload = reload
    try:
        files.source(str(path))
    except ChangedWhileEditing:
        raise
    except InputError:
        return findings  # not editable as text (an odd encoding): findings without fixes
    planned = plan_fixes(analysis, findings, choice, files, safe_only=safe_only)
    return attach(findings, planned, files)
