"""IN068 inertia-for-other-mass: the tensor fits the geometry for another mass than declared."""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np

from inertia_kit.analysis.forensics.links import diagnose_link
from inertia_kit.analysis.forensics.mass_changed import mass_beside_copy, mass_change
from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.numbers import one_digit

CODE = "IN068"
NAME = "inertia-for-other-mass"
SEVERITY = Severity.WARNING
SCOPE = "link"
WEIGHED = True  # judged by what it adds to its lumped body (lint.weighing)
SUMMARY = (
    "the declared tensor is the geometry's for another mass, alike about every axis: the mass "
    "was changed after the tensor was computed"
)
# the explanation replaces the symptom it explains on the same link: far from the geometry
SUPERSEDES = ("IN020",)


def _isotropic_placeholder(tensor: np.ndarray) -> bool:
    """``ixx = iyy = izz = 1`` and the like: IN013's placeholder, not a tensor computed."""
    moments = np.linalg.eigvalsh(tensor)
    return bool(moments[-1] - moments[0] <= 1e-9 * moments[-1] and one_digit(float(moments[-1])))


def _times(factor: float) -> str:
    """``3 times`` or ``1/3 of``: a factor as a message says it."""
    return f"{fmt(factor, 3)} times" if factor > 1 else f"1/{fmt(1 / factor, 3)} of"


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    declared = link.declared
    inertial = link.link.inertial
    if declared is None or inertial is None or not declared.mass > 0:
        return
    if _isotropic_placeholder(declared.inertia) or diagnose_link(link) is not None:
        return  # a placeholder (IN013) or another slip (IN060-IN064) explains it
    found = []
    for basis in link.bases:
        expected = basis.at_mass(declared.mass)
        change = None if expected is None else mass_change(declared, expected)
        if change is None:
            found = []  # either geometry reads the values otherwise: its own scatter hides it
            break
        found.append((basis, change))
    if not found:
        yield from _beside_copy(link, ctx)
        return
    basis, change = found[0]
    relation = _times(change.factor)
    yield ctx.finding(
        f"link `{link.name}`: inertia fits its geometry for {fmt(change.tensor_mass, 3)} kg, "
        f"not the declared {fmt(declared.mass)} kg",
        inertial.mass_source or inertial.source,
        link=link.name,
        detail=f"the tensor is its {basis.describe()}'s for {fmt(change.tensor_mass, 3)} kg, "
        f"not the declared {fmt(declared.mass)} kg: every principal moment is {relation} the "
        f"geometry's at the declared mass (alike within a factor of "
        f"{fmt(math.exp(change.shape), 2)}); the mass was likely changed after the tensor was "
        "computed",
        expected={
            "mass": declared.mass,
            "tensor_mass": change.tensor_mass,
            "factor": change.factor,
            "basis": basis.kind,
        },
        help=f"check the mass: if it is right, multiply the six values by {fmt(change.scaled, 3)} "
        f"(the part's shape kept); if the tensor is, the mass it was computed for is about "
        f"{fmt(change.tensor_mass, 3)} kg",
    )


def _beside_copy(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    """The tensor is another link's of the same shape per kilogram, for its mass (module doc of
    analysis.forensics.mass_changed)."""
    found = mass_beside_copy(link)
    if found is None:
        return
    declared, inertial = link.declared, link.link.inertial
    other = found.other
    assert declared is not None and inertial is not None and other.declared is not None
    from inertia_kit.analysis.forensics.candidate import one_line  # a finding's only

    relation = _times(found.factor)
    masses = f" {fmt(other.declared.mass)} kg, not the declared {fmt(declared.mass)} kg"
    yield ctx.finding(
        one_line(
            f"link `{link.name}`: ",
            f"inertia is `{other.name}`'s, for its{masses}",
            f"inertia is another link's, for its{masses}",
        ),
        inertial.mass_source or inertial.source,
        link=link.name,
        detail=f"its six `<inertia>` values are those of `{other.name}`, whose geometry is the "
        f"same shape per kilogram, but its mass is {relation} `{other.name}`'s "
        f"({fmt(declared.mass)} kg against {fmt(other.declared.mass)} kg): the mass was likely "
        "changed after the tensor was computed",
        expected={
            "mass": declared.mass,
            "tensor_mass": other.declared.mass,
            "factor": found.factor,
            "original": other.name,
        },
        help=f"check the mass: if it is right, multiply the six values by {fmt(found.factor, 3)} "
        f"(the part's shape kept); if the tensor is, the mass is `{other.name}`'s "
        f"{fmt(other.declared.mass)} kg; `{link.name}`'s values depart more from its geometry "
        "than the other's do from theirs",
    )
