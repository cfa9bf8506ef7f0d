"""
Which fixes ``inertia-fill`` applies, by what they repair (never by rule code), and its options.

``inertia-fill`` runs the rules that offer fixes with its mass inputs and applies the fixes its
mode selects (:mod:`inertia_kit.lint.fixing` finds and places them, as for ``inertia-lint
--fix``; safe and unsafe alike, the user asked):

- ``missing`` (default): links that need a mass (a link that moves or has collision geometry,
  or the root above moving links, with no mass in its fixed-joint group). Massless frames on
  fixed joints, and fixed links with visual geometry only, are left alone.
- ``invalid``: also links whose ``<inertial>`` is impossible (incomplete, not numeric, not a
  possible rigid body, beyond what the geometry allows), and recognised slips, which keep
  their declared values with the slip undone.
- ``all``: also every link that has an ``<inertial>`` and geometry, recomputed (and values the
  rules only doubt). Never a link with no ``<inertial>`` that needs none (frames and helper
  links welded to a body with mass, such as self-collision capsules) unless asked by name.

Links asked for by name (``--link NAME``, ``--mass NAME=KG``) are fixed from the geometry in
every mode. Every link asked for (by the mode or by name) that is not fixed is refused with the
reason: no geometry, a mesh that cannot be trusted, values with no place to be written.

The mass of a link fixed from the geometry: :func:`~inertia_kit.fixes.masses.mass_for`.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from typing import TYPE_CHECKING

from inertia_kit.fill.materials import MATERIALS, canonical_material
from inertia_kit.fixes.masses import MassChoice
from inertia_kit.lint.findings import Repairs
from inertia_kit.physics.numbers import usable

if TYPE_CHECKING:
    from inertia_kit.fill.plan import FillPlan
    from inertia_kit.lint.config import LinkSettings

FIX_MODES = ("missing", "invalid", "all")

#: what each mode's fixes repair; ``all`` also recomputes every link with an <inertial> (and
#: replaces a slip by the geometry's values, as it does every other tensor)
REPAIRS = {
    "missing": frozenset({Repairs.MISSING}),
    "invalid": frozenset({Repairs.MISSING, Repairs.IMPOSSIBLE, Repairs.SLIP}),
    "all": frozenset({Repairs.MISSING, Repairs.IMPOSSIBLE, Repairs.DOUBTFUL}),
}

__all__ = ["FIX_MODES", "REPAIRS", "MassChoice", "check_fix", "density_option"]


# --- the options ----------------------------------------------------------------------------


def density_option(density: float | None, material: str | None, total_mass: float | None) -> float:
    """
    The density ``inertia-fill`` gives links without a mass, from ``--density`` or
    ``--material`` (1000 kg/m³ when neither is given); ``--total-mass`` excludes both.
    ``ValueError`` naming the option for a conflict or a value out of range.
    """
    if material is not None:
        if density is not None:
            raise ValueError("give --density or --material, not both")
        name = canonical_material(material)
        if name is None:
            raise ValueError(
                f"--material: unknown {material!r}; known: {', '.join(MATERIALS)} (in any case, "
                "with spaces or underscores for hyphens; aluminum is aluminium)"
            )
        density = MATERIALS[name]
    if total_mass is not None:
        if density is not None:
            raise ValueError("give --total-mass or --density/--material, not both")
        if not (total_mass > 0 and usable(total_mass, scale=True)):
            raise ValueError(f"--total-mass must be a positive number of kg, got {total_mass}")
    if density is None:
        density = 1000.0
    if not (density > 0 and usable(density, scale=True)):
        raise ValueError(f"--density must be a positive number of kg/m³, got {density}")
    return density


def per_link(
    configured: Mapping[str, LinkSettings], given: Mapping[str, float]
) -> dict[str, dict[str, float]]:
    """
    ``masses`` and ``densities`` for one file: its configuration's ``[links.NAME]`` settings,
    under the masses given on the command line.
    """
    return {
        "masses": {n: v.mass for n, v in configured.items() if v.mass is not None} | dict(given),
        "densities": {n: v.density for n, v in configured.items() if v.density is not None},
    }


def unknown_links(names: Iterable[str], plans: Sequence[FillPlan]) -> list[str]:
    """
    The link names (of ``--mass``, ``--link``) that no planned file holds, sorted; none when
    no file was planned (then the files' errors are what to tell).
    """
    if not plans:
        return []
    known = set().union(*(plan.links for plan in plans))
    return sorted(name for name in names if name not in known)


def check_fix(fix: str) -> None:
    """``ValueError`` unless ``fix`` is one of :data:`FIX_MODES`."""
    if fix not in FIX_MODES:
        raise ValueError(f"fix must be one of {', '.join(FIX_MODES)}, got {fix!r}")
