"""
Which links ``inertia-fill`` fills, which it refuses, and the mass each one gets.

Which links (``fix``):

- ``missing`` (default): the links IN001 reports (a link that moves or has collision geometry, or
  the root above moving links, with no mass in its fixed-joint group) that have geometry (one
  without is refused). Massless frames on fixed joints, and fixed links with visual geometry
  only, are left alone.
- ``invalid``: those, and links whose ``<inertial>`` is impossible: incomplete or not numeric
  (IN003/IN004), not a possible rigid body (``MassProperties.validity``), or reported by
  IN010, IN011, or IN020/IN023 as errors; and links whose tensor shows a recognised slip
  (IN060-IN064: about the link origin, flipped product signs, other axes, a unit slip,
  transposed values), which get their declared values with the slip undone
  (:func:`inertia_kit.analysis.forensics.diagnose_link`), not the geometry's.
- ``all``: every link with geometry.

The mass: ``masses[link]`` when given (``--mass``, or configured); else a declared mass that is
finite and positive (kept: it is usually measured or from CAD; the tensor and centre of mass are
recomputed from the geometry for it); else the geometry's volume times the link's configured
density, else the density that makes the robot weigh ``total_mass``, else ``density``. The
centre of mass and tensor are always the geometry's at uniform density (collision shapes, else
visual ones, overlaps counted once).

A link is refused (not filled, with the reason) when its geometry cannot be trusted: a mesh
missing, unreadable, empty or wound inside-out, a mesh that looks authored in other units without
a ``scale`` (IN031), or a shape with bad dimensions.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from inertia_kit.fill.materials import MATERIALS
from inertia_kit.fixes.sites import Target
from inertia_kit.lint.findings import Severity
from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.numbers import usable

if TYPE_CHECKING:
    from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
    from inertia_kit.fill.plan import FillPlan
    from inertia_kit.lint.config import LinkSettings
    from inertia_kit.lint.findings import Finding

FIX_MODES = ("missing", "invalid", "all")

# rules whose findings mean a declared tensor is impossible (``--fix invalid``)
_IMPOSSIBLE = ("IN010", "IN011", "IN020", "IN023")


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
        if material.lower() not in MATERIALS:
            raise ValueError(f"--material: unknown {material!r}; known: {', '.join(MATERIALS)}")
        density = MATERIALS[material.lower()]
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
    The link names (of ``--mass``) that no planned file holds, sorted; none when no file was
    planned (then the files' errors are what to tell).
    """
    if not plans:
        return []
    known = set().union(*(plan.links for plan in plans))
    return sorted(name for name in names if name not in known)


@dataclass(frozen=True)
class MassChoice:
    """Where a filled link's mass comes from; :func:`_mass` reads it in this order."""

    density: float
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


def check_fix(fix: str) -> None:
    """``ValueError`` unless ``fix`` is one of :data:`FIX_MODES`."""
    if fix not in FIX_MODES:
        raise ValueError(f"fix must be one of {', '.join(FIX_MODES)}, got {fix!r}")


# --- the links ------------------------------------------------------------------------------


@dataclass
class Choices:
    """What :func:`choose` decided for a robot's links, in document order."""

    targets: list[Target] = field(default_factory=list)
    refused: list[tuple[str, str]] = field(default_factory=list)  # (link, why)
    notes: list[str] = field(default_factory=list)


def choose(analysis: RobotAnalysis, choice: MassChoice, fix: str) -> Choices:
    """The links of ``analysis`` to fill in mode ``fix``, their values, and the refusals."""
    from inertia_kit.lint.runner import Selection, run_rules

    codes = ("IN001", "IN031") + ((*_IMPOSSIBLE, "IN021") if fix != "missing" else ())
    flagged: dict[str, dict[str, list[Finding]]] = {}
    for finding in run_rules(analysis, Selection(select=codes)):
        if finding.link is not None:
            flagged.setdefault(finding.link, {}).setdefault(finding.code, []).append(finding)

    choices = Choices()
    masses: dict[str, tuple[float | None, str]] = {}  # None: the share of --total-mass
    corrected: dict[str, MassProperties] = {}  # declared values with a known slip undone
    seen: set[str] = set()
    for link in analysis.links:
        if link.name in seen:
            continue  # a duplicate name (IN040): the first one is the one tools use
        seen.add(link.name)
        codes_here = flagged.get(link.name, {})
        if not _targeted(link, codes_here, fix):
            if (
                link.name in choice.masses
                and link.link.inertial is not None
                and link.link.inertial.mass != choice.masses[link.name]
            ):
                choices.notes.append(
                    f"--mass {link.name}: the link has an <inertial>; not replaced "
                    f"(--fix {'all' if fix != 'all' else fix} replaces it)"
                )
            continue
        problem = _refusal(link, codes_here)
        if problem is not None:
            choices.refused.append((link.name, problem))
            continue
        unit = link.geometry.unit
        assert unit is not None  # _refusal checked
        diagnosis = None if fix != "invalid" else _diagnosis(link, choice)
        if diagnosis is not None:
            # a recognised slip (IN06x): the declared values with the slip undone keep what
            # CAD knew about the real part; the geometry's uniform solid would lose it. A
            # centre of mass IN021 rejects is the geometry's (the tensor is about the COM,
            # wherever that is)
            fixed = diagnosis.corrected
            if "IN021" in codes_here:
                fixed = MassProperties(fixed.mass, unit.com, fixed.inertia)
            corrected[link.name] = fixed
            masses[link.name] = (fixed.mass, f"declared, corrected ({diagnosis.code})")
            continue
        masses[link.name] = _mass(link, choice, unit.mass)

    if choice.total_mass is not None:
        problem = _share_total(analysis, masses, choice.total_mass)
        if problem is not None:
            choices.refused.extend((name, problem) for name, (m, _) in masses.items() if m is None)
            masses = {name: (m, b) for name, (m, b) in masses.items() if m is not None}
    for name, (mass, basis) in masses.items():
        link = analysis.by_name[name]
        unit = link.geometry.unit
        assert unit is not None and mass is not None
        properties = corrected.get(name) or unit.with_mass(mass)
        problem = unwritable(properties)
        if problem is not None:
            choices.refused.append((name, problem))
            continue
        choices.targets.append(Target(link, properties, basis))
    return choices


def unwritable(properties: MassProperties) -> str | None:
    """
    Why fill must not write ``properties`` (:func:`~inertia_kit.description.inertial_xml.
    unwritable`: it never writes a number the linter refuses), with what to do, or ``None``.
    """
    from inertia_kit.description.inertial_xml import unwritable as why

    problem = why(properties)
    if problem is None:
        return None
    return (
        f"{problem.replace('its ', 'its computed ', 1)}; check the geometry's dimensions, the "
        "density and the mass, then run again"
    )


def _targeted(link: LinkAnalysis, codes: Mapping[str, list], fix: str) -> bool:
    if "IN001" in codes:
        return True  # needs a mass (refused below when it has no geometry)
    if not link.geometry.solids:
        return False
    if fix == "all":
        return True
    if fix == "missing" or link.link.inertial is None:
        return False
    declared = link.declared
    if declared is None or not declared.validity().ok:
        return True  # incomplete, not numeric, or no possible rigid body
    if any(code in codes for code in ("IN010", "IN011")):
        return True
    # IN020 and IN023 are errors only when the tensor is certainly impossible; a warning (a
    # visual-only basis, an overshoot within rounding) may be a real part: kept
    if any(f.severity >= Severity.ERROR for c in ("IN020", "IN023") for f in codes.get(c, ())):
        return True
    from inertia_kit.analysis.forensics.links import diagnose_link

    return diagnose_link(link) is not None  # a recognised slip (IN06x)


def _diagnosis(link: LinkAnalysis, choice: MassChoice):
    """The IN06x diagnosis whose corrected values ``--fix invalid`` writes (``None`` when the
    link has none, or a mass is given for it: then the geometry's tensor for that mass)."""
    from inertia_kit.analysis.forensics.links import diagnose_link

    if link.name in choice.masses:
        return None
    return diagnose_link(link)


def _refusal(link: LinkAnalysis, codes: Mapping[str, list]) -> str | None:
    """Why the link's geometry cannot give its mass properties, or ``None``."""
    geometry = link.geometry
    if not geometry.solids:
        if link.parent is None:
            return (
                "the robot's base has no mass (IN001) and no <visual> or <collision> geometry "
                "to compute it from: write its <inertial> by hand, or hang the robot from a "
                "`world` link by a fixed joint if its base is fixed"
            )
        return (
            "it has no <visual> or <collision> geometry to compute from: write its <inertial> "
            "by hand, or give it geometry"
        )
    for solid, (kind, message) in geometry.problems:
        what = _shape_name(solid)
        hint = {
            "mesh-not-found": "fix the mesh path (or --package-path)",
            "mesh-unreadable": "re-export the mesh as STL, OBJ or PLY",
            "mesh-empty": "re-export the mesh",
        }.get(kind, "fix the shape")
        return f"its {what}: {kind.replace('-', ' ')}: {message}; {hint}, then run again"
    for solid in geometry.solids:
        if solid.mesh is not None and solid.mesh.inverted:
            return (
                f"its {_shape_name(solid)} is wound inside-out (negative volume, IN033): "
                "re-export it with outward normals, then run again"
            )
    for finding in codes.get("IN031", ()):
        scale = (finding.expected or {}).get("scale")
        suggestion = (
            f'; set scale="{" ".join(f"{v:g}" for v in scale)}" if that is its unit'
            if scale
            else ""
        )
        return f"a mesh looks authored in other units (IN031): {finding.message}{suggestion}"
    if geometry.unit is None or not geometry.unit.mass > 0:
        return "its geometry has no volume"
    return None


def _shape_name(solid) -> str:
    from inertia_kit.analysis.describe import describe_geometry

    return f"{solid.shape.kind} {describe_geometry(solid.shape.geometry)}"


def _mass(link: LinkAnalysis, choice: MassChoice, volume: float) -> tuple[float | None, str]:
    """The link's mass and where it comes from; ``None`` for a share of ``--total-mass``."""
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


def _share_total(
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
