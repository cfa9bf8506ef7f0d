"""IN013 placeholder-inertia: a made-up tensor (copied between shapes, or isotropic)."""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Iterator

import numpy as np
from numpy.typing import NDArray

from inertia_kit.analysis.copies import block, six_values
from inertia_kit.analysis.copies import copies as whole_copies
from inertia_kit.analysis.expected import base_tensors, basis_text, geometry_tensor
from inertia_kit.analysis.fault import COM_MARGIN, PLAUSIBLE_COM, TENSOR_MARGIN, departure
from inertia_kit.analysis.forensics.mass_changed import mass_beside_copy
from inertia_kit.analysis.forensics.measure import BAND, TOLERANCE, LogMetric
from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
from inertia_kit.analysis.tensors import compare_tensors
from inertia_kit.engines.lumping import lumped, positive_mass
from inertia_kit.lint.findings import Finding, FixRule, Repairs, Safety, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt, tensor_text
from inertia_kit.physics.numbers import one_digit

CODE = "IN013"
NAME = "placeholder-inertia"
SEVERITY = Severity.WARNING
SCOPE = "robot"
WEIGHED = True  # judged by what it adds to its lumped body (lint.weighing)
FIX = FixRule(
    "geometry",
    Safety.UNSAFE,
    Repairs.DOUBTFUL,
    "replace the placeholder with its geometry's tensor",
)
SUMMARY = (
    "a made-up tensor: the same six values on links of clearly different geometry, or an "
    "isotropic tensor on clearly anisotropic geometry"
)
OPTIONS = (
    # 2.0: a box of sides 1 : 1 : 1.7 already has principal moments 1 : 2, and an isotropic
    # value can then be no closer than a factor √2 to both; see rules/IN013-placeholder-inertia.md
    Option(
        "anisotropy",
        float,
        2.0,
        "the geometry's largest to smallest principal moment above which an isotropic tensor "
        "is flagged",
    ),
    Option(
        "copy_factor",
        float,
        2.0,
        "how far apart two links' geometries must be before identical values on them are flagged",
    ),
    Option(
        "error_factor",
        float,
        10.0,
        "an error for an isotropic placeholder this many times off its collision geometry's "
        "moment about some axis",
        minimum=1.0,
    ),
)

ISOTROPIC_RTOL = 1e-6  # ixx = iyy = izz to this relative precision counts as equal
NEGLIGIBLE = 0.01  # a welded link's tensor below this share of its body's moments cannot matter
#: a link owns copied values only when they fit its geometry as a real part's do: within a
#: factor of 2.5 about every axis (measure.BAND, between the 95th and 99th percentile of the
#: real CAD links the linter is silent on)
OWNER_FIT = math.exp(BAND)


def _spread(a: NDArray[np.float64], b: NDArray[np.float64]) -> float:
    """How far apart two shapes are: the largest ratio between matching principal moments."""
    p, q = np.linalg.eigvalsh(a), np.linalg.eigvalsh(b)
    if not (p.min() > 0 and q.min() > 0):
        return float("inf")
    return float(np.max(np.maximum(p / q, q / p)))


def _negligible(robot: RobotAnalysis, link: LinkAnalysis, geometry: NDArray[np.float64]) -> bool:
    """
    Whether the link is welded into a body so much larger that neither its declared tensor nor
    its geometry's can change that body's moments by more than ``NEGLIGIBLE``: a dummy frame
    whose placeholder cannot matter.
    """
    if len(robot.group_of(link.name)) < 2:
        return False
    body = lumped(robot, link.name)
    declared = positive_mass(link)
    if body is None or declared is None:
        return False
    own = max(
        float(np.abs(declared.principal_moments).max()), float(np.linalg.eigvalsh(geometry).max())
    )
    return own < NEGLIGIBLE * float(body.principal_moments[0])


#: more distinct bodies than this sharing six values are not counted against each other (a
#: quadratic count); the best fit is then the original
MAX_DISTINCT = 64


def _agreement(
    tensors: list[NDArray[np.float64]], owners: list[int], factor: float
) -> dict[int, int]:
    """
    For each of ``owners``, how many of ``tensors`` are the same body within ``factor``
    (:func:`_spread`). Equal principal moments are counted once with their number, so that
    5000 identical links cost one comparison; beyond :data:`MAX_DISTINCT` distinct bodies
    nothing is counted (every owner 0).
    """
    keys = [tuple(f"{v:.9g}" for v in np.linalg.eigvalsh(t)) for t in tensors]
    distinct: dict[tuple, tuple[NDArray[np.float64], int]] = {}
    for key, tensor in zip(keys, tensors, strict=True):
        first, count = distinct.get(key, (tensor, 0))
        distinct[key] = (first, count + 1)
    if len(distinct) > MAX_DISTINCT:
        return dict.fromkeys(owners, 0)
    return {
        i: sum(n for t, n in distinct.values() if _spread(tensors[i], t) <= factor) for i in owners
    }


def _least_closeness(declared: NDArray[np.float64], link: LinkAnalysis, mass: float) -> float:
    """How close the values come to any of the link's geometries (compare_tensors' factor)."""
    found = [compare_tensors(declared, w.tensor) for w in base_tensors(link, mass)]
    return min((c.factor for c in found if c is not None), default=math.inf)


def _carried_offsets(members: list[LinkAnalysis]) -> list[float]:
    """
    For each link, its centre of mass's offset from its centroid over its size when its whole
    block (mass and centre of mass too) is another's of ``members``, else 0: a centre of mass
    copied along with the tensor tells which part the block was made for (Baxter's hand given
    a wrist's block: its tensor a factor of 1.3 from the hand's, its centre of mass half the
    hand's size off it), a link's own one tells nothing about a shared tensor.
    """
    blocks = [block(m) for m in members]
    counts = Counter(blocks)
    offsets = []
    for member, key in zip(members, blocks, strict=True):
        found = departure(member) if counts[key] > 1 else None
        offsets.append(0.0 if found is None else found.com)
    return offsets


def _isotropic(values: tuple[float, ...]) -> bool:
    ixx, ixy, ixz, iyy, iyz, izz = values
    return (
        ixx > 0
        and ixy == ixz == iyz == 0
        and abs(iyy - ixx) <= ISOTROPIC_RTOL * ixx
        and abs(izz - ixx) <= ISOTROPIC_RTOL * ixx
    )


def _written(values: tuple[float, ...]) -> NDArray[np.float64]:
    ixx, ixy, ixz, iyy, iyz, izz = values
    return np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    anisotropy = float(ctx.option("anisotropy"))
    copy_factor = float(ctx.option("copy_factor"))
    error_factor = float(ctx.option("error_factor"))
    flagged: set[str] = set()
    copies: dict[tuple[float, ...], list[LinkAnalysis]] = {}
    for link in robot.links:
        values = six_values(link)
        if values is None:
            continue
        copies.setdefault(values, []).append(link)
        if not _isotropic(values):
            continue
        declared = positive_mass(link)
        assert declared is not None
        expected = link.expected
        if expected is None:
            continue
        principal = expected.principal_moments
        if not principal[0] > 0:
            continue
        written = geometry_tensor(link, declared.mass)
        if written is None:
            continue
        anisotropic = principal[2] / principal[0] > anisotropy
        # a sphere's, a cube's or a near-cube's isotropic tensor is right, unless it is a
        # one-digit value (1, 0.001) farther from its geometry's than any real part's tensor
        # lands (the forensics' band): ixx = iyy = izz = 1 on a 60 g foot
        far = one_digit(values[0]) and LogMetric(written.tensor)(_written(values)) > BAND
        if not (anisotropic or far) or _negligible(robot, link, written.tensor):
            continue
        inertial = link.link.inertial
        assert inertial is not None
        flagged.add(link.name)
        ratio = values[0] / float(np.mean(np.diag(written.tensor)))
        why = (
            f"has principal moments in the ratio 1 : {fmt(principal[1] / principal[0], 3)} : "
            f"{fmt(principal[2] / principal[0], 3)}"
            if anisotropic
            else f"is near-isotropic but gives {fmt(1 / ratio, 3)} times more"
            if ratio < 1
            else f"is near-isotropic but gives 1/{fmt(ratio, 3)} of that"
        )
        off = float(np.max(np.abs(np.log(values[0] / principal))))
        severe = link.geometry.kind == "collision" and off > math.log(error_factor)
        notes = ""
        if severe:
            notes += (
                f"; {fmt(math.exp(off), 3)} times off about one axis, beyond any real part "
                "(0.6 to 1.7 times its solid's)"
            )
        if robot.robot.format == "mjcf":
            notes += (
                "; in an MJCF file also what MuJoCo's balanceinertia makes of a tensor that "
                "breaks the triangle inequality (a URDF compiled and saved as MJCF keeps it)"
            )
        yield ctx.finding(
            f"link `{link.name}`: ixx = iyy = izz = {fmt(values[0], 4)} kg·m² is an isotropic "
            "placeholder",
            inertial.inertia_source or inertial.source,
            link=link.name,
            expected={"mass": declared.mass, **written.fields},
            detail=f"with no products of inertia; its {link.geometry.describe()} {why}: with the "
            f"declared {fmt(declared.mass)} kg it gives {written.text()}{notes}",
            severity=Severity.ERROR if severe else None,
            help="replace the placeholder with the part's tensor about its centre of mass (from "
            "CAD, or `inertia-fill --fix invalid` from the geometry)",
        )
    # a whole block that fits its owner and is named copied is IN066's (analysis.copies)
    named = {c.link.name for c in whole_copies(robot)}
    for values, members in copies.items():
        members = [m for m in members if m.name not in named]
        if len({m.name for m in members}) < 2:
            continue
        declared_tensor = _written(values)
        candidates = []
        for member in members:
            declared = positive_mass(member)
            assert declared is not None
            written = geometry_tensor(member, declared.mass)
            if written is not None:
                candidates.append((member, declared.mass, written))
        if len(candidates) < 2:
            continue
        comparisons = [compare_tensors(declared_tensor, w.tensor) for _, _, w in candidates]
        if any(c is None for c in comparisons):
            continue  # not positive definite: IN010/IN011's
        closeness = [c.factor for c in comparisons if c is not None]
        offsets = _carried_offsets([m for m, _, _ in candidates])
        # the original is the link most others agree with (identical parts outvote the one
        # whose mass slipped), among those the values fit as a real part's fit its geometry
        # (with the centre of mass too, when it came along); when they fit none so (a
        # placeholder on every link), the one they fit best
        owners = [
            i for i, c in enumerate(closeness) if c <= OWNER_FIT and offsets[i] <= PLAUSIBLE_COM
        ]
        agree = _agreement(
            [w.tensor for _, _, w in candidates], list(range(len(candidates))), copy_factor
        )
        if owners:
            index = min(owners, key=lambda i: (-agree[i], closeness[i]))
        else:
            index = min(
                range(len(candidates)),
                key=lambda i: math.log(closeness[i]) + offsets[i] * TENSOR_MARGIN / COM_MARGIN,
            )
        original, original_mass, original_written = candidates[index]
        for i, (member, mass, written) in enumerate(candidates):
            if member is original or member.name in flagged:
                continue
            # the copy is the link outvoted by identical parts, or the one the values fit
            # clearly worse than the original and worse than a real part's fit its geometry,
            # unless they are the original's exactly (analysis.fault): UR5e's two wrists share
            # a tensor, and with one's mass tripled both still fit alike, so neither is named
            # ... on each of its geometries: a crude collision shape standing in for the part
            # (GR3's upper arm roll link, a 5 cm sphere) does not make its own values a copy
            fit, best = _least_closeness(declared_tensor, member, mass), closeness[index]
            outvoted = agree[i] < agree[index]
            beyond = fit > OWNER_FIT or best <= 1 + TOLERANCE
            if not (outvoted or (beyond and math.log(fit / best) > TENSOR_MARGIN)):
                continue
            # principal moments at each link's mass: a mirrored or turned copy of the same
            # part is the same body, and a part whose mass slipped is not
            apart = _spread(written.tensor, original_written.tensor)
            if apart <= copy_factor or _negligible(robot, member, written.tensor):
                continue
            if mass_beside_copy(member) is not None:
                continue  # the tensor kept while the mass changed: IN068's
            inertial = member.link.inertial
            assert inertial is not None
            flagged.add(member.name)
            shape = _spread(written.tensor / mass, original_written.tensor / original_mass)
            why = (
                f"the two shapes' principal moments differ by a factor of {fmt(apart, 3)}"
                if shape > copy_factor
                else f"it declares {fmt(mass / original_mass, 3)} times `{original.name}`'s "
                f"mass on a shape alike per kilogram (within a factor of {fmt(shape, 3)}): at "
                f"their masses the principal moments differ by a factor of {fmt(apart, 3)}"
            )
            yield ctx.finding(
                f"link `{member.name}`: `<inertia>` copied from `{original.name}`, a different "
                f"body (×{fmt(apart, 3)})",
                inertial.inertia_source or inertial.source,
                link=member.name,
                expected={"mass": mass, **written.fields},
                detail=f"its six `<inertia>` values are those of link `{original.name}` "
                f"({tensor_text(declared_tensor)} kg·m²), but {why}: "
                f"{basis_text(member, mass)} {written.text()}",
                help="compute this link's own tensor (from CAD, or `inertia-fill --fix invalid` "
                "from the geometry) instead of copying another link's"
                + ("" if shape > copy_factor else "; or check its mass"),
            )
