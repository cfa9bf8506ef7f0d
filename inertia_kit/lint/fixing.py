"""
The fixes of one robot: the values each link a fix was asked for gets, and the edits that write
them. ``inertia-lint`` attaches them to its findings; ``inertia-fill`` applies them by mode.

A rule says which of its findings a fix repairs, how its values are found and how far they may
be trusted (its ``FIX``, :class:`~inertia_kit.lint.findings.FixRule`). The values are found
here for the whole robot at once (a ``--total-mass`` is shared among every link that takes a
density), and placed together with one :func:`~inertia_kit.description.placement.place` call,
which sees every link a shared macro makes: two wheels from one macro body that get the same
values get one edit there; links that need different values get theirs at their calls'
parameters.

A link gets one set of values, whichever findings asked for it:

- a recognised slip (``how="slip"``, IN06x) gives the declared values with the slip undone
  (:func:`~inertia_kit.analysis.forensics.links.diagnose_link`): safe when it fits exactly,
  unsafe when it is a real part's likely slip. When the centre of mass is also rejected
  (``how="com"``), it becomes the geometry's, and the fix unsafe;
- a centre of mass slip (``how="com-slip"``, IN067) gives the declared values (or those of a
  tensor slip undone) with the centre of mass read as the slip undone: unsafe;
- else the geometry's values at uniform density, the mass from
  :func:`~inertia_kit.fixes.masses.mass_for` (a declared finite positive mass kept): unsafe.

A link the geometry cannot give values for gets no fix, and the reason is kept.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Collection, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from inertia_kit.description.placement import Target
from inertia_kit.fixes.masses import MassChoice, mass_for, share_total
from inertia_kit.fixes.refusals import geometry_refusal, spoiled, unwritable
from inertia_kit.lint import catalog
from inertia_kit.lint.findings import EditPlace, Finding, Fix, FixRule, Repairs, Safety
from inertia_kit.physics.mass import MassProperties

if TYPE_CHECKING:
    import numpy as np
    from numpy.typing import NDArray

    from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
    from inertia_kit.description.editing import Files
    from inertia_kit.description.edits import Edit

#: the ``how`` of fixes that undo a slip in the declared values (not values from the geometry)
_SLIPS = ("slip", "com-slip")
#: the title of a fix asked for by name, or by ``inertia-fill --fix all``
RECOMPUTE = "recompute the <inertial> from the geometry"


@dataclass(frozen=True)
class LinkFix:
    """
    What one link gets: its ``target`` values and the ``edits`` that write them (none: the
    files already say this), or the ``reason`` it gets none (with the ``block`` to paste when
    the values are known but have no place to go). ``placed`` false: no edit was looked for
    (:func:`plan_fixes` without ``files``).
    """

    link: str
    safety: Safety
    title: str
    target: Target | None = None
    edits: tuple[Edit, ...] = ()
    reason: str | None = None
    block: str | None = None
    placed: bool = True

    @property
    def fixed(self) -> bool:
        return self.target is not None and self.reason is None


@dataclass
class RobotFixes:
    """The fixes of one robot, by link name in document order, and notes for the user."""

    links: dict[str, LinkFix] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)


def plan_fixes(
    analysis: RobotAnalysis,
    findings: Sequence[Finding],
    choice: MassChoice,
    files: Files | None,
    *,
    repairs: Collection[Repairs] | None = None,
    asked: Collection[str] = (),
    recompute: bool = False,
    safe_only: bool = False,
    vouched: Collection[str] = (),
) -> RobotFixes:
    """
    The fixes the ``findings`` of ``analysis`` ask for, placed in ``files`` (``None``: their
    values, safety and refusals only, without looking for where the edits go, which costs more
    than the rest together: for a run that does not apply, show or write out the edits).

    ``repairs``: only fixes repairing these (``None``: all); ``asked``: links fixed from the
    geometry although no finding asks (``inertia-fill --link``/``--mass``); ``recompute``:
    also every link that has an ``<inertial>`` and geometry (``inertia-fill --fix all``), but
    those in ``vouched`` (a finding on them is suppressed: their author keeps their values);
    ``safe_only``: only safe fixes (``inertia-lint --fix`` without ``--unsafe-fixes``).
    """
    wants: dict[str, list[FixRule]] = {}
    spoils: dict[str, str] = {}
    for finding in findings:
        if finding.link is None:
            continue
        if finding.wants is not None:
            wants.setdefault(finding.link, []).append(finding.wants)
        rule = catalog.find(finding.code)
        if rule is not None and getattr(rule, "SPOILS_GEOMETRY", False):
            spoils.setdefault(
                finding.link, spoiled(finding.code, finding.message, finding.expected)
            )

    result = RobotFixes()
    masses: dict[str, tuple[float | None, str]] = {}  # None: a share of the total mass
    chosen: dict[str, tuple[Safety, str, MassProperties | None]] = {}
    seen: set[str] = set()
    for link in analysis.links:
        if link.name in seen:
            continue  # a duplicate name (IN040): the first one is the one tools use
        seen.add(link.name)
        offered = wants.get(link.name, [])
        selected = [w for w in offered if repairs is None or w.repairs in repairs]
        by_name = link.name in asked
        again = (
            recompute
            and link.name not in vouched
            and link.link.inertial is not None
            and bool(link.geometry.solids)
        )
        if not (selected or by_name or again):
            continue
        slip = _slip(link, selected, offered, choice, safe_only)
        if slip is not None:
            safety, title, values = slip
            chosen[link.name] = slip
            masses[link.name] = (values.mass, title)
            continue
        title = next((w.title for w in selected if w.how not in _SLIPS), RECOMPUTE)
        reason = geometry_refusal(link) or spoils.get(link.name)
        if reason is not None:
            result.links[link.name] = LinkFix(link.name, Safety.UNSAFE, title, reason=reason)
            continue
        unit = link.geometry.unit
        assert unit is not None  # geometry_refusal checked
        chosen[link.name] = (Safety.UNSAFE, title, None)
        masses[link.name] = mass_for(link, choice, unit.mass)

    if choice.total_mass is not None:
        problem = share_total(analysis, masses, choice.total_mass)
        if problem is not None:
            for name in [name for name, (mass, _) in masses.items() if mass is None]:
                safety, title, _ = chosen.pop(name)
                result.links[name] = LinkFix(name, safety, title, reason=problem)
                del masses[name]
    targets: list[Target] = []
    for name, (safety, title, values) in chosen.items():
        link = analysis.by_name[name]
        mass, basis = masses[name]
        if values is None:
            unit = link.geometry.unit
            assert unit is not None and mass is not None
            values = unit.with_mass(mass)
        else:
            basis = f"declared, corrected: {basis}"
        problem = unwritable(values)
        if problem is not None:
            result.links[name] = LinkFix(name, safety, title, reason=problem)
            continue
        if safe_only and safety is not Safety.SAFE:
            continue
        shapes = tuple(solid.shape for solid in link.geometry.solids)
        targets.append(Target(link.link, values, basis, shapes))
    if files is not None:
        _place(targets, analysis, files, chosen, result)
    else:
        for target in targets:
            safety, title, _ = chosen[target.name]
            result.links[target.name] = LinkFix(target.name, safety, title, target, placed=False)
    order = {link.name: index for index, link in enumerate(analysis.links)}
    result.links = dict(sorted(result.links.items(), key=lambda item: order.get(item[0], 0)))
    return result


def _slip(
    link: LinkAnalysis,
    selected: list[FixRule],
    offered: list[FixRule],
    choice: MassChoice,
    safe_only: bool = False,
) -> tuple[Safety, str, MassProperties] | None:
    """``(safety, title, values)`` of a selected slip fix, of the tensor (``how="slip"``) or of
    the centre of mass (``how="com-slip"``), or both (``None``: none, or a mass given for the
    link: then the geometry's tensor for that mass). With ``safe_only``, a safe tensor fix is
    not joined to the unsafe centre of mass one (which would make both unsafe: neither taken)."""
    rule = next((w for w in selected if w.how == "slip"), None)
    moved = next((w for w in selected if w.how == "com-slip"), None)
    if (rule is None and moved is None) or link.name in choice.masses:
        return None
    found = _tensor_slip(link, rule, offered) if rule is not None else None
    if moved is None or (safe_only and found is not None and found[0] is Safety.SAFE):
        return found
    com = _com_slip(link)
    if com is None:
        return found
    _, title, values = found or (moved.safety, moved.title, link.declared)
    if values is None:
        return found
    if found is not None:
        title = f"{title}; {moved.title}"
    # a centre of mass slip is never proven (forensics.com_slip): the fix is unsafe
    return Safety.UNSAFE, title, MassProperties(values.mass, com, values.inertia)


def _com_slip(link: LinkAnalysis) -> NDArray[np.float64] | None:
    """The centre of mass with its slip undone (IN067), or ``None``."""
    from inertia_kit.analysis.forensics.com_slip import diagnose_link_com

    diagnosis = diagnose_link_com(link)
    return None if diagnosis is None or diagnosis.reading is None else diagnosis.reading.point


def _tensor_slip(
    link: LinkAnalysis, rule: FixRule, offered: list[FixRule]
) -> tuple[Safety, str, MassProperties] | None:
    """``(safety, title, values)`` of a tensor slip (IN06x) undone, or ``None``."""
    from inertia_kit.analysis.forensics.links import diagnose_link

    diagnosis = diagnose_link(link)
    if diagnosis is None:
        return None
    values = diagnosis.corrected
    unit = link.geometry.unit
    if any(w.how == "com" for w in offered) and unit is not None:
        # the centre of mass is rejected too: the geometry's (the tensor is about the COM,
        # wherever that is); a judgment, so no longer safe
        values = MassProperties(values.mass, unit.com, values.inertia)
        return Safety.UNSAFE, f"{rule.title}, centre of mass from the geometry", values
    if diagnosis.likely is not None:
        # a real part's likely slip (forensics.diagnosis.diagnose_part), not an exact fit
        return Safety.UNSAFE, f"{rule.title} (likely: check against the CAD report)", values
    return rule.safety, rule.title, values


def _place(
    targets: list[Target],
    analysis: RobotAnalysis,
    files: Files,
    chosen: dict[str, tuple[Safety, str, MassProperties | None]],
    result: RobotFixes,
) -> None:
    """Place every target with one call, so links sharing a macro body are seen together."""
    from inertia_kit.description.placement import place

    placements = place(targets, analysis.robot, files)
    for target in targets:
        safety, title, _ = chosen[target.name]
        placement = placements[target.name]
        if placement.problem is None:
            fix = LinkFix(target.name, safety, title, target, placement.edits)
            result.notes.extend(placement.notes)
        else:
            # the problem says what to do, right for every link a shared macro makes
            block = _block(target, analysis.robot.format)
            fix = LinkFix(target.name, safety, title, target, reason=placement.problem, block=block)
        result.links[target.name] = fix


def _block(target: Target, form: str) -> str:
    from inertia_kit.description.writing import inertial_text

    return inertial_text(target.properties, form)


def attach(findings: Sequence[Finding], fixes: RobotFixes, files: Files | None) -> list[Finding]:
    """``findings`` with the fix of their link (or why it has none) where they offer one."""
    result = []
    for finding in findings:
        found = fixes.links.get(finding.link or "") if finding.wants is not None else None
        if found is not None and finding.wants.how == "com-slip" and found.safety is Safety.SAFE:
            found = None  # a centre of mass slip fix is never safe: a safe one leaves it (_slip)
        if found is not None and found.reason is not None:
            reason = found.reason
            if found.block:  # the values to paste, on the reason's one line
                reason += "; its <inertial>: " + "".join(s.strip() for s in found.block.split("\n"))
            finding = dataclasses.replace(finding, unfixable=reason)
        elif found is not None and not found.placed:
            fix = Fix(found.title, (), found.safety, placed=False)
            finding = dataclasses.replace(finding, fix=fix)
        elif found is not None and found.edits:
            assert files is not None  # placed edits were placed in files
            places = tuple(_edit_place(edit, files) for edit in found.edits)
            fix = Fix(found.title, found.edits, found.safety, places)
            finding = dataclasses.replace(finding, fix=fix)
        result.append(finding)
    return result


def _edit_place(edit: Edit, files: Files) -> EditPlace | None:
    """Lines, columns and byte offsets of an edit in the text it was made on."""
    import bisect

    source = files.sources.get(files.real(edit.path))
    if source is None:
        return None
    starts = source.line_starts

    def line_column(offset: int) -> tuple[int, int]:
        line = bisect.bisect_right(starts, offset)
        return line, offset - starts[line - 1] + 1

    start, end = line_column(edit.start), line_column(edit.end)
    return EditPlace(*start, *end, source.byte_offset(edit.start), source.byte_offset(edit.end))


def fixing_rules() -> list:
    """The rules that offer fixes or withhold them (``FIX``, ``SPOILS_GEOMETRY``); no engine's."""
    return [
        rule
        for rule in catalog.RULES
        if catalog.engine(rule) is None
        and (hasattr(rule, "FIX") or getattr(rule, "SPOILS_GEOMETRY", False))
    ]


def robot_fixes(
    analysis: RobotAnalysis,
    choice: MassChoice,
    files: Files,
    *,
    repairs: Collection[Repairs] | None = None,
    asked: Collection[str] = (),
    recompute: bool = False,
    path: str | None = None,
) -> RobotFixes:
    """
    Run :func:`fixing_rules` (default options) on ``analysis`` and plan their fixes; findings
    a suppression comment covers are not fixed (as ruff's fixers honour ``noqa``), nor are
    their links recomputed by ``recompute``; ``path`` being the file of the findings that name
    none.
    """
    from inertia_kit.lint.runner import Selection, run_rules
    from inertia_kit.lint.suppress import suppressed

    found = run_rules(analysis, Selection(), fixing_rules())
    covered = [
        suppressed(f if f.path or path is None else dataclasses.replace(f, path=path))
        for f in found
    ]
    findings = [f for f, hidden in zip(found, covered, strict=True) if not hidden]
    vouched = {f.link for f, hidden in zip(found, covered, strict=True) if hidden and f.link}
    return plan_fixes(
        analysis,
        findings,
        choice,
        files,
        repairs=repairs,
        asked=asked,
        recompute=recompute,
        vouched=vouched,
    )
