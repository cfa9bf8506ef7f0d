"""
``inertia-fill`` on a file that robots include (a xacro fragment a hook hands over): the robot
is filled, but only where its edits land in the given files.

The robots come from :func:`inertia_kit.lint.fragments.targets`, as for ``inertia-lint``. A
robot's plan keeps the links whose every edit lands in the given files, and the refusals of
links whose ``<link>`` or ``<inertial>`` stands in them (or in a macro call there); a link
whose values are written partly elsewhere is left, with a note naming the robot to fill.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from inertia_kit.lint.fragments import Target, Targets, targets
from inertia_kit.lint.include_graph import real

if TYPE_CHECKING:
    from inertia_kit.description.model import Link, Robot, Source
    from inertia_kit.description.xacro_limits import XacroLimits
    from inertia_kit.fill.plan import FillPlan


def fill_targets(
    paths: Sequence[str | Path],
    output: str | None,
    xacro_args: Mapping[str, str] | None,
    package_paths: Sequence[str | Path],
    xacro_limits: Mapping[str, float] | None,
    discovery: Any = None,
) -> Targets:
    """
    The robots to fill for ``paths``: :func:`~inertia_kit.lint.fragments.targets`; with
    ``-o`` (one file written into OUT), the file as given.
    """
    from inertia_kit.description.xacro_limits import XacroLimits
    from inertia_kit.errors import ConfigError

    if output is not None:
        return Targets([Target(str(path)) for path in paths])
    try:
        limits = XacroLimits.resolve(None, xacro_limits)
    except ConfigError:  # a bad INERTIA_KIT_XACRO_LIMITS: told when the files are planned
        limits = XacroLimits.resolve(None, xacro_limits, env={})
    return targets(
        paths,
        xacro_args=xacro_args,
        package_paths=package_paths,
        xacro_limits=limits,
        discovery=discovery,
    )


def cut(
    plan: FillPlan,
    target: Target,
    chosen: Targets,
    xacro_args: Mapping[str, str] | None,
    package_paths: Sequence[str | Path],
    xacro_limits: XacroLimits | None,
) -> FillPlan:
    """
    ``plan`` as ``target`` asks: a robot filled for given files it includes cut down to them
    (:func:`only_in`); a given file with the note on the robots filled for it, or that none
    includes it.
    """
    if target.changed:
        return only_in(
            plan,
            target.changed,
            xacro_args=xacro_args,
            package_paths=package_paths,
            xacro_limits=xacro_limits,
        )
    if not plan.links and chosen.read_by_robots(target):
        # a placeholder its robots include (no link of its own): filled through them only
        plan = dataclasses.replace(plan, fragment=True, notes=())
    note = chosen.note(target.robot, plan.fragment, "fill")
    if note is None:
        return plan
    kept = () if plan.fragment else plan.notes  # "a fragment without links" says less
    return dataclasses.replace(plan, notes=(*kept, note))


def only_in(
    plan: FillPlan,
    changed: Sequence[str],
    *,
    xacro_args: Mapping[str, str] | None = None,
    package_paths: Sequence[str | Path] = (),
    xacro_limits: XacroLimits | None = None,
) -> FillPlan:
    """``plan`` (of a robot that includes the ``changed`` files) cut down to what lands there."""
    keys = {real(path) for path in changed}
    fills, notes = [], list(plan.notes)
    for fill in plan.fills:
        inside = [real(edit.path) in keys for edit in fill.edits]
        if all(inside):
            fills.append(fill)
        elif any(inside):
            notes.append(
                f"link `{fill.link}` not filled: its values are also written outside "
                f"{', '.join(changed)}; run inertia-fill on {plan.path}"
            )
    refused = plan.refused
    if refused:
        robot = _load(plan.path, xacro_args, package_paths, xacro_limits)
        where = {link.name: _files(link) for link in robot.links}
        refused = tuple(r for r in refused if where.get(r.link, set()) & keys)
    return dataclasses.replace(plan, fills=tuple(fills), refused=refused, notes=tuple(notes))


def _load(
    path: str,
    xacro_args: Mapping[str, str] | None,
    package_paths: Sequence[str | Path],
    xacro_limits: XacroLimits | None,
) -> Robot:
    from inertia_kit.description.loader import load

    return load(path, xacro_args=xacro_args, package_paths=package_paths, xacro_limits=xacro_limits)


def _files(link: Link) -> set[str]:
    """The files a link's ``<link>`` and ``<inertial>`` elements, and their macro calls, are in."""
    sources = [link.source] if link.inertial is None else [link.source, link.inertial.source]
    return {real(s.path) for s in _with_calls(sources) if s.path}


def _with_calls(sources: Iterable[Source]) -> Iterable[Source]:
    for source in sources:
        yield source
        yield from source.calls
