"""
``inertia-fill``: plan the ``<inertial>`` blocks computed from each link's geometry as text edits
on the original bytes (every byte outside the edited spans stays as it was), then write them
atomically.

A plan is the fixes of the rules (:mod:`~inertia_kit.lint.fixing`, the path ``inertia-lint
--fix`` takes) that :mod:`~inertia_kit.fill.policy` selects by what they repair, with fill's
mass inputs: the values, the edits where :mod:`~inertia_kit.description.placement` places them
(in xacro, perhaps a macro body or a macro call), and the links refused with their reasons.
:class:`FillPlan` holds the result: the edits, the refusals, the diff. For ``-o OUT``,
:mod:`~inertia_kit.fill.output` says what is filled and writes it.
"""

from __future__ import annotations

import dataclasses
import functools
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from inertia_kit.description.edits import Edit
from inertia_kit.errors import InputError
from inertia_kit.fill.output import output_source
from inertia_kit.fill.policy import REPAIRS, check_fix
from inertia_kit.fixes.masses import MassChoice
from inertia_kit.physics.mass import MassProperties

if TYPE_CHECKING:
    from inertia_kit.description.edits import SourceText
    from inertia_kit.description.model import Robot
    from inertia_kit.description.xacro_limits import XacroLimits


@dataclass(frozen=True)
class LinkFill:
    """
    One link's new ``<inertial>``: ``properties`` in the link frame, ``basis`` says where its
    mass comes from, ``edits`` the text edits (none when the files already say exactly this;
    several for values passed through a xacro macro's parameters; shared with other links
    made from the same macro body).
    """

    link: str
    properties: MassProperties
    basis: str
    replaced: bool
    edits: tuple[Edit, ...] = ()
    # where the link's <inertial> (or, without one, its <link>) is written: resolved path, line,
    # column; robots that include one fragment meet there (fill.shared)
    written_at: tuple[str, int | None, int | None] | None = None

    @property
    def mass_text(self) -> str:
        from inertia_kit.description.writing import mass_text

        return mass_text(self.properties.mass)


@dataclass(frozen=True)
class Refusal:
    """A link that needs an ``<inertial>`` but was not filled, why, and (when its values are
    known but could not be written in place) the block to paste."""

    link: str
    reason: str
    block: str | None = None


@dataclass(frozen=True)
class FillPlan:
    """What filling one file would do; :func:`apply` writes it."""

    path: str
    source: SourceText | None
    fills: tuple[LinkFill, ...] = ()
    refused: tuple[Refusal, ...] = ()
    notes: tuple[str, ...] = ()
    links: frozenset[str] = field(default_factory=frozenset)  # every link name in the file
    # for ``-o``: the file read (``path`` is the one written, ``source`` the text filled:
    # the input's bytes, or the expanded URDF of a xacro input)
    input_path: str | None = None
    # the other files edits go to: xacro files holding macros or included links
    others: tuple[SourceText, ...] = ()
    fragment: bool = False  # a xacro file of macros and properties: no robot, nothing filled
    # what the environment gave the robot's xacro expansion: kept out of fill's messages by
    # --redact-env (description.redaction), never out of the files written
    environment_values: tuple[str, ...] = ()
    # every file the robot was read from (real path -> digest): the write checks that those it
    # does not edit still hold what was read
    reads: Mapping[str, str | None] = field(default_factory=dict)

    @property
    def edits(self) -> list[Edit]:
        """Every edit once (links made from one macro body share its edit)."""
        return list(dict.fromkeys(edit for fill in self.fills for edit in fill.edits))

    @property
    def changed_links(self) -> list[LinkFill]:
        return [f for f in self.fills if f.edits]

    def changes(self) -> list[tuple[SourceText, str]]:
        """``(file as read, its new text)`` for every file whose bytes change, input first."""
        from inertia_kit.description.edits import apply_edits

        result = []
        for source in (self.source, *self.others):
            if source is None:
                continue
            mine = [e for e in self.edits if _same_file(e.path, source.path)]
            if not mine:
                continue
            text, applied = apply_edits(source.text, mine)
            if len(applied) != len(mine):
                raise InputError("two fills edit overlapping text", source.path)
            if source.encode(text) != source.original:
                result.append((source, text))
        return result

    @property
    def new_text(self) -> str:
        """The input's (``source``'s) text after the edits."""
        if self.source is None:
            return ""
        for source, text in self.changes():
            if source is self.source:
                return text
        return self.source.text

    @property
    def new_bytes(self) -> bytes:
        if self.source is None:
            return b""
        return self.source.encode(self.new_text)

    @property
    def changed(self) -> bool:
        return bool(self.changes())

    def diff(self) -> str:
        """A unified diff of the change, file after file (empty when nothing changes)."""
        from inertia_kit.description.edits import unified_diff

        return unified_diff(
            (self.path if source is self.source else source.path, source.text, text)
            for source, text in self.changes()
        )


def _same_file(a: str, b: str) -> bool:
    return a == b or Path(a).resolve() == Path(b).resolve()


def plan_fill(
    path: str | Path,
    *,
    density: float = 1000.0,
    masses: Mapping[str, float] | None = None,
    fix: str = "missing",
    package_paths: Sequence[str | Path] = (),
    xacro_args: Mapping[str, str] | None = None,
    densities: Mapping[str, float] | None = None,
    total_mass: float | None = None,
    output: str | Path | None = None,
    xacro_limits: XacroLimits | None = None,
    links: Sequence[str] = (),
) -> FillPlan:
    """
    Plan the ``<inertial>`` edits for one file (nothing is written).

    Parameters
    ----------
    density : float
      kg/m³, for links without a given or kept mass.
    masses : mapping
      ``link name -> kg``: the link's mass, its tensor scaled to it (wins over a declared mass).
    fix : str
      ``missing``, ``invalid`` or ``all`` (see :mod:`~inertia_kit.fill.policy`).
    densities : mapping
      ``link name -> kg/m³`` for links without a given or kept mass (configuration).
    total_mass : float
      kg of the whole robot: the links that would take ``density`` take instead the one
      density that brings the robot's total mass (declared, kept and given masses included)
      to this; they are refused when the other links already weigh that much.
    output : path
      ``inertia-fill -o``: plan filling ``path`` into this new file instead
      (:func:`~inertia_kit.fill.output.output_source`; ``write_output`` writes it). The plan's
      ``path`` is ``output``, its ``input_path`` is ``path``.
    xacro_limits : XacroLimits, optional
      The limits of a xacro expansion (:func:`~inertia_kit.description.loader.load`).
    links : sequence of str
      Links to fix from the geometry in any mode (``--link``; ``--mass`` names them too).

    Raises
    ------
    InputError
      The file cannot be read or parsed; with ``output``, also a xacro fragment (no robot to
      write) and ``output`` being ``path`` itself. ``ChangedWhileEditing`` when a file to edit
      no longer holds the bytes the robot was loaded from.
    ValueError
      Bad ``density``, ``masses``, ``densities``, ``total_mass`` or ``fix``.
    """
    from inertia_kit.description.edits import real_target
    from inertia_kit.description.loader import load
    from inertia_kit.description.reads import as_loaded

    check_fix(fix)
    choice = MassChoice.checked(density, masses, densities, total_mass)
    path = Path(path)
    if output is not None:
        source, robot = output_source(path, Path(output), package_paths, xacro_args, xacro_limits)
        return plan_robot(
            str(output), source, robot, choice, fix=fix, input_path=str(path), asked=links
        )
    real_target(path)  # a link that leads nowhere: said as such

    def once() -> FillPlan:
        robot = load(
            path, xacro_args=xacro_args, package_paths=package_paths, xacro_limits=xacro_limits
        )
        # the text the robot was read from, or ChangedWhileEditing
        source = as_loaded(path, dict(robot.reads))
        return plan_robot(
            str(path),
            source,
            robot,
            choice,
            fix=fix,
            asked=links,
            reload=functools.partial(
                load,
                path,
                xacro_args=xacro_args,
                package_paths=package_paths,
                xacro_limits=xacro_limits,
            ),
        )

    return _settled(once)


def _settled(once: Callable[[], FillPlan]) -> FillPlan:
    """
    ``once()``, and when what it fills changes what a second plan would fill, both at once:
    a fill can make another needed (a base whose only mass was a broken ``<inertial/>`` on a
    welded link is, once that link is filled, implausibly light for its geometry; fuzz s1,
    input 15852), and a second run must change nothing. The second plan reads the files as the
    first leaves them (description.overlay); its new fills, their edits moved back onto the
    text as read, join the first's. An edit that falls inside text the first wrote cannot be
    moved back and is left to a second run, which the notes say.
    """
    from inertia_kit.description.overlay import overlaid
    from inertia_kit.description.reads import key

    first = once()
    changes = first.changes()
    if not changes:
        return first
    by_file = {key(source.path): (source, text) for source, text in changes}
    with overlaid({name: source.encode(text) for name, (source, text) in by_file.items()}):
        second = once()
    filled = {fill.link for fill in first.changed_links}
    missed = filled & {fill.link for fill in second.changed_links}
    if missed:
        # its edits went where the robot, as these arguments expand it, does not read (a
        # branch of a condition): written, every run would write them again
        return _without(first, missed)
    added: list[LinkFill] = []
    for fill in second.changed_links:
        if fill.link in filled:
            continue
        moved = [_moved_back(edit, first.edits) for edit in fill.edits]
        if any(edit is None for edit in moved):
            return dataclasses.replace(
                first,
                notes=(
                    *first.notes,
                    f"`{fill.link}` needs filling once these fills are written: run "
                    "inertia-fill again",
                ),
            )
        added.append(dataclasses.replace(fill, edits=tuple(e for e in moved if e is not None)))
    if not added:
        return first
    return dataclasses.replace(first, fills=(*first.fills, *added))


def _without(plan: FillPlan, missed: set[str]) -> FillPlan:
    """``plan`` without the fills of ``missed`` (and of links sharing an edit with them),
    which are listed as refused instead."""
    dropped = set(missed)
    while True:  # links made from one macro body share its edits: all of them or none
        edits = {edit for fill in plan.fills if fill.link in dropped for edit in fill.edits}
        more = {fill.link for fill in plan.fills if set(fill.edits) & edits} - dropped
        if not more:
            break
        dropped |= more
    reason = (
        "its values would be written where the robot, as these arguments expand it, does not "
        "read them (a branch of a xacro condition they do not expand): write them by hand"
    )
    return dataclasses.replace(
        plan,
        fills=tuple(fill for fill in plan.fills if fill.link not in dropped),
        refused=(
            *plan.refused,
            *(Refusal(fill.link, reason) for fill in plan.fills if fill.link in dropped),
        ),
    )


def _moved_back(edit: Edit, before: Sequence[Edit]) -> Edit | None:
    """
    ``edit``, made on a file's text after the ``before`` edits, as an edit of the text before
    them; ``None`` when it touches text they wrote.
    """
    shift = 0
    for done in sorted((e for e in before if _same_file(e.path, edit.path)), key=lambda e: e.start):
        written_start = done.start + shift
        written_end = written_start + len(done.content)
        if edit.end <= written_start:
            break
        if edit.start < written_end:
            return None  # inside (or across) what was written
        shift += len(done.content) - (done.end - done.start)
    return dataclasses.replace(edit, start=edit.start - shift, end=edit.end - shift)


def plan_robot(
    path: str,
    source: SourceText,
    robot: Robot,
    choice: MassChoice,
    *,
    fix: str,
    input_path: str | None = None,
    asked: Sequence[str] = (),
    reload: Callable[[], Robot] | None = None,
) -> FillPlan:
    """The fill plan of ``robot``, whose elements are written literally in ``source``
    (``reload``: load it again as it was, for
    :attr:`~inertia_kit.description.editing.Files.reload`)."""
    from inertia_kit.analysis.links import analyse
    from inertia_kit.description.editing import Files
    from inertia_kit.lint.fixing import robot_fixes
    from inertia_kit.lint.stand_in import is_stand_in

    names = frozenset(link.name for link in robot.links)
    if robot.fragment:
        return FillPlan(
            path,
            source,
            notes=("a xacro fragment without links",),
            fragment=True,
            input_path=input_path,
        )
    analysis = analyse(robot)
    files = Files.for_input(
        source.path, dict(robot.reads), only_itself=is_stand_in(os.path.basename(source.path))
    )
    files.add(source)
    files.reload = reload
    fixes = robot_fixes(
        analysis,
        choice,
        files,
        repairs=REPAIRS[fix],
        asked=(*asked, *choice.masses),
        recompute=fix == "all",
        path=source.path,
    )
    fills: list[LinkFill] = []
    refused: list[Refusal] = []
    for name, found in fixes.links.items():
        if found.reason is not None or found.target is None:
            refused.append(Refusal(name, found.reason or "no values", found.block))
            continue
        link = found.target.link
        replaced = link.inertial is not None
        target = found.target
        at = files.key(link.source if link.inertial is None else link.inertial.source)
        fills.append(LinkFill(name, target.properties, target.basis, replaced, found.edits, at))
    main = files.real(source.path)
    others = tuple(s for p, s in files.sources.items() if p != main)
    return FillPlan(
        path,
        source,
        tuple(fills),
        tuple(refused),
        tuple(fixes.notes),
        links=names,
        input_path=input_path,
        others=others,
        environment_values=robot.environment_values,
        reads=dict(robot.reads),
    )


def apply(plan: FillPlan) -> bool:
    """
    Write the plan's edits, each file atomically; returns whether a file was written (only
    when bytes change). Raises ``InputError`` for a read-only file or one changed since
    planning; every file is checked before any is written, so a plan spanning several xacro
    files is not left half-applied.
    """
    from inertia_kit.description.edits import write_all_atomic

    return write_all_atomic(
        [(source.path, source.encode(text), source.original) for source, text in plan.changes()],
        unchanged=plan.reads,
    )


def written_files(plan: FillPlan) -> list[str]:
    """The files writing ``plan`` replaces, as named in it: ``-o``'s OUT, else the changed ones."""
    if plan.input_path is not None:
        return [plan.path] if plan.source is not None else []
    return [source.path for source, _ in plan.changes()]


def links_followed(plan: FillPlan) -> list[tuple[str, Path]]:
    """``(name, real file)`` for each file of :func:`written_files` that is a symbolic link:
    its target is written and the link kept. A link leading nowhere is left to the write,
    which refuses it."""
    from inertia_kit.description.edits import real_target

    followed = []
    for name in written_files(plan):
        if Path(name).is_symlink():
            try:
                followed.append((name, real_target(name)))
            except InputError:
                continue
    return followed


def remove_stale(plan: FillPlan) -> list[Path]:
    """
    Remove the temporary files an earlier write that was killed left beside the files
    ``plan`` reads for editing (or, for ``-o``, beside OUT): only ours, and only those no live
    write holds (:func:`~inertia_kit.description.edits.remove_stale_temporaries`).
    """
    from inertia_kit.description.edits import real_target, remove_stale_temporaries

    names = [plan.path] if plan.input_path is not None else []
    names += [source.path for source in (plan.source, *plan.others) if source is not None]
    folders: dict[Path, None] = {}
    for name in names:
        try:
            folders[real_target(name).parent] = None
        except InputError:
            continue
    return [removed for folder in folders for removed in remove_stale_temporaries(folder)]
