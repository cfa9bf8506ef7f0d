"""IN065 twin-links-disagree: left/right twins whose geometry mirrors but whose values do not."""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator

import numpy as np

from inertia_kit.analysis.fault import at_fault, departure
from inertia_kit.analysis.forensics.measure import MARGIN, RULE_MARGINS
from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
from inertia_kit.analysis.twins import (
    COM_TOLERANCE,
    MASS_TOLERANCE,
    TENSOR_TOLERANCE,
    Disagreement,
    Twins,
    compare,
    twins,
)
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt, vector_text

CODE = "IN065"
NAME = "twin-links-disagree"
SEVERITY = Severity.WARNING
SCOPE = "robot"
SUMMARY = (
    "left/right twin links whose geometry mirrors but whose mass, centre of mass or inertia "
    "(products whose sign should flip) do not"
)

_PRODUCTS = ("ixy", "ixz", "iyz")
# a message longer than this drops its numbers (they are in the detail)
LONG = 100


def _same(a: float, b: float, scale: float) -> bool:
    return abs(a - b) <= 1e-6 * max(abs(a), abs(b), scale * 1e-9)


def _values(d: Disagreement, names: tuple[str, ...], which: dict[str, float]) -> str:
    return ", ".join(f"{n} {fmt(which[n], 4)}" for n in names)


def _parts(d: Disagreement, left: str, right: str) -> list[str]:
    parts = []
    if d.mass_ratio is not None:
        parts.append(
            f"not in mass: {fmt(d.left_mass, 4)} kg and {fmt(d.right_mass, 4)} kg "
            f"(×{fmt(d.mass_ratio, 3)})"
        )
    if d.com_gap is not None:
        parts.append(
            f"not in centre of mass: `{right}` has {vector_text(d.declared_com)} m, mirrored "
            f"from `{left}` {vector_text(d.expected_com)} m, {fmt(d.com_gap, 2)} m apart"
        )
    if d.unflipped:
        names = d.unflipped
        both = all(_same(d.left_tensor[n], d.declared_tensor[n], d.scale) for n in names)
        observed = _values(d, names, d.declared_tensor)
        observed = f"{observed} on both" if both else f"`{right}` has {observed}"
        parts.append(
            f"their products of inertia do not: {observed}; mirrored, `{right}` should have "
            f"{_values(d, names, d.expected_tensor)}"
        )
    others = tuple(n for n in d.tensor_off if n not in d.unflipped)
    if others:
        shown = others[:3]
        scaled = " (at its mass)" if d.mass_ratio is not None else ""
        parts.append(
            f"not in inertia: `{right}` has {_values(d, shown, d.declared_tensor)}; mirrored "
            f"from `{left}`{scaled}, {_values(d, shown, d.expected_tensor)}"
        )
    return parts


def _message(d: Disagreement, left: str, right: str) -> str:
    """
    ``twins `l_hip` and `r_hip` disagree in mass (×1.5) and inertia``: what does not mirror,
    with the mass ratio and the distance between the centres of mass; without them when the
    names are long (the detail has every value).
    """
    counted, bare = [], []
    if d.mass_ratio is not None:
        counted.append(f"mass (×{fmt(d.mass_ratio, 3)})")
        bare.append("mass")
    if d.com_gap is not None:
        counted.append(f"centre of mass ({fmt(d.com_gap, 2)} m)")
        bare.append("centre of mass")
    if d.unflipped or d.tensor_off:
        others = any(n not in d.unflipped for n in d.tensor_off)
        tensor = "inertia" if others else "products of inertia"
        counted.append(tensor)
        bare.append(tensor)
    for what in (counted, bare):
        listed = ", ".join(what[:-1]) + " and " + what[-1] if len(what) > 1 else what[0]
        message = f"twins `{left}` and `{right}` disagree in {listed}"
        if len(message) <= LONG:
            break
    return message


def _turned(twin: Twins) -> Twins:
    """The pair seen from its other side: the left link judged against the right one."""
    motion = None if twin.motion is None else np.linalg.inv(twin.motion)
    return dataclasses.replace(
        twin,
        left=twin.right,
        right=twin.left,
        left_pose=twin.right_pose,
        right_pose=twin.left_pose,
        motion=motion,
    )


#: the least gain over its twin a tensor must show to be the slipped one (module doc of
#: analysis.forensics.diagnosis: the forensic rules' smallest margin)
TENSOR_EVIDENCE = min(MARGIN, *RULE_MARGINS.values())


def _tensor_told(twin: Twins, culprit: LinkAnalysis) -> bool:
    """
    Whether a pair that disagrees only in the tensor (mass and centre of mass mirror) blames
    ``culprit`` with the evidence the forensic rules ask before they name a slipped tensor on
    one link: its values depart from its geometry by the least of their margins (0.6, IN061's)
    more than its twin's. Real CAD links gain up to 0.50 from negated products and 0.55 from
    other axes (``benchmarks/cad_band.py``): with one twin's products negated by a slip, Talos'
    untouched ``arm_left_2_link`` looked 0.50 worse than the slipped one, ANYmal B's ``RF_HIP``
    0.23 worse than its twin turned 90°. A twin whose values are exactly its geometry's leaves
    the margins of analysis.fault to tell, as they tell pairs that disagree in more.
    """
    found = compare(twin)
    if found is None or found.mass_ratio is not None or found.com_gap is not None:
        return True
    other = twin.right if culprit is twin.left else twin.left
    mine, theirs = departure(culprit), departure(other)
    assert mine is not None and theirs is not None  # at_fault judged them
    if theirs.exact:
        return True
    return mine.tensor - theirs.tensor >= TENSOR_EVIDENCE


def _which(twin: Twins) -> tuple[Twins, str, bool]:
    """
    The pair with the twin at fault as ``right`` (the one the finding lands on), the help's
    sentence on which one is right, and whether the file tells: the twin whose values depart
    clearly more from its own geometry (analysis.fault), else the pair as written, the file
    unable to tell (the finding then blames neither link).
    """
    culprit = at_fault(twin.left, twin.right)
    if culprit is not None and not _tensor_told(twin, culprit):
        culprit = None
    if culprit is None:
        return (
            twin,
            (
                "Which twin is right the file cannot say: check both against the CAD part (a "
                "mirrored part's products change sign), then write the right one's mirror into "
                "the other"
            ),
            False,
        )
    if culprit is twin.left:
        twin = _turned(twin)
    good, bad = departure(twin.left), departure(twin.right)
    assert good is not None and bad is not None
    return (
        twin,
        (
            f"`{twin.right.name}`'s values are the ones that depart from the geometry "
            f"({bad.text()}; `{twin.left.name}`'s {good.text()}): check it against the CAD "
            f"part, or write `{twin.left.name}`'s mirror into it"
        ),
        True,
    )


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    _, pairs = twins(robot)
    for pair in pairs:
        if compare(pair) is None:
            continue
        twin, verdict, told = _which(pair)
        found = compare(twin)
        if found is None:
            continue
        left, right = twin.left.name, twin.right.name
        parts = _parts(found, left, right)
        if not parts:
            continue
        axis = twin.plane.axis()
        plane = (
            f"the {'xyz'.replace(axis, '')}-plane of the root frame"
            if axis
            else f"the plane with normal ({vector_text(twin.plane.normal, 3)})"
        )
        flips = ", ".join(n for n in _PRODUCTS if axis in n[1:]) if axis else "the products"
        first, *rest = parts
        detail = f"`{left}` and `{right}` mirror in geometry, but " + first
        if rest:
            detail += "; " + "; ".join(p.removeprefix("not in ") for p in rest)
        source = twin.right.link.inertial.source if twin.right.link.inertial else None
        yield ctx.finding(
            _message(found, left, right),
            source or twin.right.link.source,
            detail=detail,
            # a pair the file cannot judge blames neither twin (their names are in the message)
            link=right if told else None,
            expected={
                "twin": left,
                "mirror_normal": [float(v) for v in twin.plane.normal],
                "mass": found.left_mass,
                "com": [float(v) for v in found.expected_com],
                **{n: found.expected_tensor[n] for n in found.expected_tensor},
                "mass_tolerance": MASS_TOLERANCE,
                "com_tolerance_m": COM_TOLERANCE * twin.size,
                "tensor_tolerance": TENSOR_TOLERANCE * found.scale,
            },
            help=(
                f"the two links' shapes mirror across {plane} (same shapes, volumes, centroids "
                f"and second moments, in the root frame at zero joint positions), so their "
                f"mass properties should too: the same mass, the centre of mass reflected, "
                f"and in axes that correspond the same moments with {flips} of opposite sign; "
                f"the values above are `{left}`'s mirrored into `{right}`'s frame (tolerances: "
                f"{MASS_TOLERANCE:.0%} of the mass, {fmt(COM_TOLERANCE * twin.size, 2)} m, "
                f"{fmt(TENSOR_TOLERANCE * found.scale, 2)} kg·m²). {verdict}"
            ),
        )
