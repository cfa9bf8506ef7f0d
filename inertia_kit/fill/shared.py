"""
Robots that include one fragment must agree on what is written there.

A xacro fragment (``hand.xacro``) may be filled through several robots that include it, and
each robot may compute other values for the same element: one loads the hand with its collision
meshes, another without them. Written one after the other, the last robot would win and the
next run would write the first robot's values again: fill would never settle. So an element
that robots of one run want different values for, and that a fill would write in place, is not
filled by any of them; each is told which robots disagree and what each computed. Values
passed at each robot's own call (a macro parameter in the robot's file) do not meet, and are
filled as usual.

An element no robot had values for before (a fragment's link without an ``<inertial>``, which
some robots weld to a body with mass and leave alone) is written by the robots that fill it,
each planned again on the text the one before wrote; once it has an ``<inertial>``, every robot
recomputes it, and a disagreement is found and told from the next run on, which then writes
nothing there.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from inertia_kit.fill.plan import FillPlan, LinkFill


def disagreements(plans: Sequence[tuple[str, FillPlan]]) -> dict[tuple[str, str], str]:
    """
    ``(robot, link) -> reason`` for each link of ``plans`` (``(robot file, plan)``) whose
    element another robot of the run wants other values for, where its fill would write in that
    element's file.
    """
    wanted: dict[tuple, list[tuple[str, LinkFill]]] = {}
    for robot, plan in plans:
        for fill in plan.fills:
            if fill.written_at is not None:
                wanted.setdefault(fill.written_at, []).append((robot, fill))
    refused: dict[tuple[str, str], str] = {}
    for at, fills in wanted.items():
        if len({robot for robot, _ in fills}) < 2:
            continue

        def there(fill: LinkFill, file: str = at[0]) -> frozenset:
            """The fill's edits in the element's file: what the robots must agree on (the
            same formula text agrees even where the robots' numbers differ)."""
            return frozenset(
                (edit.start, edit.end, edit.content)
                for edit in fill.edits
                if str(Path(edit.path).resolve()) == file
            )

        if len({there(fill) for _, fill in fills}) == 1:
            continue
        computed = "; ".join(f"{robot}: {_described(fill)}" for robot, fill in fills)
        for robot, fill in fills:
            if there(fill):
                refused[(robot, fill.link)] = (
                    f"the robots that include {at[0]}:{at[1]} compute other values for it "
                    f"({computed}): a value written there once cannot be right for all of "
                    "them; make the macro take the values as parameters and pass each robot's "
                    "at its call, or fill each robot with -o"
                )
    return refused


def without(plan: FillPlan, robot: str, refused: dict[tuple[str, str], str]) -> FillPlan:
    """``plan`` with the links ``refused`` names for ``robot`` moved to its refusals."""
    from inertia_kit.fill.plan import Refusal

    dropped = [fill for fill in plan.fills if (robot, fill.link) in refused]
    if not dropped:
        return plan
    return dataclasses.replace(
        plan,
        fills=tuple(fill for fill in plan.fills if fill not in dropped),
        refused=(
            *plan.refused,
            *(Refusal(fill.link, refused[(robot, fill.link)]) for fill in dropped),
        ),
    )


def _described(fill: LinkFill) -> str:
    from inertia_kit.description.writing import values_text

    values = values_text(fill.properties)
    return (
        f"{values['mass']} kg at ({values['xyz']}), "
        f"ixx iyy izz {values['ixx']} {values['iyy']} {values['izz']}"
    )
