"""
The lint engine: load each file, analyse it once, run every enabled rule over its scope, drop
what is suppressed or ignored, and return the findings sorted. No output, no exit codes: the
CLI owns those.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from types import ModuleType
from typing import Any

from inertia_kit import model
from inertia_kit.analysis import MeshLoader, RobotAnalysis, analyse
from inertia_kit.errors import InputError
from inertia_kit.findings import Finding, Severity
from inertia_kit.rules import RuleContext, load_rules


@dataclass(frozen=True)
class Selection:
    """
    Which rules run, with what options and severities. ``select``/``ignore`` entries are codes
    (``IN012``), code prefixes (``IN01``, ``IN0``) or names (``inertia-too-small``).
    """

    select: tuple[str, ...] = ("IN0",)
    ignore: tuple[str, ...] = ()
    options: dict[str, dict[str, Any]] = field(default_factory=dict)  # code -> option -> value
    severities: dict[str, Severity] = field(default_factory=dict)  # code -> severity

    @staticmethod
    def matches(rule: ModuleType, patterns: Iterable[str]) -> bool:
        return any(rule.CODE.startswith(p.upper()) or p == rule.NAME for p in patterns)

    def enabled(self, rules: Sequence[ModuleType]) -> list[ModuleType]:
        return [
            rule
            for rule in rules
            if self.matches(rule, self.select) and not self.matches(rule, self.ignore)
        ]


def run_rules(
    analysis: RobotAnalysis,
    selection: Selection = Selection(),
    rules: Sequence[ModuleType] | None = None,
) -> list[Finding]:
    """Every finding of the enabled rules on one analysed robot, sorted."""
    findings: list[Finding] = []
    for rule in selection.enabled(load_rules() if rules is None else rules):
        ctx = RuleContext(
            rule, selection.options.get(rule.CODE, {}), selection.severities.get(rule.CODE)
        )
        targets: Iterable[Any] = analysis.links if rule.SCOPE == "link" else (analysis,)
        for target in targets:
            findings.extend(rule.check(target, ctx))
    return sorted(set(findings), key=_order)


def _order(finding: Finding) -> tuple:
    return (finding.path, finding.line or 0, finding.column or 0, finding.code, finding.message)


def lint_robot(
    robot: model.Robot,
    selection: Selection = Selection(),
    load_mesh: MeshLoader | None = None,
) -> list[Finding]:
    analysis = analyse(robot) if load_mesh is None else analyse(robot, load_mesh)
    return run_rules(analysis, selection)


@dataclass
class FileResult:
    path: str
    findings: list[Finding] = field(default_factory=list)
    error: InputError | None = None
    fragment: bool = False


def lint_file(
    path: str | Path,
    selection: Selection = Selection(),
    *,
    xacro_args: dict[str, str] | None = None,
    package_paths: Sequence[str | Path] = (),
    load_mesh: MeshLoader | None = None,
) -> FileResult:
    """Lint one file; an unreadable one gives a result with ``error`` set, not an exception."""
    from inertia_kit.loader import load

    try:
        robot = load(path, xacro_args=xacro_args, package_paths=package_paths)
    except InputError as error:
        return FileResult(str(path), error=error)
    if robot.fragment:
        return FileResult(str(path), fragment=True)
    return FileResult(str(path), lint_robot(robot, selection, load_mesh))


def expand_paths(paths: Iterable[str | Path]) -> Iterator[Path]:
    """Files as given; folders searched for ``*.urdf``, ``*.xacro`` (``*.urdf.xacro`` too)."""
    for entry in paths:
        path = Path(entry)
        if path.is_dir():
            found = {p for pattern in ("*.urdf", "*.xacro") for p in path.rglob(pattern)}
            yield from sorted(p for p in found if p.is_file())
        else:
            yield path
