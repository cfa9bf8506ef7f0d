"""
Changed fragments, as a hook hands them over: which robots to lint (or fill) for the files
given, and which of their findings to report.

A file given is linted as itself. When it is xacro (by name or content), or has no link (a
placeholder a robot includes by default), and robots of its repository include it, directly
or through other includes (:mod:`.include_graph`), those robots are linted too, and only
their findings located in the given files are reported, each saying which robot produced it
(``via``). A robot that is itself given is linted as itself only: its findings already hold
everything it takes from the fragment. :func:`targets` is the one mapping ``inertia-lint``
and ``inertia-fill`` share.

The repository
  The git top level (a folder holding ``.git``) above the file, else the folder of the nearest
  configuration file (``.inertia-kit.toml``, a ``pyproject.toml`` with ``[tool.inertia-kit]``),
  else the file's package root (the nearest folder holding ``package.xml``), else the file's
  folder: the first of these is where a team keeps the robots that share its fragments.
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from inertia_kit.lint.include_graph import IncludeGraph, include_graph, real

if TYPE_CHECKING:
    from inertia_kit.description.xacro_limits import XacroLimits
    from inertia_kit.lint.discovery import Discovery
    from inertia_kit.lint.findings import Finding


@dataclass(frozen=True)
class Target:
    """
    A robot file to lint or fill: as itself (``changed`` empty: every finding), or for the
    given files it includes (``changed``: only what lands in them).
    """

    robot: str
    changed: tuple[str, ...] = ()


@dataclass(frozen=True)
class Targets:
    """
    What :func:`targets` gives: the ``targets`` in the order given (files linted as
    themselves, then the robots that include given files); ``fragments`` the given files
    robots include (real path → the file as given), for which a result of their own that says
    "fragment" or "unreadable on its own" is dropped; ``includers`` the robots (as told) that
    include each given xacro file, ``repositories`` where they were looked for and why there.
    """

    targets: list[Target] = field(default_factory=list)
    fragments: dict[str, str] = field(default_factory=dict)
    includers: dict[str, list[str]] = field(default_factory=dict)  # file as given -> robots
    repositories: dict[str, tuple[Path, str]] = field(default_factory=dict)
    graphs: list[IncludeGraph] = field(default_factory=list)

    def note(self, file: str, fragment: bool, doing: str = "lint") -> str | None:
        """
        What to tell of a given ``file`` (``fragment``: it makes no robot by itself): the robots
        ``doing`` (``lint``, ``fill``) it, or, for a fragment, that none includes it.
        """
        robots = self.includers.get(file)
        if robots:
            also = "" if fragment else "also "
            return f"{also}{doing}ed through the robots that include it: {', '.join(robots)}"
        if fragment and file in self.repositories:
            root, why = self.repositories[file]
            return (
                f"a xacro fragment no robot in {shown(root)} ({why}) includes; nothing to {doing}"
            )
        return None

    def read_by_robots(self, target: Target) -> bool:
        """Whether ``target`` is a given file that robots include (so they are its check)."""
        return not target.changed and bool(self.fragments) and real(target.robot) in self.fragments

    def through(self, robot: str) -> tuple[str, ...]:
        """The given files ``robot`` is linted or filled for (empty: as itself)."""
        return next((t.changed for t in self.targets if t.changed and t.robot == robot), ())


def repository_root(file: str | Path) -> tuple[Path, str]:
    """The folder whose robots may include ``file``, and which rule chose it."""
    from inertia_kit.lint.config_files import find_config

    folder = Path(os.path.abspath(file)).parent
    for candidate in (folder, *folder.parents):
        if os.path.exists(candidate / ".git"):
            return candidate, "the git top level"
    config = find_config(folder)
    if config is not None:
        return config.parent, f"the folder of {config.name}"
    for candidate in (folder, *folder.parents):
        if os.path.isfile(candidate / "package.xml"):
            return candidate, "the package root"
    return folder, "the file's folder (no git repository, configuration or package.xml)"


def targets(
    paths: Iterable[str | Path],
    *,
    xacro_args: Mapping[str, str] | None = None,
    package_paths: Sequence[str | Path] = (),
    xacro_limits: XacroLimits | None = None,
    cache_dir: str | Path | None = None,
    discovery: Discovery | None = None,
    found: Callable[[list[str]], None] | None = None,
) -> Targets:
    """
    The robots to lint (or fill) for ``paths`` (files and folders, walked as the linter walks
    them, ``discovery`` saying what the walk leaves out; ``found(files)`` told the files the
    walk gave): each file as itself, and each robot
    of the repository that includes a given file (and is not given itself) for the given
    files it includes.
    """
    from inertia_kit.lint.discovery import expand_paths

    files = [str(file) for file in expand_paths(paths, discovery)]
    if found is not None:  # told before the repositories are scanned for includers
        found(files)
    given = {real(file) for file in files}
    graphs: dict[Path, IncludeGraph] = {}
    through: dict[str, list[str]] = {}  # robot (real path) -> given files it is linted for
    result = Targets([Target(file) for file in files])
    roots = {file: repository_root(file) for file in filter(_includable, files)}
    wanted: dict[Path, list[str]] = {}  # repository -> the given files its robots may include
    for file, (root, _) in roots.items():
        wanted.setdefault(root, []).append(file)
    for file, (root, why) in roots.items():
        if root not in graphs:
            graphs[root] = include_graph(
                root,
                xacro_args=xacro_args,
                package_paths=package_paths,
                xacro_limits=xacro_limits,
                cache_dir=cache_dir,
                wanted=wanted[root],
            )
        result.repositories[file] = (root, why)
        includers = graphs[root].includers(file)
        if not includers:
            continue
        result.fragments[real(file)] = file
        result.includers[file] = [shown(robot) for robot in includers]
        for robot in includers:
            if robot not in given:
                through.setdefault(robot, []).append(file)
    result.targets.extend(Target(shown(r), tuple(changed)) for r, changed in through.items())
    result.graphs.extend(graphs.values())
    return result


def _includable(file: str) -> bool:
    """
    Whether ``file`` may be included by a URDF robot: xacro by name or by content, or a file
    without links (a placeholder such as husky's ``empty.urdf``, which ``$(arg urdf_extras)``
    names by default), unless an MJCF model. A plain URDF with links is included by none in
    practice, and is linted as itself without scanning the repository.
    """
    from inertia_kit.description.loader import format_of, may_be_included

    if file.lower().endswith(".xacro"):
        return True
    from inertia_kit.description.safexml import read_bounded
    from inertia_kit.errors import InputError

    try:
        data = read_bounded(file)
    except InputError:
        return False
    if format_of(data) == "mjcf":
        return False  # a model of its own, its includes read with it: no robot includes it
    return may_be_included(data) or _linkless(data)


def _linkless(data: bytes) -> bool:
    """Whether a file's bytes hold no ``<link``: cheap, and only decides whether robots that
    may include the file are looked for (its own result says whether it describes links)."""
    return b"<link" not in data


def shown(path: str | Path) -> str:
    """A path as told: relative to the working folder when below it, else absolute."""
    absolute = os.path.abspath(path)
    relative = os.path.relpath(absolute)
    return absolute if relative.startswith(os.pardir) or relative == os.curdir else relative


def located(findings: Iterable[Finding], robot: str, changed: Sequence[str]) -> list[Finding]:
    """
    The findings of ``robot`` located in the ``changed`` files, each saying ``via`` the robot:
    a finding in a changed file as it is; one for an element a macro body in a changed file
    produced, moved to that element (the call site is in the robot, not in the change).
    """
    keys = {real(path) for path in changed}
    kept = []
    for finding in findings:
        if finding.path and real(finding.path) in keys:
            kept.append(dataclasses.replace(finding, via=(robot,)))
        elif finding.macro_path and real(finding.macro_path) in keys:
            kept.append(
                dataclasses.replace(
                    finding,
                    path=finding.macro_path,
                    line=finding.macro_line,
                    column=None,
                    macro_path=None,
                    macro_line=None,
                    via=(robot,),
                )
            )
    return kept
