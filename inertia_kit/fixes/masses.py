"""
The mass inputs of a fix from the geometry, and the mass each link gets.

A link's mass: ``masses[link]`` when given (``--mass``, or configured); else a declared mass
that is finite and positive (kept: it is usually measured or from CAD; the tensor and centre of
mass are recomputed from the geometry for it); else the geometry's volume times the link's
configured density, else the density that makes the robot weigh ``total_mass``
(:func:`share_total`), else ``density``. ``inertia-lint`` uses the configured inputs and the
default density; ``inertia-fill`` adds its options.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from inertia_kit.physics.numbers import usable

if TYPE_CHECKING:
    from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis

#: kg/m³ when no density is given: water, about what printed and hollow parts average
DEFAULT_DENSITY = 1000.0


@dataclass(frozen=True)
class MassChoice:
    """Where a fixed link's mass comes from; :func:`mass_for` reads it in this order."""

    density: float = DEFAULT_DENSITY
    masses: Mapping[str, float] = field(default_factory=dict)
    densities: Mapping[str, float] = field(default_factory=dict)
    total_mass: float | None = None

    @classmethod
    def checked(
        cls,
        density: float,
        masses: Mapping[str, float] | None = None,
        densities: Mapping[str, float] | None = None,
        total_mass: float | None = None,
    ) -> MassChoice:
        """``ValueError`` for a density, mass or total that is not a positive finite number."""
        if not (usable(density, scale=True) and density > 0):
            raise ValueError(f"density must be a positive number of kg/m³, got {density}")
        if total_mass is not None and not (usable(total_mass, scale=True) and total_mass > 0):
            raise ValueError(f"the total mass must be a positive number of kg, got {total_mass}")
        masses = dict(masses or {})
        for name, kg in masses.items():
            if not (usable(kg, scale=True) and kg > 0):
                raise ValueError(f"the mass of `{name}` must be a positive number of kg, got {kg}")
        densities = dict(densities or {})
        for name, value in densities.items():
            if not (usable(value, scale=True) and value > 0):
                raise ValueError(f"the density of `{name}` must be a positive number, got {value}")
        return cls(density, masses, densities, total_mass)


def mass_for(link: LinkAnalysis, choice: MassChoice, volume: float) -> tuple[float | None, str]:
    """The link's mass and where it comes from; ``None`` for a share of ``total_mass``."""
    from inertia_kit.analysis.declared import declared_mass

    if link.name in choice.masses:
        return choice.masses[link.name], "given mass"
    declared = declared_mass(link.link)
    if declared is not None:
        return declared, "declared mass"
    if link.name in choice.densities:
        density = choice.densities[link.name]
        return density * volume, f"{density:g} kg/m³ (configured)"
    if choice.total_mass is not None:
        return None, "--total-mass"
    return choice.density * volume, f"{choice.density:g} kg/m³"


def share_total(
    analysis: RobotAnalysis, chosen: dict[str, tuple[float | None, str]], total: float
) -> str | None:
    """
    Give the links waiting for a share of ``total`` (kg) the one density that makes the robot
    weigh ``total``: what the other links weigh (declared, kept or given masses) is subtracted
    first. Updates ``chosen``; returns why it cannot (the others already weigh that much).
    """
    from inertia_kit.analysis.declared import declared_mass

    waiting = [name for name, (mass, _) in chosen.items() if mass is None]
    if not waiting:
        return None
    # what the links not waiting weigh: chosen (given, kept, configured) or declared
    others = sum(
        (
            (chosen[link.name][0] if link.name in chosen else declared_mass(link.link)) or 0.0
            for link in analysis.links
        ),
        0.0,
    )
    volume = 0.0
    for name in waiting:
        unit = analysis.by_name[name].geometry.unit
        assert unit is not None
        volume += unit.mass
    remainder = total - others
    if not remainder > 0:
        return (
            f"--total-mass {total:g} kg leaves nothing for it: the other links already weigh "
            f"{others:.6g} kg; give a larger total, or --mass LINK=KG"
        )
    density = remainder / volume
    for name in waiting:
        unit = analysis.by_name[name].geometry.unit
        assert unit is not None
        chosen[name] = (
            density * unit.mass,
            f"--total-mass {total:g} kg ({density:.6g} kg/m³ for the {len(waiting)} links "
            "without a mass)",
        )
    return None
