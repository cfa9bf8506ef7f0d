"""
How firm a hard bound is: whether a declared moment beyond what the link's geometry allows
(:func:`~inertia_kit.analysis.bounds.moment_excess`) is certainly impossible (an error for IN020,
IN023 and the forensic rules) or only probably wrong (a warning).

A bound is only as firm as what it rests on:

- **the written numbers**: a radius written ``0.035`` may be anything from 0.0345 to 0.0355 m.
  Each number the bound scales with (the mass, the shapes' sizes, the six ``<inertia>`` values)
  is taken at the end of its rounding interval that favours the declared tensor: half a unit in
  its last written digit (from its shortest decimal form, so ``0.0350`` counts as ``0.035``), at
  most :data:`ROUNDING_CAP` of it (a one-digit ``0.05`` is a chosen value more often than a
  rounded 0.054);
- **the facets of a mesh**: its vertices lie on the part's surface, its flat triangles inside it
  (a 16-sided cylinder's faces sit 2 % inside the circle), so a mesh's box is enlarged by
  :data:`FACETS` about its centre;
- **the kind of geometry**: collision shapes are what the simulator makes contact with, the
  modeller's statement of where the part is; visual geometry alone is often a schematic stand-in
  (a cylinder drawn for a motor rotor), and an open collision mesh (IN032) may not hold the
  whole part. Visual meshes only widen the region (the bound is taken over collision and
  visual geometry together), so they never weaken it.

A declared moment is firmly impossible when it exceeds the bound with every number rounded in its
favour and the meshes' facets allowed for, and the link has collision geometry and no open
collision mesh; on visual geometry alone or with an open collision mesh, only when it exceeds it
more than :data:`GROSS` times.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from decimal import Decimal
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from inertia_kit.analysis.bounds import Hull, Kind, MomentExcess, moment_excess
from inertia_kit.description import model
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.frames import rpy_matrix

if TYPE_CHECKING:
    from inertia_kit.analysis.geometry import Solid
    from inertia_kit.analysis.links import LinkAnalysis
    from inertia_kit.physics.mass import MassProperties

# the most a written number is taken to be rounded by, relative to it
ROUNDING_CAP = 0.05
# how far a mesh's flat facets may lie inside the curved surface of the part, relative to its
# size: the chords of a 16-sided polygon lie 1 - cos(π/16) = 1.9 % inside its circle
FACETS = 0.02
# on geometry that cannot make a verdict firm (visual only, an open collision mesh), a moment
# this many times the bound is impossible all the same: a radius of gyration √10 = 3.2 times
# what the geometry allows is no stand-in's inaccuracy (the placeholder ixx = 1.0 on a small
# link)
GROSS = 10.0
# a collision mesh whose convex hull's volume differs from its open surface's by more than this
# (IN032's default tolerance) may not be the whole part
OPEN = 0.05


def rounding(value: float) -> float:
    """
    Half a unit in the last digit of ``value`` as written (its shortest decimal form), at most
    :data:`ROUNDING_CAP` of it; 0 for 0 and for non-finite values.

    >>> rounding(0.035), rounding(0.000111842)
    (0.0005, 5e-10)
    """
    if not math.isfinite(value) or value == 0:
        return 0.0
    exponent = Decimal(repr(float(value))).normalize().as_tuple().exponent
    assert isinstance(exponent, int)
    return min(0.5 * 10.0**exponent, ROUNDING_CAP * abs(value))


@dataclass(frozen=True)
class Firmness:
    """
    A declared tensor beyond its link's hard bound, and how firm that verdict is.

    Attributes
    ----------
    excess : MomentExcess
      The worst axis against the geometry as written.
    margin : MomentExcess
      The same with every written number rounded in the tensor's favour and the meshes' facets
      allowed for: ``moment`` lowered, ``bound`` raised.
    weak : tuple of str
      Why the geometry cannot make the verdict firm, whatever the numbers (visual geometry
      only, an open mesh); empty when it can.
    rounded : tuple of str
      When they decide the verdict (no ``weak``, within the margin): the written numbers whose
      rounding counts most, at most three, largest first (``cylinder radius 0.035 m``,
      ``mass 0.089 kg``, ``<inertia> values``); else empty.
    facets : tuple of str
      Likewise, the meshes whose facets count (file names).
    centre : str
      For a second moment along a direction, when it decides the verdict: where the declared
      centre of mass lies, in words (its distances to the geometry's two ends); else empty.
    """

    excess: MomentExcess
    margin: MomentExcess
    weak: tuple[str, ...]
    rounded: tuple[str, ...]
    facets: tuple[str, ...]
    centre: str = ""

    @property
    def firm(self) -> bool:
        """
        Beyond the bound whichever way the numbers were rounded, on geometry that holds (or
        more than :data:`GROSS` times beyond it, on any geometry).
        """
        return bool(self.margin.ratio > (GROSS if self.weak else 1.0))

    def why_not(self) -> str | None:
        """Why the verdict is a warning, not an error, in words; ``None`` when it is firm."""
        if self.firm:
            return None
        if self.weak:
            return _listed(self.weak)
        allowances = []
        if self.rounded:
            allowances.append("rounding of the written " + _listed(self.rounded))
        if self.facets:
            allowances.append("the facets of " + _listed(tuple(f"`{n}`" for n in self.facets)))
        if self.centre:
            allowances.append(self.centre)
        over = 100.0 * (self.excess.ratio - 1.0)
        return (
            f"{fmt(over, 2)}% over is within what {' and '.join(allowances) or 'rounding'} can "
            f"explain (the bound then reaches {fmt(self.margin.bound, 4)} kg·m²)"
        )


def _listed(items: tuple[str, ...]) -> str:
    return items[0] if len(items) == 1 else f"{', '.join(items[:-1])} and {items[-1]}"


def firmness(link: LinkAnalysis) -> Firmness | None:
    """
    The firmness of the link's :attr:`~LinkAnalysis.excess` (see the module docstring);
    ``None`` without one.

    Both kinds of bound are weighed (moments about axes, second moments along directions): when
    the excess reported is not firm but the other kind is beyond its bound firmly, that one is
    the verdict (:attr:`Firmness.excess` is then of the other kind than the link's).
    """
    excess = link.excess
    declared = link.declared
    inertial = link.link.inertial
    if excess is None or declared is None or inertial is None:
        return None
    solids = [s for g in (link.collision, link.visual) if g.solids for s in g.solids]
    if not solids or any(s.hull is None for s in solids):
        return None
    written = [s.hull for s in solids]
    grown = Hull.union([_enlarged(s) for s in solids])
    weak = _weak(link)
    margin = _margin(declared, inertial, grown, excess.kind)
    if margin is None:
        return None
    if not margin.ratio > (GROSS if weak else 1.0):
        other: Kind = "along" if excess.kind == "about" else "about"
        beyond = moment_excess(declared, Hull.union(written), other)  # type: ignore[arg-type]
        firm = _margin(declared, inertial, grown, other)
        if beyond is not None and firm is not None and firm.ratio > (GROSS if weak else 1.0):
            excess, margin = beyond, firm
    if weak or margin.ratio > 1.0:
        return Firmness(excess, margin, weak, (), ())  # the allowances decide nothing
    # what each allowance alone takes off the excess, for the message: a size of one shape
    # (the others as written), the mass, the <inertia> values, a mesh's facets
    mass = declared.mass
    shares: dict[str, float] = {}
    for i, solid in enumerate(solids):
        for text, hull in _one_at_a_time(solid):
            hulls = [*written[:i], hull, *written[i + 1 :]]
            alone = moment_excess(declared, Hull.union(hulls), excess.kind)  # type: ignore[arg-type]
            if alone is not None and alone.ratio > 0:
                shares[text] = max(shares.get(text, 0.0), excess.ratio / alone.ratio - 1.0)
    shares[f"mass {fmt(mass)} kg"] = rounding(mass) / mass
    found_moment = margin.moment + _moment_rounding(inertial, margin)
    if found_moment > 0:
        shares["<inertia> values"] = 1.0 - margin.moment / found_moment
    counted = sorted(
        ((share, text) for text, share in shares.items() if share >= 1e-3), reverse=True
    )
    rounded = tuple(t for _, t in counted if not t.startswith("facets "))
    facets = tuple(t.removeprefix("facets ") for _, t in counted if t.startswith("facets "))
    centre = ""
    low, high = excess.sides
    if excess.kind == "along" and (0.5 * (low + high)) ** 2 > (1.0 + 1e-3) * low * high:
        centre = (
            f"a centre of mass off its declared place ({fmt(low, 3)} m and {fmt(high, 3)} m "
            "from the geometry's two ends)"
        )
    return Firmness(excess, margin, weak, rounded[:3], facets, centre)


def _margin(
    declared: MassProperties, inertial: model.Inertial, grown: Hull, kind: Kind
) -> MomentExcess | None:
    """
    The worst axis of ``kind`` on the ``grown`` hull, with the mass rounded up and the moment
    rounded down (the bound raised, the moment lowered: in the tensor's favour).

    Along a direction the bound is also taken whatever the centre of mass: ``m w² / 4`` for a
    hull ``w`` wide along it (Popoviciu; the Bhatia–Davis bound at its largest, the COM
    midway). A CAD export's centre of mass and its meshes often disagree by millimetres, and
    near one end of the geometry the Bhatia–Davis bound moves with the COM as fast as the COM
    moves; an error must not rest on it (a COM outside its geometry is IN021's).
    """
    found = moment_excess(declared, grown, kind)
    if found is None:
        return None
    mass = declared.mass
    bound = found.bound
    if kind == "along":
        bound = mass * (0.5 * sum(found.sides)) ** 2
    raised = bound * (1.0 + rounding(mass) / mass)
    lowered = found.moment - _moment_rounding(inertial, found)
    return dataclasses.replace(found, moment=lowered, bound=raised)


def _weak(link: LinkAnalysis) -> tuple[str, ...]:
    """
    Why the link's geometry cannot make the verdict firm. Only the collision geometry counts:
    the bound is taken over collision and visual geometry together, never tighter than over
    the collision geometry alone, so a visual mesh cannot weaken it.
    """
    if not link.link.collisions:
        return ("its only geometry is visual, often a schematic stand-in for the part",)
    weak: list[str] = []
    for solid in link.collision.solids:
        mesh = solid.mesh
        if mesh is not None and mesh.method == "convex-hull" and mesh.volume_error > OPEN:
            text = (
                f"collision mesh `{Path(mesh.path).name}` is open (IN032), so it may not hold "
                "the whole part"
            )
            if text not in weak:
                weak.append(text)
    return tuple(weak)


_DIMENSIONS = {
    "box": ("size x", "size y", "size z"),
    "cylinder": ("radius", "length"),
    "capsule": ("radius", "length"),
    "sphere": ("radius",),
}


def _primitive(solid: Solid) -> tuple[float, ...] | None:
    part = solid.part
    if part is None or part.kind not in _DIMENSIONS:
        return None
    return tuple(float(v) for v in part.dimensions)


def _grown_part(solid: Solid, sizes: tuple[float, ...]) -> Hull:
    return Hull.of_part(dataclasses.replace(solid.part, dimensions=sizes))  # type: ignore[arg-type]


def _grown_box(solid: Solid) -> Hull:
    """A mesh's envelope (its box, 8 corners in the link frame) enlarged by FACETS."""
    corners = solid.corners
    assert corners is not None
    centre = corners.mean(axis=0)
    return Hull.of_box(centre + (1.0 + FACETS) * (corners - centre))


def _enlarged(solid: Solid) -> Hull:
    """
    A hull containing what the solid may be: a primitive with every size at the top of its
    rounding interval, a mesh's box enlarged by :data:`FACETS`.
    """
    sizes = _primitive(solid)
    if sizes is not None:
        return _grown_part(solid, tuple(v + rounding(v) for v in sizes))
    if solid.part is None and solid.corners is not None:
        return _grown_box(solid)
    assert solid.hull is not None
    return solid.hull


def _one_at_a_time(solid: Solid) -> list[tuple[str, Hull]]:
    """Each allowance of the solid alone, as (words, hull): one size rounded up, or facets."""
    sizes = _primitive(solid)
    if sizes is not None:
        kind = solid.part.kind  # type: ignore[union-attr]
        found = []
        for i, value in enumerate(sizes):
            if rounding(value) > 0:
                grown = (*sizes[:i], value + rounding(value), *sizes[i + 1 :])
                name = _DIMENSIONS[kind][i]
                found.append((f"{kind} {name} {fmt(value)} m", _grown_part(solid, grown)))
        return found
    geometry = solid.shape.geometry
    if solid.part is None and solid.corners is not None and isinstance(geometry, model.Mesh):
        return [(f"facets {Path(geometry.filename).name}", _grown_box(solid))]
    return []


def _moment_rounding(inertial: model.Inertial, excess: MomentExcess) -> float:
    """
    How much the written ``<inertia>`` values' rounding can move the moment of ``excess``: it
    is ``Σᵢⱼ Wᵢⱼ Iᵢⱼ`` (:attr:`MomentExcess.weights`), so each value moves it by its
    weight, in the axes of ``<inertial><origin rpy>``, times its rounding.
    """
    values = inertial.tensor_values()
    if not all(isinstance(v, float) for v in values.values()):
        return 0.0
    rpy = inertial.origin.rpy
    rotation = rpy_matrix(rpy) if isinstance(rpy, tuple) else np.eye(3)
    weights = np.abs(rotation.T @ excess.weights @ rotation)  # in <inertia>'s axes
    h = {name: rounding(value) for name, value in values.items()}  # type: ignore[arg-type]
    pairs = {"ixx": (0, 0), "iyy": (1, 1), "izz": (2, 2), "ixy": (0, 1), "ixz": (0, 2)}
    pairs["iyz"] = (1, 2)
    total = 0.0
    for name, (i, j) in pairs.items():
        total += (1.0 if i == j else 2.0) * weights[i, j] * h[name]
    return total
