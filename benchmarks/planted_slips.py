"""
Planted slips on real links: how often the linter detects a known slip of a link's mass
properties, and how often the slip's own rule names it::

    /work/venv-robots/bin/python benchmarks/planted_slips.py            # every package, ~10 min
    /work/venv-robots/bin/python benchmarks/planted_slips.py --quick    # a sample, ~1 min
    /work/venv-robots/bin/python benchmarks/planted_slips.py --save cases.json

Run it with the interpreter that has the PyPI robot packages (see ``real_robots.py``).

Population
----------
Every robot file of the installed robot packages (found as ``real_robots.py`` finds them, read
with our loader, xacro expanded), and in it every link whose declared values agree with its
geometry (collision, else visual, at uniform density with the declared mass):

- each of the three principal moments of the declared tensor within a factor of
  :data:`AGREEMENT` (2) of the geometry's, both sorted;
- the declared centre of mass inside the geometry's bounding box;
- and no error or warning on the link from the current linter (all default rules).

Links with a mesh in that geometry are "CAD" links, the others "primitive" links; they are
reported apart. The same link found in several robot files (variants of one robot) counts
once. At most :data:`PER_ROBOT` links per robot file and :data:`PER_PACKAGE` per package are
taken, chosen by a hash of file and link name: the sample is deterministic and no package
dominates.

Planting
--------
Each slip is planted alone, on one link, in the loaded robot (the link's ``<inertial>`` values
replaced, every other element as read), and the whole robot is linted again with
``run_rules`` as ``lint_file`` does (suppression comments aside: the packages have none). This
is what linting a copy of the expanded URDF with the values written by ``repr`` would give
(the shortest decimal form reads back as the same float, and the rules that judge rounding use
that form), without writing copies that must keep ``package://`` and relative meshes resolvable,
and without reading the meshes again for each case. The slips, exactly (``T`` the six values as
a tensor in the axes they are written in, ``R`` the ``<origin rpy>`` rotation, ``c`` the COM,
``m`` the mass):

=============  ==========================================================  ===============
kind           planted values                                              own rule
=============  ==========================================================  ===============
about-origin   ``T' = Rᵀ (R T Rᵀ + m (|c|² E - c cᵀ)) R``: about the origin  IN060
signs          products negated (ixy, ixz, iyz)                            IN061
other-axes     ``T' = Rx T Rxᵀ``, Rx 90° about x                           IN062
kg-mm2         ``T' = 1e6 T``                                              IN063
swap-ixx-iyy   ixx and iyy exchanged                                       IN064
mass-x3        ``m' = 3 m``, tensor unchanged                              IN068
neighbour      the parent's ``<inertial>`` (else a child's) copied          IN066
grams          ``m' = 1000 m``                                              IN063
com-origin     ``c' = 0``                                                  IN021
com-mirrored   ``c' = -c``                                                 IN021
identity       ixx = iyy = izz = 1, products 0                             IN013
com-flip       the coordinate of ``c`` with the largest |value| negated     IN021
com-swap       the two coordinates of ``c`` largest in |value| exchanged    IN021
=============  ==========================================================  ===============

Own rules, from ``inertia_kit/analysis/forensics`` and ``rules/``: IN060-IN064 are the forensic
rules (IN063 also names a mass in grams, "the mass ... is in grams"); IN013 names an isotropic
placeholder; no rule names a centre of mass slip but IN021 (com-geometry-mismatch, whose help
says "check the sign, the axes and the unit"); IN068 (inertia-for-other-mass) names a mass ×3:
the tensor the geometry's for another mass, alike about every axis (IN022 judges the density
alone, and 3 × 2700 kg/m³ is still a metal); IN066 (copied-inertial) names a copied
neighbour's block.

Identifiable
------------
A case is identifiable when what the linter sees, the planted values against the link's
geometry (collision, else visual, at uniform density with the planted mass), is outside what
the silent real links show, in what the slip changes:

- the tensor: its log distance from the geometry's
  (:class:`~inertia_kit.analysis.forensics.measure.LogMetric`, the forensics' own metric) is
  beyond :data:`~inertia_kit.analysis.forensics.measure.BAND` (0.92, a factor of 2.5: between the
  95th and 99th percentile of the silent links, ``benchmarks/cad_band.py``); a mass ×3 whose
  tensor still lands within the band is not identifiable, whatever the true values were;
- a unit slip (kg-mm2, grams): always, by its exact factor (10⁶, 10³), far beyond any scatter;
- the centre of mass (com-*): farther than :data:`COM_SHIFT` of the geometry's largest box
  extent from the geometry's centroid.

The older test, planted values against the TRUE ones (by a factor of :data:`AGREEMENT` about
some axis, or the mass by that factor, or the COM moved by :data:`COM_SHIFT` of the extent), is
kept as the ``old id.`` column for comparison.

Equivalent slips
----------------
Some slips are exactly another slip on some links: ixx and iyy exchanged with zero products
IS a quarter turn about z (IN062), products negated with a single non-zero product IS a half
turn (IN062). A case counts as named when its own rule names it, or when another forensic
rule (:data:`FORENSIC`) names it with a repair that restores the true values (the finding's
``expected`` tensor within :data:`RESTORED_LOG` of the true one, link axes, and the mass
within :data:`RESTORED`); the ``equiv.`` column counts the identifiable cases named only that way.

Measured
--------
Per kind: cases, identifiable cases (and by the older test), detected (a new error or warning on
the link, any rule) of all cases and of the identifiable ones, named (an error or warning of the
own rule on the link, or of an equivalent rule that restores the true values) of the
identifiable ones, and the cases with a new finding (any severity) on another link of the robot
than the one planted ("untouched+"; a finding on no link, IN065's pair of twins the file cannot
judge, blames no untouched link and is not counted). A finding there is new when that link had
no finding of its rule before, or of the rule's family (:data:`FAMILIES`: a copied tensor is
IN013's, IN066's when the whole block is the same, IN068's when the two parts are one shape with
other masses; a slip on the original changes which of them speaks of the copy); a finding there
whose severity only changed is counted apart ("raised", "lowered": a helper frame's share of its
body judged again when the body's own values slip, rules/README.md "Severity by consequence").
So is a new finding of a rule that judges a link by its share of the body the engines lump
(``WEIGHED`` rules) on a link welded to the planted one ("welded"): that body changed with the
slip (Go1's 1 g IMU frame, a placeholder negligible beside a 5 kg trunk, is most of the body
once the trunk holds a 1 µg block), so the finding is the slip's consequence, not a claim about
an untouched part.
``--save FILE`` writes every case as JSON.
"""

from __future__ import annotations

import argparse
import dataclasses
import hashlib
import json
import os
import sys
import time
from collections import defaultdict
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # 2 processes on 2 cores

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from real_robots import PACKAGES, package_folder

#: the population's agreement between declared values and geometry, and the change a slip must
#: make to be identifiable: real CAD values differ from uniform-density geometry by up to this
#: factor (hollow shells, dense motors), so a smaller change cannot be told from that noise
AGREEMENT = 2.0
#: a centre of mass moved by less than this fraction of the link's largest extent could be a
#: real one: a motor at one end moves it a third of the way to the end (rules/IN021's note)
COM_SHIFT = 0.25
#: the forensic rules whose repair may restore the true values of a slip planted as another
FORENSIC = ("IN060", "IN061", "IN062", "IN063", "IN064")
#: a repair restores the true values when its mass is within this fraction of the true one ...
RESTORED = 0.01
#: ... and its tensor within this log distance of the true one (LogMetric: 5 % about every axis,
#: a twelfth of the scatter real CAD parts show against their geometry). An exact equivalent
#: restores to the printed rounding; a quarter turn read for ixx and iyy exchanged differs only
#: in the sign of products far below the moments (Trossen forearms: ixy 3e-7 beside 1.6e-5 and
#: 5.3e-5 kg·m², 2 % of a moment's scale): the same body to any engine, which no geometry tells
RESTORED_LOG = 0.05
PER_ROBOT = 4
PER_PACKAGE = 60
QUICK_PER_ROBOT = 1
QUICK_PER_PACKAGE = 6

OWN_RULE = {
    "about-origin": "IN060",
    "signs": "IN061",
    "other-axes": "IN062",
    "kg-mm2": "IN063",
    "swap-ixx-iyy": "IN064",
    "mass-x3": "IN068",
    "neighbour": "IN066",
    "grams": "IN063",
    "com-origin": "IN021",
    "com-mirrored": "IN021",
    "identity": "IN013",
    "com-flip": "IN021",
    "com-swap": "IN021",
}
KINDS = tuple(OWN_RULE)
#: rules whose finding also names a slip its own rule names: IN067 (com-slip) names the slip of
#: a centre of mass IN021 rejects, and replaces IN021's finding
ALSO_NAMED_BY = {"IN021": ("IN067",)}
#: the slips IN067 undoes (a COM left at the origin has no reading to undo)
COM_READINGS = ("com-mirrored", "com-flip", "com-swap")


# --- the slips: pure functions of a link's values ------------------------------------------


@dataclass(frozen=True)
class Values:
    """A link's ``<inertial>``: mass, COM (link frame), rpy, the six values as a tensor."""

    mass: float
    xyz: np.ndarray
    rpy: np.ndarray
    tensor: np.ndarray  # (3, 3) in the axes of rpy, about the COM, as written

    @classmethod
    def of(cls, inertial) -> Values:
        t = inertial.tensor_values()
        tensor = np.array(
            [
                [t["ixx"], t["ixy"], t["ixz"]],
                [t["ixy"], t["iyy"], t["iyz"]],
                [t["ixz"], t["iyz"], t["izz"]],
            ],
            dtype=float,
        )
        origin = inertial.origin
        return cls(
            float(inertial.mass), np.array(origin.xyz, float), np.array(origin.rpy, float), tensor
        )

    def replace(self, **changes) -> Values:
        return dataclasses.replace(self, **changes)


def _rotation(rpy: np.ndarray) -> np.ndarray:
    from inertia_kit.physics.frames import rpy_matrix

    return rpy_matrix(rpy)


def about_origin(v: Values, sign: float = 1.0) -> Values:
    """The tensor about the link origin instead of the COM (``sign=-1`` undoes it)."""
    rotation = _rotation(v.rpy)
    c = v.xyz
    shift = v.mass * (np.dot(c, c) * np.eye(3) - np.outer(c, c))
    link_axes = rotation @ v.tensor @ rotation.T + sign * shift
    return v.replace(tensor=rotation.T @ link_axes @ rotation)


def signs(v: Values) -> Values:
    tensor = -v.tensor
    np.fill_diagonal(tensor, np.diag(v.tensor))
    return v.replace(tensor=tensor)


RX90 = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])


def other_axes(v: Values, rotation: np.ndarray = RX90) -> Values:
    return v.replace(tensor=rotation @ v.tensor @ rotation.T)


def kg_mm2(v: Values) -> Values:
    return v.replace(tensor=v.tensor * 1e6)


def swap_ixx_iyy(v: Values) -> Values:
    tensor = v.tensor.copy()
    tensor[0, 0], tensor[1, 1] = v.tensor[1, 1], v.tensor[0, 0]
    return v.replace(tensor=tensor)


def mass_x3(v: Values) -> Values:
    return v.replace(mass=v.mass * 3)


def grams(v: Values) -> Values:
    return v.replace(mass=v.mass * 1000)


def com_origin(v: Values) -> Values:
    return v.replace(xyz=np.zeros(3))


def com_mirrored(v: Values) -> Values:
    return v.replace(xyz=-v.xyz)


def identity(v: Values) -> Values:
    return v.replace(tensor=np.eye(3))


def com_flip(v: Values) -> Values:
    xyz = v.xyz.copy()
    i = int(np.argmax(np.abs(xyz)))
    xyz[i] = -xyz[i]
    return v.replace(xyz=xyz)


def com_swap(v: Values) -> Values:
    order = np.argsort(-np.abs(v.xyz), kind="stable")
    i, j = int(order[0]), int(order[1])
    xyz = v.xyz.copy()
    xyz[i], xyz[j] = v.xyz[j], v.xyz[i]
    return v.replace(xyz=xyz)


SLIPS = {
    "about-origin": about_origin,
    "signs": signs,
    "other-axes": other_axes,
    "kg-mm2": kg_mm2,
    "swap-ixx-iyy": swap_ixx_iyy,
    "mass-x3": mass_x3,
    "grams": grams,
    "com-origin": com_origin,
    "com-mirrored": com_mirrored,
    "identity": identity,
    "com-flip": com_flip,
    "com-swap": com_swap,
}  # "neighbour" takes the neighbour's values


def planted(link, values: Values):
    """``link`` (a ``model.Link`` with an ``<inertial>``) with ``values`` written into it."""
    inertial = link.inertial
    t = values.tensor
    origin = dataclasses.replace(
        inertial.origin,
        xyz=tuple(float(x) for x in values.xyz),
        rpy=tuple(float(x) for x in values.rpy),
    )
    new = dataclasses.replace(
        inertial,
        origin=origin,
        mass=float(values.mass),
        ixx=float(t[0, 0]),
        ixy=float(t[0, 1]),
        ixz=float(t[0, 2]),
        iyy=float(t[1, 1]),
        iyz=float(t[1, 2]),
        izz=float(t[2, 2]),
    )
    return dataclasses.replace(link, inertial=new)


def visible(kind: str, link, size: float) -> bool:
    """
    Whether the planted values (``link``: the slipped link's analysis) are outside what silent
    real links show against their geometry (module doc, "Identifiable").
    """
    from inertia_kit.analysis.forensics.measure import BAND, LogMetric

    if kind in ("kg-mm2", "grams"):
        return True  # an exact factor of 1e6 or 1e3: no scatter reaches it
    declared, geometry = link.declared, link.geometry
    expected = None if geometry is None else geometry.at_mass(declared.mass)
    if expected is None:
        return False
    if kind.startswith("com-"):
        return bool(np.linalg.norm(declared.com - expected.com) > COM_SHIFT * size)
    try:
        return bool(LogMetric(expected.inertia)(declared.inertia) > BAND)
    except np.linalg.LinAlgError:
        return True  # the geometry has no tensor to be near


def restored(finding, true: Values) -> bool:
    """Whether a finding's repair (its ``expected``) restores the true values (module doc)."""
    from inertia_kit.analysis.forensics.measure import LogMetric

    fix = finding.expected or {}
    if not all(k in fix for k in ("mass", "ixx", "ixy", "ixz", "iyy", "iyz", "izz")):
        return False
    tensor = np.array(
        [
            [fix["ixx"], fix["ixy"], fix["ixz"]],
            [fix["ixy"], fix["iyy"], fix["iyz"]],
            [fix["ixz"], fix["iyz"], fix["izz"]],
        ],
        dtype=float,
    )
    rotation = _rotation(true.rpy)
    right = rotation @ true.tensor @ rotation.T  # the repair is in link axes
    if abs(fix["mass"] / true.mass - 1.0) > RESTORED:
        return False
    try:
        return bool(LogMetric(right)(tensor) <= RESTORED_LOG)
    except (ValueError, np.linalg.LinAlgError):
        return False


def identifiable(true: Values, slipped: Values, size: float) -> bool:
    """The older test: the slip changed the values by more than the population's noise."""
    from inertia_kit.analysis.forensics.measure import deviation
    from inertia_kit.physics.mass import MassProperties

    def per_mass(v: Values) -> np.ndarray:
        return MassProperties.from_urdf(1.0, *_six(v.tensor / v.mass), xyz=v.xyz, rpy=v.rpy).inertia

    a, b = per_mass(true), per_mass(slipped)
    tensor = _safe_deviation(deviation, b, a) >= 1.0 or _safe_deviation(deviation, a, b) >= 1.0
    ratio = slipped.mass / true.mass
    mass = max(ratio, 1 / ratio) >= AGREEMENT
    com = float(np.linalg.norm(slipped.xyz - true.xyz)) > COM_SHIFT * size
    return bool(tensor or mass or com)


def _six(t: np.ndarray) -> tuple[float, ...]:
    return (t[0, 0], t[0, 1], t[0, 2], t[1, 1], t[1, 2], t[2, 2])


def _safe_deviation(deviation, tensor, reference) -> float:
    if not np.all(np.linalg.eigvalsh((reference + reference.T) / 2) > 0):
        return float("inf")  # a reference that is no tensor: anything differs from it
    return deviation(tensor, reference)


# --- the population -------------------------------------------------------------------------


def _loader():
    from inertia_kit.analysis.geometry import default_mesh_loader

    kept: dict = {}

    def load(path, scale):
        key = (path, tuple(scale))
        if key not in kept:
            try:
                kept[key] = default_mesh_loader(path, scale)
            except Exception as error:  # a MeshError, kept to raise again
                kept[key] = error
        if isinstance(kept[key], Exception):
            raise kept[key]
        return kept[key]

    return load


def _lint(robot, load):
    from inertia_kit.analysis.links import analyse
    from inertia_kit.lint.runner import run_rules

    analysis = analyse(robot, load)
    return analysis, run_rules(analysis)


def _loud(finding) -> bool:
    from inertia_kit.lint.findings import Severity

    return finding.severity >= Severity.WARNING


def _agrees(link) -> dict | None:
    """The population's test (module doc): ``None``, or what the case needs of the link."""
    from inertia_kit.description import model

    declared = link.declared
    inertial = link.link.inertial
    if declared is None or not isinstance(inertial.mass, float):
        return None
    geometry = link.geometry
    expected = geometry.at_mass(declared.mass)
    corners = geometry.corners
    if expected is None or corners is None:
        return None
    mine, theirs = (np.linalg.eigvalsh(t) for t in (declared.inertia, expected.inertia))
    if not (np.all(mine > 0) and np.all(theirs > 0)):
        return None
    ratios = mine / theirs
    if not np.all((ratios <= AGREEMENT) & (ratios >= 1 / AGREEMENT)):
        return None
    low, high = corners.min(axis=0), corners.max(axis=0)
    if not np.all((declared.com >= low) & (declared.com <= high)):
        return None
    shapes = link.link.collisions if link.link.collisions else link.link.visuals
    cad = any(isinstance(s.geometry, model.Mesh) for s in shapes)
    return {"cad": cad, "size": float(np.max(high - low))}


def _robot_files(package: str) -> list[tuple[str, Path, Path]]:
    from inertia_kit.lint.discovery import expand_paths

    folder = package_folder(package)
    if folder is None:
        print(f"{package}: not installed, left out", file=sys.stderr)
        return []
    return [(package, folder, path) for path in sorted(expand_paths([folder]))]


def _load(folder: Path, path: Path):
    from inertia_kit.description.loader import load
    from inertia_kit.errors import InputError

    try:
        robot = load(path, package_paths=[folder])
    except InputError:
        return None
    return None if robot.fragment or not robot.links else robot


def _hash(*parts: str) -> str:
    return hashlib.sha1("\0".join(parts).encode()).hexdigest()


def survey(job: tuple[str, Path, Path]) -> list[dict]:
    """The population's links of one robot file."""
    package, folder, path = job
    robot = _load(folder, path)
    if robot is None:
        return []
    try:
        analysis, findings = _lint(robot, _loader())
    except Exception as error:  # reported; the benchmark goes on
        print(f"{path}: {type(error).__name__}: {error}", file=sys.stderr)
        return []
    loud = {f.link for f in findings if _loud(f)}
    names = [link.name for link in robot.links]
    found = []
    for link in analysis.links:
        if link.name in loud or names.count(link.name) != 1:
            continue
        agrees = _agrees(link)
        if agrees is None:
            continue
        values = Values.of(link.link.inertial)
        identity_key = _hash(link.name, repr(values.mass), values.tensor.tobytes().hex())
        relative = str(path.relative_to(folder))
        found.append(
            {
                "package": package,
                "folder": str(folder),
                "file": str(path),
                "relative": relative,
                "link": link.name,
                "key": identity_key,
                "order": _hash(relative, link.name),
                **agrees,
            }
        )
    return found


def sample(population: list[dict], per_robot: int, per_package: int) -> list[dict]:
    """Distinct links, at most ``per_robot`` per file and ``per_package`` per package, by hash."""
    seen: set[str] = set()
    by_file: dict[str, int] = defaultdict(int)
    by_package: dict[str, int] = defaultdict(int)
    chosen = []
    # every file's first link before any file's second: spread over the robots of a package
    ranked = sorted(population, key=lambda c: (c["package"], c["order"]))
    rank_in_file: dict[str, int] = defaultdict(int)
    for case in ranked:
        case["rank"] = rank_in_file[case["file"]]
        rank_in_file[case["file"]] += 1
    for case in sorted(ranked, key=lambda c: (c["package"], c["rank"], c["order"])):
        if case["key"] in seen:
            continue
        if by_file[case["file"]] >= per_robot or by_package[case["package"]] >= per_package:
            continue
        seen.add(case["key"])
        by_file[case["file"]] += 1
        by_package[case["package"]] += 1
        chosen.append(case)
    return chosen


# --- the cases ----------------------------------------------------------------------------


def _neighbour(analysis, link) -> Values | None:
    from inertia_kit.analysis.declared import declared

    candidates = []
    if link.parent is not None and link.parent.parent in analysis.by_name:
        candidates.append(analysis.by_name[link.parent.parent])
    candidates += [analysis.by_name[j.child] for j in link.children if j.child in analysis.by_name]
    for other in candidates:
        if declared(other.link) is not None and isinstance(other.link.inertial.mass, float):
            return Values.of(other.link.inertial)
    return None


#: rules that speak of one defect of a link: which of them does depends on its neighbours
FAMILIES = {"IN013": "copied", "IN066": "copied"}


def _subject(finding) -> tuple:
    """The link and the defect a finding is about, whatever its severity."""
    if finding.code == "IN068" and "original" in (getattr(finding, "expected", None) or {}):
        return (finding.link, "copied")  # the six values of another link, for its mass
    return (finding.link, FAMILIES.get(finding.code, finding.code))


def changes_elsewhere(
    before: list, after: list, planted: str, body: frozenset[str] = frozenset()
) -> tuple[list, list, list, list]:
    """
    The findings on links other than ``planted``: new (``link:code``), raised and lowered in
    severity, and new weighed findings on the links of ``body``, welded to ``planted``
    (module doc).
    """
    severities: dict[tuple, set[int]] = defaultdict(set)
    for f in before:
        severities[_subject(f)].add(int(f.severity))
    new, raised, lowered, welded = set(), set(), set(), set()
    for f in after:
        if f.link == planted or f.link is None:
            continue  # on the planted link, or on none (a twin pair the file cannot judge)
        known = severities.get(_subject(f))
        if not known and f.weighed and f.link in body:
            welded.add(f"{f.link}:{f.code}")
        elif not known:
            new.add(f"{f.link}:{f.code}")
        elif int(f.severity) > max(known):
            raised.add(f"{f.link}:{f.code}")
        elif int(f.severity) < min(known):
            lowered.add(f"{f.link}:{f.code}")
    return sorted(new), sorted(raised), sorted(lowered), sorted(welded)


def plant(jobs: list[dict]) -> list[dict]:
    """Every slip on every chosen link of one robot file (``jobs`` share the file)."""
    first = jobs[0]
    robot = _load(Path(first["folder"]), Path(first["file"]))
    load = _loader()
    analysis, findings = _lint(robot, load)
    results = []
    for job in jobs:
        name = job["link"]
        index = next(i for i, link in enumerate(robot.links) if link.name == name)
        link = robot.links[index]
        true = Values.of(link.inertial)
        neighbour = _neighbour(analysis, analysis.by_name[name])
        for kind in KINDS:
            if kind == "neighbour":
                if neighbour is None:
                    continue
                slipped = neighbour.replace()
            else:
                slipped = SLIPS[kind](true)
            if _same(true, slipped):
                continue  # the slip changes nothing here (a COM at the origin): no case
            links = (*robot.links[:index], planted(link, slipped), *robot.links[index + 1 :])
            try:
                slipped_analysis, after = _lint(dataclasses.replace(robot, links=links), load)
                seen = visible(kind, slipped_analysis.by_name[name], job["size"])
                crash = None
            except Exception as error:  # a crash is a result too
                after, crash, seen = [], f"{type(error).__name__}: {error}", False
            on_link = [f for f in after if f.link == name and _loud(f)]
            body = (
                frozenset(m.name for m in slipped_analysis.group_of(name))
                if crash is None
                else frozenset()
            )
            elsewhere, raised, lowered, welded = changes_elsewhere(findings, after, name, body)
            own = OWN_RULE[kind]
            named = own is not None and any(
                f.code in (own, *ALSO_NAMED_BY.get(own, ())) for f in on_link
            )
            equivalent = (
                own is not None
                and not named
                and any(f.code in FORENSIC and restored(f, true) for f in on_link)
            )
            results.append(
                {
                    "package": job["package"],
                    "file": job["relative"],
                    "link": name,
                    "cad": job["cad"],
                    "kind": kind,
                    "identifiable": seen,
                    "old_identifiable": identifiable(true, slipped, job["size"]),
                    "detected": bool(on_link),
                    "named": named or equivalent,
                    "equivalent": equivalent,
                    "reading": com_reading(on_link, true, job["size"]),
                    "codes": sorted({f"{f.code}:{f.severity}" for f in after if f.link == name}),
                    "elsewhere": elsewhere,
                    "raised": raised,
                    "lowered": lowered,
                    "welded": welded,
                    "crash": crash,
                }
            )
    return results


def com_reading(on_link: list, true: Values, size: float) -> str | None:
    """
    What IN067 says of a planted centre of mass slip: ``right`` (its corrected point is the
    true one, or one IN067 cannot tell from it: ``x`` negated for a mirrored ``(x, 1e-4, 0)``),
    ``wrong`` (another point), ``None`` (no IN067 finding).
    """
    from inertia_kit.analysis.forensics.com_slip import SAME_POINT

    found = next((f for f in on_link if f.code == "IN067"), None)
    if found is None:
        return None
    gap = float(np.linalg.norm(np.asarray(found.expected["xyz"]) - true.xyz))
    return "right" if gap <= SAME_POINT * size else "wrong"


def com_table(cases: list[dict]) -> list[str]:
    """Of the identifiable centre of mass slips, how many IN067 undoes rightly, or wrongly."""
    lines = [
        "IN067 (com-slip) readings of the identifiable centre of mass slips",
        f"{'slip':<14}{'ident.':>7}{'right':>8}{'wrong':>8}",
    ]
    for kind in COM_READINGS:
        ident = [c for c in cases if c["kind"] == kind and c["identifiable"]]
        right = sum(c.get("reading") == "right" for c in ident)
        wrong = sum(c.get("reading") == "wrong" for c in ident)
        lines.append(
            f"{kind:<14}{len(ident):>7}{_percent(right, len(ident)):>8}"
            f"{_percent(wrong, len(ident)):>8}"
        )
    return lines


def _same(a: Values, b: Values) -> bool:
    return (
        a.mass == b.mass
        and np.array_equal(a.xyz, b.xyz)
        and np.array_equal(a.rpy, b.rpy)
        and np.array_equal(a.tensor, b.tensor)
    )


# --- the report ---------------------------------------------------------------------------


def _percent(part: int, whole: int) -> str:
    return "  -  " if whole == 0 else f"{100 * part / whole:4.0f} %"


def table(cases: list[dict], title: str) -> list[str]:
    lines = [
        title,
        f"{'slip':<14}{'cases':>6}{'ident.':>7}{'old id.':>8}{'detected':>10}"
        f"{'det. ident.':>12}{'named/ident.':>13}{'equiv.':>7}  {'own rule':<9}"
        f"{'untouched+':>10}",
    ]
    rows = [(kind, [c for c in cases if c["kind"] == kind]) for kind in KINDS]
    rows.append(("overall", cases))
    for kind, group in rows:
        ident = [c for c in group if c["identifiable"]]
        own = OWN_RULE.get(kind, "")
        named = "no rule" if kind != "overall" and own is None else ""
        named_share = (
            "  -  "
            if kind == "overall" or own is None
            else _percent(sum(c["named"] for c in ident), len(ident))
        )
        if kind == "overall":
            named_cases = [c for c in ident if OWN_RULE[c["kind"]] is not None]
            named_share = _percent(sum(c["named"] for c in named_cases), len(named_cases))
        lines.append(
            f"{kind:<14}{len(group):>6}{len(ident):>7}"
            f"{sum(c.get('old_identifiable', False) for c in group):>8}"
            f"{_percent(sum(c['detected'] for c in group), len(group)):>10}"
            f"{_percent(sum(c['detected'] for c in ident), len(ident)):>12}"
            f"{named_share:>13}{sum(c.get('equivalent', False) for c in ident):>7}"
            f"  {(own or named):<9}"
            f"{sum(bool(c['elsewhere']) for c in group):>10}"
        )
    return lines


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="a small sample (~1 min)")
    parser.add_argument("--save", type=Path, help="write every case to this JSON file")
    parser.add_argument("--only", action="append", help="this package only (repeatable)")
    parser.add_argument("-j", "--jobs", type=int, default=2, help="processes (default 2)")
    args = parser.parse_args()
    began = time.monotonic()
    files = [job for package in args.only or PACKAGES for job in _robot_files(package)]
    if args.quick:  # a few robot files per package, chosen by hash
        per_package: dict[str, list] = defaultdict(list)
        for job in sorted(files, key=lambda j: _hash(str(j[2].relative_to(j[1])))):
            if len(per_package[job[0]]) < 4:
                per_package[job[0]].append(job)
        files = [job for jobs in per_package.values() for job in jobs]
    per_robot, cap = (
        (QUICK_PER_ROBOT, QUICK_PER_PACKAGE) if args.quick else (PER_ROBOT, PER_PACKAGE)
    )
    with ProcessPoolExecutor(max_workers=args.jobs) as pool:
        population = [c for found in pool.map(survey, files) for c in found]
        chosen = sample(population, per_robot, cap)
        by_file: dict[str, list[dict]] = defaultdict(list)
        for case in chosen:
            by_file[case["file"]].append(case)
        results = [r for found in pool.map(plant, list(by_file.values())) for r in found]
    results.sort(key=lambda r: (r["package"], r["file"], r["link"], KINDS.index(r["kind"])))
    counts = defaultdict(int)
    for case in chosen:
        counts[case["package"], case["cad"]] += 1
    print(
        f"population: {len(population)} agreeing silent links in {len(files)} robot files; "
        f"{len(chosen)} distinct links taken (at most {per_robot} per file, {cap} per package)"
    )
    for package in sorted({p for p, _ in counts}):
        print(f"  {package}: {counts[package, True]} CAD, {counts[package, False]} primitive")
    print()
    for title, group in (
        ("CAD links (meshes)", [r for r in results if r["cad"]]),
        ("primitive links", [r for r in results if not r["cad"]]),
        ("all links", results),
    ):
        print("\n".join(table(group, title)))
        print()
    print("\n".join(com_table(results)))
    print()
    elsewhere = defaultdict(int)
    for r in results:
        for item in r["elsewhere"]:
            elsewhere[r["kind"], item.split(":")[1]] += 1
    if elsewhere:
        print("new findings on untouched links (slip, rule: cases):")
        for (kind, code), n in sorted(elsewhere.items()):
            print(f"  {kind} {code}: {n}")
    for change, what in (
        ("raised", "findings on untouched links whose severity raised"),
        ("lowered", "findings on untouched links whose severity lowered"),
        ("welded", "new weighed findings on links welded to the slipped one"),
    ):
        changed = defaultdict(int)
        for r in results:
            for item in r.get(change, ()):
                changed[r["kind"], item.split(":")[1]] += 1
        if changed:
            print(f"{what} (slip, rule: cases):")
            for (kind, code), n in sorted(changed.items()):
                print(f"  {kind} {code}: {n}")
    crashes = [r for r in results if r["crash"]]
    if crashes:
        print(f"{len(crashes)} cases crashed the linter, e.g. {crashes[0]['crash']}")
    print(f"{len(results)} cases in {time.monotonic() - began:.0f} s ({args.jobs} processes)")
    if args.save:
        args.save.write_text(json.dumps(results, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
