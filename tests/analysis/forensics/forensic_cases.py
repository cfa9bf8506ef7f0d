"""
Shared builders of the forensics tests: each slip is constructed from closed forms here, and
undone by ``diagnose``.
"""

from __future__ import annotations

import itertools

import numpy as np

from inertia_kit.analysis.bounds import Hull
from inertia_kit.analysis.forensics.diagnosis import diagnose
from inertia_kit.physics.mass import MassProperties

EYE = np.eye(3)


def box_tensor(mass, x, y, z, rotation=EYE):
    moments = np.diag([y * y + z * z, x * x + z * z, x * x + y * y]) * mass / 12
    return rotation @ moments @ rotation.T


def cylinder_tensor(mass, radius, length):
    """Along z."""
    transverse = mass * (3 * radius**2 + length**2) / 12
    return np.diag([transverse, transverse, mass * radius**2 / 2])


def box_hull(x, y, z, centre=(0.0, 0.0, 0.0), rotation=EYE):
    signs = np.array(list(itertools.product((-0.5, 0.5), repeat=3)))
    return Hull(signs * [x, y, z] @ rotation.T + np.asarray(centre))


def parallel_axis(mass, d):
    d = np.asarray(d, dtype=float)
    return mass * (d @ d * np.eye(3) - np.outer(d, d))


def rounded(tensor, digits=4):
    """Each value rounded to ``digits`` significant digits, as CAD reports print them."""
    out = np.array(tensor, dtype=float)
    for index, value in np.ndenumerate(out):
        out[index] = float(f"{value:.{digits - 1}e}") if value else 0.0
    return 0.5 * (out + out.T)


def props(mass, tensor, com=(0.0, 0.0, 0.0)):
    return MassProperties(mass, com, tensor)


BOX = (0.4, 0.2, 0.1)
MASS = 2.0
VOLUME = 0.4 * 0.2 * 0.1


def box_case(tensor, com=(0.0, 0.0, 0.0), rotation=EYE, **kw):
    """``diagnose`` against the box (turned by ``rotation``), 2 kg, its hull and volume."""
    expected = props(MASS, box_tensor(MASS, *BOX, rotation))
    kw.setdefault("hull", box_hull(*BOX, rotation=rotation))
    kw.setdefault("volume", VOLUME)
    kw.setdefault("points", [("the link origin", (0.0, 0.0, 0.0))])
    return diagnose(props(MASS, tensor, com), expected, **kw)


def case_of(declared, expected, axes=EYE):
    """The :class:`Case` ``diagnose`` tests (for the searches alone)."""
    from inertia_kit.analysis.forensics.candidate import Case
    from inertia_kit.analysis.forensics.measure import Metric

    return Case(declared, expected, np.asarray(axes), Metric(expected.inertia), "box")


def slightly_off(tensor, seed):
    """``tensor`` with each value off by up to 0.2 % (symmetric), as a declared value may be."""
    noise = np.random.default_rng(seed).uniform(-0.002, 0.002, (3, 3))
    return tensor * (1 + 0.5 * (noise + noise.T))
