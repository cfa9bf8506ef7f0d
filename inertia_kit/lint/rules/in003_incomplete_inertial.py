"""IN003 incomplete-inertial: an ``<inertial>`` without ``<mass>``/``<inertia>`` or a value."""

from __future__ import annotations

from collections.abc import Iterator

from inertia_kit.analysis.expected import geometry_tensor
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.lint.findings import Finding, FixRule, Repairs, Safety, Severity
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.tensor_names import DIAGONAL, TENSOR

CODE = "IN003"
NAME = "incomplete-inertial"
SEVERITY = Severity.ERROR
SCOPE = "link"
FIX = FixRule(
    "geometry", Safety.UNSAFE, Repairs.IMPOSSIBLE, "replace the <inertial> with its geometry's"
)
SUMMARY = "`<inertial>` without `<mass>` or `<inertia>`, or an `<inertia>` attribute missing"

DENSITY = 1000.0  # kg/m³ for the expected values when the mass is missing too
SHOWN = 2  # missing attributes the message names; more are counted (the detail names them)


def _engines(missing_mass: bool, missing_inertia: bool, absent: list[str]) -> str:
    """What the parsers do with what is missing (measured; see the rule's document)."""
    refuse = "ROS (urdfdom), Gazebo and MuJoCo refuse the file"
    if missing_mass or missing_inertia or any(a in DIAGONAL for a in absent):
        refuse = "ROS (urdfdom), Gazebo, MuJoCo and PyBullet refuse the file"
    readers = []
    if missing_mass:
        readers.append("Drake reads mass 0")
    if missing_inertia:
        readers.append("Drake reads a zero tensor")
    elif absent:
        diagonal = [a for a in absent if a in DIAGONAL]
        readers.append(f"Drake reads {'/'.join(absent)} as 0")
        if diagonal:
            readers.append(f"yourdfpy {'/'.join(diagonal)} as 1.0")
        else:
            readers.append("PyBullet as 0")
    return refuse + (", " + ", ".join(readers) if readers else "")


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    inertial = link.link.inertial
    if inertial is None:
        return
    missing_mass_element = inertial.mass_source is None
    missing_mass = inertial.mass is None
    missing_inertia = inertial.inertia_source is None
    values = inertial.tensor_values()
    absent = [] if missing_inertia else [name for name, v in values.items() if v is None]
    if not (missing_mass or missing_inertia or absent):
        return
    parts = []  # the message's words: what is missing
    listed = ""  # the detail's: every attribute missing, when the message only counts them
    if missing_mass_element:
        parts.append("no `<mass>`")
    elif missing_mass:
        parts.append("a `<mass>` without `value`")
    if missing_inertia:
        parts.append("no `<inertia>`")
    elif absent:
        names = ", ".join(f"`{a}`" for a in absent)
        if len(absent) > SHOWN:
            parts.append(f"an `<inertia>` without {len(absent)} of its 6 values")
            listed = f"the `<inertia>` has no {names}; "
        else:
            parts.append(f"an `<inertia>` without {names}")
    # the most specific element that holds every problem
    if missing_mass_element or missing_inertia or (missing_mass and absent):
        source = inertial.source
    elif missing_mass:
        source = inertial.mass_source
    else:
        source = inertial.inertia_source
    mass = inertial.mass if isinstance(inertial.mass, float) and inertial.mass > 0 else None
    geometry = link.geometry
    payload: dict[str, float] | None = None
    basis = ""
    if geometry.unit is not None and geometry.volume > 0:
        at = mass if mass is not None else DENSITY * geometry.volume
        written = geometry_tensor(link, at)
        if written is not None:
            payload = {**written.fields, "mass": at}
            if mass is None:
                payload["density"] = DENSITY
                how = f"at 1000 kg/m³ holds {fmt(at, 4)} kg with"
            else:
                how = f"with the declared {fmt(mass)} kg gives"
            # only the missing attributes, when the rest of the <inertial> is there
            wanted = [] if missing_inertia or missing_mass else [a for a in TENSOR if a in absent]
            basis = f"; its {geometry.describe()} {how} {written.text(wanted or None)}"
    yield ctx.finding(
        f"link `{link.name}`: `<inertial>` has {' and '.join(parts)}",
        source,
        link=link.name,
        expected=payload,
        detail=f"{listed}{_engines(missing_mass, missing_inertia, absent)}{basis}",
        help="write all of `<mass value>` and `<inertia ixx ixy ixz iyy iyz izz>` (products "
        "of inertia too, 0 when they are), or remove the `<inertial>` of a massless frame; "
        "`inertia-fill --fix invalid` computes the values from the geometry",
    )
