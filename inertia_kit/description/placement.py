"""
Where a body's new mass properties are written, whatever the format: a :class:`Target` (the
body's model, its values and the shapes they were computed from) becomes a :class:`Placement`
(the text edits that write them, or why not) through its format's writer:
:mod:`.urdf.placement.sites` (URDF and xacro: in place, at a macro call or in a property) or
:mod:`.mjcf.placement` (the body's ``<inertial>``). A third format's writer is a third branch
of :func:`place`.
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from dataclasses import dataclass

from inertia_kit.description import model
from inertia_kit.description.editing import Files
from inertia_kit.description.edits import Edit
from inertia_kit.physics.mass import MassProperties


@dataclass(frozen=True)
class Target:
    """
    A link to fill with ``properties`` (link frame, about its centre of mass); ``basis`` says
    where its mass comes from; ``shapes`` are the shapes the values were computed from (a
    writer may write a formula of a lone shape's dimensions instead of a number).
    """

    link: model.Link
    properties: MassProperties
    basis: str = ""
    shapes: tuple[model.Shape, ...] = ()

    def __post_init__(self) -> None:
        from inertia_kit.description.writing import as_written

        # what the file will hold, so that every comparison (and the next run) sees the same
        object.__setattr__(self, "properties", as_written(self.properties))

    @property
    def name(self) -> str:
        return self.link.name

    @functools.cached_property
    def values(self) -> dict[str, str]:
        """The text written for each value (compared across links made by one element)."""
        from inertia_kit.description.writing import values_text

        values = values_text(self.properties)
        del values["rpy"]
        return values


@dataclass(frozen=True)
class Placement:
    """How a link's values get into its files: ``edits`` (empty: already there), or ``problem``."""

    edits: tuple[Edit, ...] = ()
    problem: str | None = None  # why not, and what to do
    notes: tuple[str, ...] = ()  # expressions replaced by numbers: the link is no longer parametric


def place(targets: Sequence[Target], robot: model.Robot, files: Files) -> dict[str, Placement]:
    """The edits that write each target's values into ``robot``'s files, by link name (every
    link of ``robot`` is seen, to know which others an element makes too)."""
    if robot.format == "mjcf":
        from inertia_kit.description.mjcf.placement import place as place_mjcf

        return place_mjcf(targets, robot, files)
    from inertia_kit.description.urdf.placement.sites import place as place_urdf

    return place_urdf(targets, robot.links, files)
