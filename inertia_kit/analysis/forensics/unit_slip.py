"""
IN063: a unit slip: the tensor in g·m², kg·mm², kg·cm², lb·in², … (or converted the wrong way),
or the mass in grams.

A slip in the tensor's unit scales all six values by one factor; a mass in grams makes the
density 1000 times too high. Unit slips are judged by the density the declared mass gives the
geometry: when it is implausible whichever way, the geometry's scale is in doubt (IN022, IN031),
not the tensor's unit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from inertia_kit.analysis.forensics.candidate import Candidate, Case, Wording, entries
from inertia_kit.analysis.forensics.measure import Metric, symmetric
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.numbers import one_digit
from inertia_kit.physics.tensor_names import DIAGONAL

#: plausible densities, kg/m³ (IN022's defaults): a unit slip is only considered when undoing it
#: leaves one (a density 1e-9 says the mesh is in millimetres, IN031, not the tensor)
DENSITIES = (50.0, 25000.0)
#: a real part (forensics.diagnosis.diagnose_part) is only refused a unit slip when its density
#: says its mass or its geometry's scale is in doubt: a mesh in millimetres gives 1e-9 of the
#: density, a mass cut from 5 kg to 0.01 kg (pybullet's iiwa base) 2 kg/m³; a light camera
#: housing (30 kg/m³) or a dense counterweight is no such doubt
PART_DENSITIES = (10.0, 1e5)

# (factor, unit) for a tensor written in another unit: declared = factor × the right value
UNITS: tuple[tuple[float, str], ...] = (
    (1e3, "g·m²"),
    (1e4, "kg·cm²"),
    (1e6, "kg·mm²"),
    (1e7, "g·cm²"),
    (1e9, "g·mm²"),
    (1.0 / 2.9263965e-4, "lb·in²"),
    (1.0 / 4.2140110e-2, "lb·ft²"),
)
GRAMS = 1e3


@dataclass(frozen=True, eq=False)
class UnitSlip(Candidate):
    """
    The tensor :attr:`factor` times its value in kg·m² (written in :attr:`unit`; below 1, divided
    as if it were in that unit), and the mass :attr:`mass_factor` times its value in kg.
    """

    CODE: ClassVar[str] = "IN063"

    factor: float
    unit: str
    mass_factor: float

    def word(self, case: Case) -> Wording:
        declared, corrected = case.declared, self.corrected.inertia
        factor, mass_factor = self.factor, self.mass_factor
        i = int(np.argmax(np.diag(declared.inertia)))
        parts = []
        if mass_factor != 1.0:
            parts.append(f"the mass {fmt(declared.mass, 5)} is in grams")
        if factor > 1.0:
            parts.append(f"the tensor is in {self.unit}, not kg·m²")
        elif factor < 1.0:
            parts.append(
                f"the tensor was divided by {fmt(1 / factor, 5)} as if it were in {self.unit}"
            )
        summary = "a unit slip: " + " and ".join(parts)
        # the message: the same in fewer words
        short = []
        if mass_factor != 1.0:
            short.append(f"mass {fmt(declared.mass, 5)} in grams")
        if factor > 1.0:
            short.append(f"inertia in {self.unit}, not kg·m²")
        elif factor < 1.0:
            short.append(f"inertia divided by {fmt(1 / factor, 3)} as if in {self.unit}")
        claim = "unit slip: " + " and ".join(short)
        detail = (
            f"{DIAGONAL[i]} {fmt(declared.inertia[i, i], 5)} is {fmt(factor * mass_factor, 5)} "
            f"times the {fmt(case.expected.inertia[i, i], 4)} the {case.geometry} gives; "
            f"converted it is {fmt(corrected[i, i], 4)} (all six match {self.within})"
        )
        todo = []
        if mass_factor != 1.0:
            todo.append(f"write the mass in kg ({fmt(self.corrected.mass, 5)})")
        if factor != 1.0:
            todo.append(f"divide the tensor by {fmt(factor, 5)} ({entries(corrected)})")
        data = {"factor": factor, "unit": self.unit, "mass_factor": mass_factor}
        return Wording(summary, detail, " and ".join(todo), data, claim)


def search(
    case: Case,
    volume: float | None,
    tolerance: float = math.inf,
    plausible: tuple[float, float] = DENSITIES,
) -> list[UnitSlip]:
    """
    Every unit conversion of the tensor (and of the mass, when its density says grams) whose
    deviation from the geometry's is not above ``tolerance``; none when the density the
    declared mass gives the geometry is outside ``plausible`` (kg/m³: the geometry's scale is
    then in doubt, not the tensor's unit).
    """
    declared = case.declared
    moments = np.linalg.eigvalsh(symmetric(declared.inertia))
    if moments[-1] - moments[0] <= 1e-9 * moments[-1] and one_digit(float(moments[-1])):
        # ixx = iyy = izz = 1 on a sphere or a cube is a placeholder (IN013); that a power of
        # ten relates it to the geometry's tensor is a coincidence of round numbers
        return []
    mass_factors = [1.0]
    if volume is not None and volume > 0:
        low, high = DENSITIES
        density = declared.mass / volume
        if density > high and low <= density / GRAMS <= high:
            mass_factors = [GRAMS]
        elif not plausible[0] <= density <= plausible[1]:
            return []  # the geometry's scale is in doubt (IN022, IN031): no unit to blame
    found = []
    for mass_factor in mass_factors:
        mass = declared.mass / mass_factor
        # the case's metric is the one for the declared mass (x / 1.0 is x, bit for bit)
        metric = case.metric if mass_factor == 1.0 else Metric(case.expected.inertia / mass_factor)
        options = [(1.0, "kg·m²")] if mass_factor != 1.0 else []
        options += [(f, u) for f, u in UNITS] + [(1.0 / f, u) for f, u in UNITS]
        factors = np.array([factor for factor, _ in options])
        # every conversion at once, each the declared tensor divided by its factor
        tensors = declared.inertia / factors[:, None, None]
        residuals = metric(tensors)
        for (factor, unit), inertia, residual in zip(options, tensors, residuals, strict=True):
            if residual > tolerance:
                continue  # cannot be chosen
            corrected = MassProperties(mass, declared.com, inertia)
            found.append(UnitSlip(0, corrected, float(residual), factor, unit, mass_factor))
    return found
