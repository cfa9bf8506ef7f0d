"""
``inertia-fill``: write ``<inertial>`` blocks computed from each link's geometry, as text edits on
the original bytes (every byte outside the edited spans stays as it was), then write atomically.

What is filled (``fix``):

- ``missing`` (default): the links IN001 reports (a link that moves or has collision geometry, with
  no mass in its fixed-joint group) that have geometry. Massless frames without geometry, and
  fixed links with visual geometry only, are left alone.
- ``invalid``: those, and links whose ``<inertial>`` is impossible: incomplete or not numeric
  (IN003/IN004), not a possible rigid body (``MassProperties.validity``), or reported by
  IN010, IN011, IN020 (error) or IN023; and links whose tensor shows a recognised slip
  (IN060-IN064: about the link origin, flipped product signs, other axes, a unit slip,
  transposed values), which get their declared values with the slip undone
  (:func:`inertia_kit.analysis.forensics.links.diagnose_link`), not the geometry's.
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

``-o OUT`` (:func:`plan_fill_output`, :func:`write_output`): the filled robot goes to a new file
and the input is not touched. A URDF input gives its own bytes with the edits; a xacro input
gives the fully expanded URDF (two-space indentation, comments dropped), in which links made by
macros or includes are filled too (in place they are refused). Relative mesh paths are resolved,
and written, as in the xacro sources.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from inertia_kit.description.edits import Edit
from inertia_kit.errors import InputError
from inertia_kit.lint.findings import Severity
from inertia_kit.physics.mass import MassProperties

if TYPE_CHECKING:
    from inertia_kit.analysis.links import LinkAnalysis
    from inertia_kit.description.edits import SourceText
    from inertia_kit.description.model import Robot

# kg/m³, typical values for ``--material``: solid parts; 3D-printed parts are lighter at partial
# infill, so pass ``--mass`` when the real mass is known
MATERIALS: dict[str, float] = {
    "steel": 7850.0,
    "aluminium": 2700.0,
    "abs": 1040.0,
    "pla": 1240.0,
    "petg": 1270.0,
    "nylon": 1150.0,
    "carbon-fibre": 1600.0,
    "water": 1000.0,
    "wood": 700.0,
}

FIX_MODES = ("missing", "invalid", "all")

# rules whose findings mean a declared tensor is impossible (``--fix invalid``)
_IMPOSSIBLE = ("IN010", "IN011", "IN020", "IN023")


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

    @property
    def mass_text(self) -> str:
        from inertia_kit.description.inertial_xml import inertial_values

        return inertial_values(self.properties)["mass"]


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
        parts = []
        for source, text in self.changes():
            name = self.path if source is self.source else source.path
            shown = (name, name) if Path(name).is_absolute() else (f"a/{name}", f"b/{name}")
            parts.append(
                "".join(
                    difflib.unified_diff(
                        source.text.splitlines(keepends=True),
                        text.splitlines(keepends=True),
                        *shown,
                    )
                )
            )
        return "".join(parts)


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
      ``missing``, ``invalid`` or ``all`` (see the module docstring).
    densities : mapping
      ``link name -> kg/m³`` for links without a given or kept mass (configuration).
    total_mass : float
      kg of the whole robot: the links that would take ``density`` take instead the one
      density that brings the robot's total mass (declared, kept and given masses included)
      to this; they are refused when the other links already weigh that much.

    Raises
    ------
    InputError
      The file cannot be read or parsed.
    ValueError
      Bad ``density``, ``masses``, ``densities``, ``total_mass`` or ``fix``.
    """
    from inertia_kit.description.edits import read_source
    from inertia_kit.description.loader import load

    choice = _check_options(density, masses, fix, densities, total_mass)
    path = Path(path)
    source = read_source(path)
    robot = load(path, xacro_args=xacro_args, package_paths=package_paths)
    return _plan(str(path), source, robot, choice, fix=fix)


@dataclass(frozen=True)
class MassChoice:
    """Where a filled link's mass comes from; :func:`_mass` reads it in this order."""

    density: float
    masses: Mapping[str, float]
    densities: Mapping[str, float]
    total_mass: float | None


def _check_options(
    density: float,
    masses: Mapping[str, float] | None,
    fix: str,
    densities: Mapping[str, float] | None = None,
    total_mass: float | None = None,
) -> MassChoice:
    if fix not in FIX_MODES:
        raise ValueError(f"fix must be one of {', '.join(FIX_MODES)}, got {fix!r}")
    if not (math.isfinite(density) and density > 0):
        raise ValueError(f"density must be a positive number of kg/m³, got {density}")
    if total_mass is not None and not (math.isfinite(total_mass) and total_mass > 0):
        raise ValueError(f"the total mass must be a positive number of kg, got {total_mass}")
    masses = dict(masses or {})
    for name, kg in masses.items():
        if not (math.isfinite(kg) and kg > 0):
            raise ValueError(f"the mass of `{name}` must be a positive number of kg, got {kg}")
    densities = dict(densities or {})
    for name, value in densities.items():
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"the density of `{name}` must be a positive number, got {value}")
    return MassChoice(density, masses, densities, total_mass)


def _plan(
    path: str,
    source: SourceText,
    robot: Robot,
    choice: MassChoice,
    *,
    fix: str,
    input_path: str | None = None,
) -> FillPlan:
    """The fill plan of ``robot``, whose elements are written literally in ``source``."""
    from inertia_kit.analysis.links import analyse
    from inertia_kit.lint.runner import Selection, run_rules

    names = frozenset(link.name for link in robot.links)
    if robot.fragment:
        return FillPlan(
            path, source, notes=("a xacro fragment without links",), input_path=input_path
        )
    analysis = analyse(robot)
    codes = ("IN001", "IN031") + ((*_IMPOSSIBLE, "IN021") if fix != "missing" else ())
    findings = run_rules(analysis, Selection(select=codes))
    flagged: dict[str, dict[str, list]] = {}
    for finding in findings:
        if finding.link is not None:
            flagged.setdefault(finding.link, {}).setdefault(finding.code, []).append(finding)

    from inertia_kit.fill.sites import Files, Target, place

    targets: list[Target] = []
    bases: dict[str, str] = {}
    chosen: dict[str, tuple[float | None, str]] = {}  # None: the share of --total-mass
    corrected: dict[str, MassProperties] = {}  # declared values with a known slip undone
    refused: list[Refusal] = []
    notes: list[str] = []
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
                notes.append(
                    f"--mass {link.name}: the link has an <inertial>; not replaced "
                    f"(--fix {'all' if fix != 'all' else fix} replaces it)"
                )
            continue
        problem = _refusal(link, codes_here)
        if problem is not None:
            refused.append(Refusal(link.name, problem))
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
            chosen[link.name] = (fixed.mass, f"declared, corrected ({diagnosis.code})")
            continue
        chosen[link.name] = _mass(link, choice, unit.mass)

    if choice.total_mass is not None:
        problem = _share_total(analysis, chosen, choice.total_mass)
        if problem is not None:
            refused.extend(Refusal(name, problem) for name, (m, b) in chosen.items() if m is None)
            chosen = {name: (m, b) for name, (m, b) in chosen.items() if m is not None}
    for name, (mass, basis) in chosen.items():
        link = analysis.by_name[name]
        unit = link.geometry.unit
        assert unit is not None and mass is not None
        bases[name] = basis
        properties = corrected.get(name) or unit.with_mass(mass)
        targets.append(Target(link, properties))

    files = Files.for_input(source.path)
    files.add(source)
    placements = place(targets, analysis.links, files)
    fills: list[LinkFill] = []
    for target in targets:
        placement = placements[target.name]
        if placement.problem is not None:
            refused.append(
                Refusal(
                    target.name,
                    f"{placement.problem}; paste the block below there, or make the macro "
                    "take the values as parameters",
                    _paste_block(target.properties),
                )
            )
            continue
        replaced = target.link.link.inertial is not None
        fills.append(
            LinkFill(target.name, target.properties, bases[target.name], replaced, placement.edits)
        )
    main = str(Path(source.path).resolve())
    others = tuple(s for p, s in files.sources.items() if p != main)
    return FillPlan(
        path,
        source,
        tuple(fills),
        tuple(refused),
        tuple(notes),
        names,
        input_path=input_path,
        others=others,
    )


def _paste_block(properties: MassProperties) -> str:
    from inertia_kit.description.inertial_xml import inertial_block

    return inertial_block(properties, indent="  ", level=0)


def apply(plan: FillPlan) -> bool:
    """
    Write the plan's edits, each file atomically; returns whether a file was written (only
    when bytes change). Raises ``InputError`` for a read-only file or one changed since
    planning; every file is checked before any is written, so a plan spanning several xacro
    files is not left half-applied.
    """
    from inertia_kit.description.edits import write_all_atomic

    return write_all_atomic(
        [(source.path, source.encode(text), source.original) for source, text in plan.changes()]
    )


def plan_fill_output(
    path: str | Path,
    output: str | Path,
    *,
    density: float = 1000.0,
    masses: Mapping[str, float] | None = None,
    fix: str = "missing",
    package_paths: Sequence[str | Path] = (),
    xacro_args: Mapping[str, str] | None = None,
    densities: Mapping[str, float] | None = None,
    total_mass: float | None = None,
) -> FillPlan:
    """
    Plan filling ``path`` into a new file ``output`` (``inertia-fill -o``); nothing is written
    (:func:`write_output` writes). The plan's ``source`` is what gets filled: the input's bytes
    for a URDF file, the fully expanded URDF for a xacro file (so links produced by macros or
    includes can be filled too); its ``path`` is ``output``, its ``input_path`` is ``path``.

    Raises ``InputError`` as :func:`plan_fill`, for a xacro fragment (no robot to write), and
    when ``output`` is ``path`` itself.
    """
    import dataclasses

    from inertia_kit.description.edits import SourceText
    from inertia_kit.description.loader import needs_expansion
    from inertia_kit.description.safexml import read_bounded

    choice = _check_options(density, masses, fix, densities, total_mass)
    path, output = Path(path), Path(output)
    if output.exists() and path.exists() and output.resolve() == path.resolve():
        raise InputError("-o names the input file itself; give another output file", path)
    data = read_bounded(path)
    if not needs_expansion(data):
        # a URDF file: its own bytes, edited (offsets into them), written elsewhere
        plan = plan_fill(
            path,
            density=density,
            masses=masses,
            fix=fix,
            package_paths=package_paths,
            densities=densities,
            total_mass=total_mass,
        )
        if "a xacro fragment without links" in plan.notes:
            raise InputError("a xacro fragment without links: no robot to write", path)
        return dataclasses.replace(plan, path=str(output), input_path=str(path))
    text, robot = _expanded(path, output, package_paths, xacro_args)
    source = SourceText(str(output), text.encode("utf-8"), text, "utf-8", b"")
    return _plan(str(output), source, robot, choice, fix=fix, input_path=str(path))


def write_output(plan: FillPlan) -> bool:
    """
    Write ``plan``'s filled text to its ``path`` (a plan from :func:`plan_fill_output`),
    atomically, creating the file if need be; an existing file keeps its permission bits and
    is left alone when it already holds these bytes. Returns whether the file was written;
    ``InputError`` for a folder, a missing folder or a read-only file.
    """
    from inertia_kit.description.edits import write_atomic

    if plan.source is None:
        return False
    return write_atomic(plan.path, plan.new_bytes, create=True)


def _expanded(
    path: Path,
    output: Path,
    package_paths: Sequence[str | Path],
    xacro_args: Mapping[str, str] | None,
) -> tuple[str, Robot]:
    """The expanded URDF of the xacro file ``path`` as text (indented two spaces, with a
    comment naming its source), and its model with the lines of that text; meshes and
    packages resolve as from ``path``."""
    import copy

    from lxml import etree

    from inertia_kit.description import model
    from inertia_kit.description.loader import Builder, parse_xml, start_tag_positions
    from inertia_kit.description.packages import PackageResolver
    from inertia_kit.description.xacro_expand import expand

    resolver = PackageResolver(package_paths=tuple(package_paths), start=path)
    expanded = expand(path, args=dict(xacro_args or {}), resolver=resolver)
    if expanded.fragment:
        raise InputError("a xacro fragment without links: no robot to write", path)
    root = copy.deepcopy(expanded.root)
    for element in root.iter():
        if element.text is not None and not element.text.strip():
            element.text = None
        if element.tail is not None and not element.tail.strip():
            element.tail = None
    etree.indent(root, space="  ")
    comment = f"generated by inertia-fill from {path.name}: edit that file, not this one"
    body = etree.tostring(root, encoding="unicode")
    text = f'<?xml version="1.0" encoding="utf-8"?>\n<!-- {comment} -->\n{body}\n'
    data = text.encode("utf-8")
    tree = parse_xml(data, output)
    positions = start_tag_positions(data, tree) or {}
    # the same elements in the same order: where each came from in the xacro sources
    origins = dict(zip(tree.iter(etree.Element), expanded.root.iter(etree.Element), strict=True))

    def source_of(element: etree._Element) -> model.Source:
        parent = element.getparent()
        if parent is not None and parent.tag == "geometry":
            # relative mesh paths resolve from the file that wrote them, as for the xacro
            return expanded.source_of(origins[element])
        line, column = positions.get(element, (element.sourceline, None))
        return model.Source(str(output), line, column)

    robot = Builder(path, source_of, resolver, tuple(expanded.files)).robot(tree)
    return text, robot


# --- which links, what mass ----------------------------------------------------------------


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
    if any(code in codes for code in ("IN010", "IN011", "IN023")):
        return True
    if any(f.severity >= Severity.ERROR for f in codes.get("IN020", ())):
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


def _share_total(analysis, chosen: dict[str, tuple[float | None, str]], total: float) -> str | None:
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
