"""analysis.fault: which of two links is at fault, judged against real parts' scatter."""

from __future__ import annotations

import math

import pytest
from kit.urdf import box, box_inertial, collision, link, sphere, visual

from inertia_kit.analysis.fault import (
    BAND,
    PLAUSIBLE_COM,
    Departure,
    departure,
    least_departure,
    worse,
    worse_part,
)


def test_two_real_parts_fitting_alike_blame_neither():
    # UR3e's shape: a shared block fits one link at a factor of 1.82, the other at 2.13, and
    # its centre of mass 7 % and 12 % of their sizes from their centroids: both as real parts
    base, shoulder = Departure(math.log(1.82), 0.07), Departure(math.log(2.13), 0.125)
    assert not worse_part(shoulder, base) and not worse_part(base, shoulder)
    # ... while of two twins (one part mirrored, its values scattering alike about its
    # geometry) the margin alone tells: the centre of mass 5.5 % of the size farther
    assert worse(shoulder, base) and not worse(base, shoulder)


def test_evidence_pointing_both_ways_names_neither_twin():
    # GR3's upper arm yaw twins, one given its neighbour's block: it departs 0.18 more in
    # tensor, its twin 11 % of the size more in centre of mass
    given, twin = Departure(0.805, 0.057), Departure(0.624, 0.168)
    assert not worse(twin, given) and not worse(given, twin)
    # ... while a centre of mass as far off with the tensor closer only by noise is told
    assert worse(Departure(0.6, 0.168), Departure(0.65, 0.057))


def test_a_link_beyond_any_real_part_is_worse():
    good = Departure(math.log(1.5), 0.05)
    assert worse_part(Departure(BAND + 0.3, 0.05), good)
    assert worse_part(Departure(math.log(1.5), PLAUSIBLE_COM + 0.1), good)
    # ... but not when it is the clearly closer one in the other part
    assert not worse_part(Departure(BAND + 0.3, 0.0), Departure(math.log(1.5), 0.3))


def test_beside_exact_values_the_margin_alone_tells():
    # values computed from their geometry: a copy 1.5 times off on another link is a copy
    exact = Departure(0.0, 0.0)
    assert worse_part(Departure(math.log(1.5), 0.0), exact)
    assert worse_part(Departure(0.0, 0.12), exact)
    assert not worse_part(Departure(0.1, 0.03), exact)  # within the margins


def test_least_departure_is_from_the_geometry_the_values_fit_best(analysed):
    # a 5 cm collision sphere standing in for a 0.3 m arm part: the values are the visual
    # box's; the link's departure is judged on its collision sphere (the geometry mass comes
    # from, what its twin is judged on too), its least one on the box
    size = (0.06, 0.06, 0.3)
    body = box_inertial(2.0, size) + collision(sphere(0.05)) + visual(box(*size))
    arm = analysed(link("arm", body)).by_name["arm"]
    least, plain = least_departure(arm), departure(arm)
    assert least is not None and plain is not None
    assert least.tensor == pytest.approx(0.0, abs=1e-9) and least.com == pytest.approx(0.0)
    assert plain.tensor > BAND
