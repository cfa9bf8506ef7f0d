"""
A MuJoCo primitive geom's mass properties (sphere, capsule, cylinder, box, ellipsoid; solid or
``shellinertia``) as MuJoCo's compiler infers them: ``mjCGeom::GetVolume`` and ``SetInertia`` in
``src/user/user_objects.cc``, checked against MuJoCo 4.0.0. Solids share
:mod:`.primitives`' formulas (MuJoCo's capsule is the same); shells mirror MuJoCo's term for
term, its ellipsoid approximation included.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from inertia_kit.physics import primitives
from inertia_kit.physics.mass import MassProperties
from inertia_kit.physics.mujoco_mesh_inertia import MJEPS, geom_mass

#: geom types whose mass properties MuJoCo computes in closed form
PRIMITIVE_KINDS = ("sphere", "capsule", "cylinder", "box", "ellipsoid")


def primitive_size(kind: str, size: ArrayLike, fromto: ArrayLike | None = None) -> NDArray:
    """
    A primitive geom's ``size`` after ``fromto``, as ``mjCGeom::Compile`` resolves it: the
    half-length ``|from - to| / 2`` becomes ``size[1]`` (capsule, cylinder) or ``size[2]``, with
    ``size[1] = size[0]`` (box, ellipsoid); the geom's z axis then runs along ``to - from``.

    Returns
    -------
    size : (3,) float
      Unused entries zero.
    """
    if kind not in PRIMITIVE_KINDS:
        raise ValueError(f"kind must be one of {', '.join(PRIMITIVE_KINDS)}, got {kind!r}")
    given = np.atleast_1d(np.asarray(size, dtype=np.float64))
    out = np.zeros(3)
    out[: min(len(given), 3)] = given[:3]
    if fromto is not None:
        ends = np.asarray(fromto, dtype=np.float64)
        if ends.shape != (6,):
            raise ValueError(f"fromto must be 6 numbers, got shape {ends.shape}")
        if kind == "sphere":
            raise ValueError("fromto requires capsule, cylinder, box or ellipsoid in geom")
        vec = ends[:3] - ends[3:]
        half = math.sqrt(vec[0] * vec[0] + vec[1] * vec[1] + vec[2] * vec[2]) / 2
        if half < MJEPS:
            raise ValueError("fromto points too close in geom")
        out[1] = half
        if kind in ("box", "ellipsoid"):
            out[2], out[1] = out[1], out[0]
    needed = {"sphere": 1, "capsule": 2, "cylinder": 2, "box": 3, "ellipsoid": 3}[kind]
    if not (out[:needed] > 0).all():
        raise ValueError(f"{kind} size must be {needed} positive numbers, got {out[:needed]}")
    return out


def primitive_measure(kind: str, size: ArrayLike, shell: bool = False) -> float:
    """
    ``mjCGeom::GetVolume``: the volume (m³), or with ``shell`` the area (m², the ellipsoid's by
    Thomsen's approximation, p = 1.6075), that ``density`` multiplies. ``size`` as MuJoCo's.
    """
    s = [float(v) for v in primitive_size(kind, size)]
    pi = math.pi
    r = s[0]
    height = 2 * s[1]
    if kind == "sphere":
        return 4 * pi * r * r if shell else 4 * pi * r * r * r / 3
    if kind == "capsule":
        if shell:
            return 4 * pi * r * r + 2 * pi * r * height
        return pi * (r * r * height + 4 * r * r * r / 3)
    if kind == "cylinder":
        return 2 * pi * r * r + 2 * pi * r * height if shell else pi * r * r * height
    if kind == "ellipsoid":
        if not shell:
            return 4 * pi * s[0] * s[1] * s[2] / 3
        p = 1.6075
        tmp = (s[0] * s[1]) ** p + (s[1] * s[2]) ** p + (s[2] * s[0]) ** p
        return 4 * pi * (tmp / 3) ** (1 / p)
    if shell:
        return 8 * (s[0] * s[1] + s[1] * s[2] + s[2] * s[0])
    return s[0] * s[1] * s[2] * 8


def primitive_mass_properties(
    kind: str,
    size: ArrayLike,
    *,
    shell: bool = False,
    density: float | None = None,
    mass: float | None = None,
    fromto: ArrayLike | None = None,
) -> MassProperties:
    """
    Mass properties of a primitive geom as ``mjCGeom::GetVolume`` and ``SetInertia`` compute
    them, in the geom's frame (centre of mass at its origin; capsule and cylinder along z).

    Solids are :mod:`.primitives`' closed forms, which are MuJoCo's (its capsule too: two
    hemispheres of ``2/5 m r²`` moved by the exact parallel-axis term). Shells
    (``shellinertia="true"``) mirror MuJoCo's: a sphere's ``2/3 m r²``; a cylinder's tube and two
    disks, a capsule's tube and hemispherical shells (centre ``r/2`` from the flat side), a box's
    six plates, each with mass by area; an ellipsoid's as MuJoCo approximates it, the difference
    of two solid ellipsoids 1e-6 m apart, with its mass by Thomsen's area.

    Parameters
    ----------
    kind : {"sphere", "capsule", "cylinder", "box", "ellipsoid"}
    size : (1 to 3,) float
      MuJoCo's ``size``: radius; radius and half-length; half-sides; semi-axes, m.
    shell : bool
      ``shellinertia``: mass on the surface, ``density`` per m².
    density, mass : float
      Exactly one: kg/m³ (kg/m² for a shell), or kg. Zero gives a massless geom, as in MuJoCo.
    fromto : (6,) float, optional
      Two points: the length and axis instead of ``size[1]`` (:func:`primitive_size`).

    Returns
    -------
    MassProperties
      kg, m, kg·m², in the geom frame (z along ``fromto``).
    """
    s = primitive_size(kind, size, fromto)
    m = geom_mass(primitive_measure(kind, s, shell), density, mass)
    if m == 0:
        return MassProperties(0.0)
    r, half = float(s[0]), float(s[1])
    if not shell:
        if kind == "sphere":
            return primitives.sphere(r, mass=m)
        if kind == "capsule":
            return primitives.capsule(r, 2 * half, mass=m)
        if kind == "cylinder":
            return primitives.cylinder(r, 2 * half, mass=m)
        if kind == "box":
            return primitives.box(2 * s, mass=m)
        return primitives.ellipsoid(s, mass=m)
    return MassProperties(m, np.zeros(3), np.diag(_shell_moments(kind, s, m)))


def _shell_moments(kind: str, size: NDArray, mass: float) -> list[float]:
    """The shell branch of ``mjCGeom::SetInertia``, term for term."""
    s = [float(v) for v in size]
    pi = math.pi
    if kind == "sphere":
        moment = 2 * mass * s[0] * s[0] / 3
        return [moment, moment, moment]
    if kind in ("capsule", "cylinder"):
        radius, halfheight = s[0], s[1]
        height = 2 * halfheight
        if kind == "capsule":
            a_sphere, a_cylinder = 4 * pi * radius * radius, 2 * pi * radius * height
            sphere_mass = mass * a_sphere / (a_sphere + a_cylinder)
            cylinder_mass = mass - sphere_mass
            side = cylinder_mass * (6 * radius * radius + height * height) / 12
            axial = cylinder_mass * radius * radius
            sphere_inertia = 2 * sphere_mass * radius * radius / 3
            hs_com = radius / 2
            hs_pos = halfheight + hs_com
            side += sphere_inertia + sphere_mass * (hs_pos * hs_pos - hs_com * hs_com)
            return [side, side, axial + sphere_inertia]
        a_disk, a_cylinder = pi * radius * radius, 2 * pi * radius * height
        mass_disk = mass * a_disk / (2 * a_disk + a_cylinder)
        mass_cylinder = mass - 2 * mass_disk
        side = mass_cylinder * (6 * radius * radius + height * height) / 12
        axial = mass_cylinder * radius * radius
        disk_x = mass_disk * radius * radius / 4 + mass_disk * halfheight * halfheight
        disk_z = mass_disk * radius * radius / 2
        return [side + 2 * disk_x, side + 2 * disk_x, axial + 2 * disk_z]
    s00, s11, s22 = s[0] * s[0], s[1] * s[1], s[2] * s[2]
    if kind == "ellipsoid":
        eps = 1e-6
        va = 4 * pi * s[0] * s[1] * s[2] / 3
        ae, be, ce = s[0] + eps, s[1] + eps, s[2] + eps
        vb = 4 * pi * ae * be * ce / 3
        density = mass / (vb - va)
        mass_a, mass_b = va * density, vb * density
        return [
            mass_b * (be * be + ce * ce) / 5 - mass_a * (s11 + s22) / 5,
            mass_b * (ae * ae + ce * ce) / 5 - mass_a * (s00 + s22) / 5,
            mass_b * (ae * ae + be * be) / 5 - mass_a * (s00 + s11) / 5,
        ]
    lx, ly, lz = 2 * s[0], 2 * s[1], 2 * s[2]
    a0, a1, a2 = lx * ly, ly * lz, lz * lx
    total = 2 * (a0 + a1 + a2)
    mass0, mass1, mass2 = mass * a0 / total, mass * a1 / total, mass * a2 / total
    ix0, iy0, iz0 = mass0 * ly * ly / 12, mass0 * lx * lx / 12, mass0 * (lx * lx + ly * ly) / 12
    ix1, iy1, iz1 = mass1 * (ly * ly + lz * lz) / 12, mass1 * lz * lz / 12, mass1 * ly * ly / 12
    ix2, iy2, iz2 = mass2 * lz * lz / 12, mass2 * (lx * lx + lz * lz) / 12, mass2 * lx * lx / 12
    return [
        2 * (mass0 * s22 + mass2 * s11 + ix0 + ix1 + ix2),
        2 * (mass0 * s22 + mass1 * s00 + iy0 + iy1 + iy2),
        2 * (mass1 * s00 + mass2 * s11 + iz0 + iz1 + iz2),
    ]
