"""
``inertia-fill``'s work, as :func:`filling` gives it back to the command, which prints it: every
robot planned (:class:`Planned`, in input order), then each planned file written, or told
(``--diff``) or checked (:class:`Finished`). Nothing here prints.

Every robot is planned before any is written: robots that include one fragment and want other
values there write none of them (:mod:`inertia_kit.fill.shared`), and a ``--mass``/``--link``
name no file holds stops the run (:class:`Unknown`) before anything is written.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from inertia_kit.cli.guard import internal, processing

if TYPE_CHECKING:
    from inertia_kit.cli.runs import FillRun
    from inertia_kit.fill.plan import FillPlan
    from inertia_kit.lint.fragments import Target, Targets


@dataclass(frozen=True)
class Planned:
    """
    One robot planned: ``plan``, or ``None`` when it could not be; ``error`` then what to tell
    (``None``: nothing, as for a given file read through the robots that include it).
    ``secrets``: what the environment gave its expansion, kept out of everything printed
    from now on (``--redact-env``). ``again``: planned a second time, on the text an earlier
    robot's fill wrote in a fragment they share.
    """

    target: Target
    plan: FillPlan | None
    error: str | None = None
    secrets: tuple[str, ...] = ()
    again: bool = False


@dataclass(frozen=True)
class Unknown:
    """``--mass``/``--link`` names no planned file holds: nothing is written (exit 2)."""

    names: tuple[str, ...]


@dataclass(frozen=True)
class Finished:
    """
    One planned file written, or shown (``--diff``) or checked: ``removed`` the temporary files
    an earlier killed fill left, removed; ``diff`` its diff (``--diff``); ``done`` whether its
    links were (or would be) filled, ``followed`` the symbolic links written through;
    ``error`` why writing failed; ``crash`` a bug (nothing more of it told); ``through`` the
    given files it was filled for (empty: as itself).
    """

    plan: FillPlan
    through: tuple[str, ...] = ()
    removed: tuple[Path, ...] = ()
    diff: str = ""
    done: bool = False
    followed: tuple[tuple[str, Path], ...] = ()
    error: str | None = None
    crash: str | None = None

    @property
    def changed(self) -> bool:
        return self.done and bool(self.plan.changed_links)

    @property
    def refused(self) -> bool:
        return self.crash is None and bool(self.plan.refused)

    @property
    def failed(self) -> bool:
        return self.error is not None or self.crash is not None


def filling(run: FillRun) -> Iterator[Planned | Unknown | Finished]:
    """
    Plan every robot ``run`` asks for, then write (or show, or check) each planned file; what
    happened, in order. ``ConfigError`` for a bad configuration (exit 2).
    """
    from inertia_kit.fill.fragments import fill_targets
    from inertia_kit.fill.plan import written_files
    from inertia_kit.fill.policy import unknown_links
    from inertia_kit.fill.shared import disagreements, without

    chosen = fill_targets(
        run.paths, run.output, run.xacro_args, run.package_paths, run.xacro_limits, run.walk
    )
    planned = []
    for target in chosen.targets:
        told = _plan(run, chosen, target)
        yield told
        if told.plan is not None:
            planned.append((target, told.plan))
    # robots that include one fragment and want other values there: none writes it (fill.shared)
    disagree = disagreements([(target.robot, plan) for target, plan in planned])
    planned = [(target, without(plan, target.robot, disagree)) for target, plan in planned]
    unknown = unknown_links([*run.masses, *run.links], [plan for _, plan in planned])
    if unknown:
        yield Unknown(tuple(unknown))
        return
    written: set[Path] = set()
    for target, plan in planned:
        if run.writes and written & {Path(name).resolve() for name in written_files(plan)}:
            # a fragment several robots include: an earlier robot's fill wrote there, so this
            # one is planned again on the new text (else its edits would not apply)
            told = dataclasses.replace(_plan(run, chosen, target), again=True)
            yield told
            if told.plan is None:
                continue
            plan = without(told.plan, target.robot, disagree)
        finished = _finish(run, plan, chosen.through(plan.path))
        yield finished
        if run.writes and finished.changed:
            written.update(Path(name).resolve() for name in written_files(plan))


def _plan(run: FillRun, chosen: Targets, target: Target) -> Planned:
    """The plan of one robot, or why there is none; ``ConfigError`` raised."""
    from inertia_kit.description.edits import ChangedWhileEditing
    from inertia_kit.description.xacro_limits import XacroLimits
    from inertia_kit.errors import ConfigError, InputError
    from inertia_kit.fill.fragments import cut
    from inertia_kit.fill.plan import plan_fill
    from inertia_kit.fill.policy import per_link

    path = target.robot
    redacts, secrets = False, ()
    with processing(path):
        try:
            found = run.finder.for_file(path)
            redacts = run.redact_env if run.redact_env is not None else found.redact_environment
            bounds = XacroLimits.resolve(found.xacro, run.xacro_limits)
            plan = plan_fill(
                path,
                density=run.density,
                fix=run.fix,
                package_paths=run.package_paths,
                xacro_args=run.xacro_args,
                total_mass=run.total_mass,
                output=run.output,
                xacro_limits=bounds,
                links=run.links,
                **per_link(found.links, run.masses),
            )
            secrets = plan.environment_values if redacts else ()
            plan = cut(plan, target, chosen, run.xacro_args, run.package_paths, bounds)
            return Planned(target, plan, secrets=secrets)
        except ConfigError:
            raise
        except InputError as error:
            meanwhile = isinstance(error, ChangedWhileEditing)  # told, whoever reads it
            if meanwhile or not chosen.read_by_robots(target):  # else: through its robots
                told = (*secrets, *error.environment_values) if redacts else ()
                return Planned(target, None, str(error), told)
        except Exception as error:  # a bug: reported for this file, the others go on
            return Planned(target, None, str(internal(error, path)), secrets)
    return Planned(target, None, secrets=secrets)


def _finish(run: FillRun, plan: FillPlan, through: tuple[str, ...]) -> Finished:
    """
    Write (or show, ``--diff``) one planned file. A file that is a symbolic link out of its
    repository is not written, unless ``--follow-symlinks``
    (:mod:`~inertia_kit.lint.repository_links`).
    """
    from inertia_kit.errors import InputError
    from inertia_kit.fill.output import write_output
    from inertia_kit.fill.plan import apply, links_followed, remove_stale, written_files
    from inertia_kit.lint.repository_links import refuse_links_out

    told = Finished(plan, through)
    with processing(plan.path):
        try:
            if run.writes:
                told = Finished(plan, through, removed=tuple(remove_stale(plan)))
            if run.diff and plan.changed:
                told = Finished(plan, through, told.removed, plan.diff())
            if not (plan.changed_links or (plan.input_path is not None and run.writes)):
                return told
            followed = tuple(links_followed(plan)) if run.writes else ()
            try:
                if run.writes and plan.input_path is None:
                    refuse_links_out(written_files(plan), run.follow_symlinks)
                    apply(plan)
                elif run.writes:
                    write_output(plan, run.follow_symlinks)
            except InputError as error:
                return Finished(plan, through, told.removed, told.diff, error=str(error))
            return Finished(plan, through, told.removed, told.diff, True, followed)
        except Exception as error:  # a bug: reported for this file, the others go on
            crash = str(internal(error, plan.path))
            return Finished(plan, through, told.removed, told.diff, crash=crash)
