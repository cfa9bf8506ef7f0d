"""
analysis.firmness: a declared moment beyond the geometry's hard bound is certainly impossible
only when it stays beyond it with every written number rounded in its favour and mesh facets
allowed for, on collision geometry. The bounds are closed forms computed here.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from kit import write
from kit.meshes import ascii_stl, box_triangles
from kit.urdf import collision, cylinder, inertial, link, mesh, visual

from inertia_kit.analysis.bounds import RIM_SIDES
from inertia_kit.analysis.firmness import FACETS, GROSS, ROUNDING_CAP, rounding

RIM = 1.0 / math.cos(math.pi / RIM_SIDES)  # the cylinder hull's polygon overshoot

# Unitree Go1's rotor links (example-robot-data, go1.urdf): a 0.089 kg rotor whose axial moment
# 0.000111842 kg·m² is 2.3 % above the 0.089 × 0.035² a mass inside the drawn cylinder can have
ROTOR_SHAPE = cylinder(0.035, 0.02)
ROTOR_MASS = inertial(0.089, 0.000111842, 5.9647e-05, 5.9647e-05)
ROTOR_RPY = "0 1.5707963267948966 0"  # the cylinder along x, the link's ixx axis


@pytest.mark.parametrize(
    "value, half",
    [
        (0.035, 0.0005),
        (0.0350, 0.0005),  # the same float: trailing zeros are not seen
        (0.000111842, 5e-10),
        (0.089, 0.0005),
        (0.05, 0.05 * ROUNDING_CAP),  # one digit: at most 5 %
        (1e-05, 1e-05 * ROUNDING_CAP),
        (0.034999999999999996, 5e-19),  # a value xacro computed: all its digits count
        (0.0, 0.0),
        (-0.035, 0.0005),
        (math.inf, 0.0),
    ],
)
def test_rounding_is_half_a_unit_in_the_last_written_digit(value, half):
    assert rounding(value) == pytest.approx(half, rel=1e-9, abs=0)


def rotor(analysed, shapes, mass=ROTOR_MASS):
    return analysed(link("rotor", mass, shapes)).by_name["rotor"]


def test_go1_rotor_overshoot_is_within_the_rounding_of_its_radius_and_mass(analysed):
    found = rotor(
        analysed, collision(ROTOR_SHAPE, rpy=ROTOR_RPY) + visual(ROTOR_SHAPE, rpy=ROTOR_RPY)
    )
    firmness = found.firmness
    assert firmness.excess.ratio == pytest.approx(0.000111842 / (0.089 * (0.035 * RIM) ** 2))
    assert firmness.excess.ratio > 1.02
    # the bound with r = 0.0355 m and m = 0.0895 kg (the moment's own digits barely count)
    allowed = 0.0895 * (0.0355 * RIM) ** 2
    assert firmness.margin.bound == pytest.approx(allowed, rel=1e-6)
    assert not firmness.firm
    assert firmness.rounded[:2] == ("cylinder radius 0.035 m", "mass 0.089 kg")
    assert firmness.why_not() == (
        "2.3% over is within what rounding of the written cylinder radius 0.035 m and mass "
        f"0.089 kg can explain (the bound then reaches {allowed:.4g} kg·m²)"
    )


def test_the_same_overshoot_with_every_digit_written_is_firm(analysed):
    precise = cylinder("0.0349999", "0.0200001")
    found = rotor(analysed, collision(precise, rpy=ROTOR_RPY), inertial("0.0890001", 0.000111842))
    assert found.firmness.firm and found.firmness.why_not() is None


def test_visual_only_geometry_is_a_warning_unless_gross(analysed):
    found = rotor(analysed, visual(ROTOR_SHAPE, rpy=ROTOR_RPY))
    assert not found.firmness.firm
    assert found.firmness.why_not() == (
        "its only geometry is visual, often a schematic stand-in for the part"
    )
    # the placeholder ixx = 1.0 on the same rotor: beyond any stand-in's inaccuracy
    placeholder = rotor(analysed, visual(ROTOR_SHAPE), inertial(0.089, 1.0))
    assert placeholder.firmness.margin.ratio > GROSS and placeholder.firmness.firm


def write_box_mesh(tmp_path, name="part.stl", drop=0):
    size = np.array([0.1234, 0.2345, 0.3456])
    triangles = box_triangles(size, -size / 2)
    write(tmp_path / name, ascii_stl(triangles[drop:]))
    return size


@pytest.mark.parametrize("over, firm", [(1.03, False), (1.06, True)])
def test_mesh_facets_are_allowed_for(analysed, tmp_path, over, firm):
    """A centred box mesh: about x at most m (b² + c²) / 4; its facets add 2 % to each size."""
    size = write_box_mesh(tmp_path)
    mass = 2.345
    bound = mass * (size[1] ** 2 + size[2] ** 2) / 4
    found = rotor(analysed, collision(mesh("part.stl")), inertial(mass, over * bound, 1e-3, 1e-3))
    firmness = found.firmness
    assert firmness.excess.bound == pytest.approx(bound)
    assert firmness.margin.bound == pytest.approx(bound * (1 + FACETS) ** 2 * (1 + 0.0005 / mass))
    assert firmness.firm is firm
    if not firm:
        assert firmness.facets == ("part.stl",)
        assert "the facets of `part.stl`" in firmness.why_not()


def test_an_open_mesh_is_weak(analysed, tmp_path):
    write_box_mesh(tmp_path, drop=2)  # a face missing: its convex hull stands in for it
    size = np.array([0.1234, 0.2345, 0.3456])
    mass = 2.345
    bound = mass * (size[1] ** 2 + size[2] ** 2) / 4
    found = rotor(analysed, collision(mesh("part.stl")), inertial(mass, 1.5 * bound, 1e-3, 1e-3))
    assert not found.firmness.firm
    assert "mesh `part.stl` is open (IN032)" in found.firmness.why_not()


def test_no_excess_no_firmness(analysed):
    right = inertial(0.089, 0.089 * 0.035**2 / 2, 3e-5, 3e-5)
    assert rotor(analysed, collision(ROTOR_SHAPE, rpy=ROTOR_RPY), right).firmness is not None
    assert rotor(analysed, "", right).firmness is None  # no geometry, no bound
