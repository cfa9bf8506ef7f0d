"""
The review page's data: a robot in its zero pose, each link with its drawing, its declared and
geometry-derived mass properties as equivalent boxes, and its findings, as JSON-ready values
(the scene contract: SI units, right-handed z-up, 4×4 transforms as 16 row-major floats).

The robot is linted exactly as ``inertia-lint`` lints it (:func:`~inertia_kit.lint.paths.
lint_paths`: the same configuration, ``select``/``ignore``, engines), and analysed as the rules
analyse it (:func:`~inertia_kit.analysis.links.analyse`).
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from inertia_kit.analysis.links import LinkAnalysis, analyse
from inertia_kit.description import model
from inertia_kit.errors import ConfigError, InputError
from inertia_kit.fixes.masses import DEFAULT_DENSITY
from inertia_kit.lint.findings import Finding
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.mass import MassProperties
from inertia_kit.view.boxes import equivalent_box, principal_directions
from inertia_kit.view.display_meshes import DEFAULT_TRIANGLE_BUDGET, MeshTable, TriangleReader
from inertia_kit.view.pose import zero_pose

FORMAT = 1


def build_scene(
    path: str | Path,
    *,
    package_paths: Sequence[str | Path] = (),
    xacro_args: dict[str, str] | None = None,
    config: str | Path | None = None,
    select: Sequence[str] = (),
    ignore: Sequence[str] = (),
    engines: Sequence[str] | None = None,
    xacro_limits: Mapping[str, float] | None = None,
    triangle_budget: int = DEFAULT_TRIANGLE_BUDGET,
    read_triangles: TriangleReader | None = None,
    redact_environment: bool | None = None,
) -> dict[str, Any]:
    """
    The scene of the robot file ``path`` for the review page (the contract in the module).

    The options are ``inertia-lint``'s (:func:`~inertia_kit.lint.paths.lint_paths`);
    ``triangle_budget`` caps the triangles the page carries (each distinct mesh once), meshes
    over it decimated for display; ``read_triangles`` reads a mesh file for display (default:
    as the analysis reads it); ``redact_environment`` (``None``: as configured) keeps what the
    environment gave the xacro expansion out of the scene
    (:mod:`~inertia_kit.description.redaction`).

    Raises ``InputError`` (file and line) for a file that is not a readable robot, as
    ``inertia-lint`` reports it, and ``ConfigError`` for a bad configuration or option.
    """
    from inertia_kit.description.loader import load
    from inertia_kit.description.xacro_limits import XacroLimits
    from inertia_kit.lint.config_files import ConfigFinder
    from inertia_kit.lint.paths import lint_paths

    file = Path(path)
    if os.path.isdir(file):
        raise InputError("is a folder: give one robot file (.urdf or .xacro)", file)
    if triangle_budget < 1:
        raise ConfigError(
            f"the triangle budget must be a positive number of triangles, got {triangle_budget}"
        )
    results = lint_paths(
        [file],
        config=config,
        select=select,
        ignore=ignore,
        xacro_args=xacro_args,
        package_paths=package_paths,
        engines=engines,
        xacro_limits=xacro_limits,
        fix=False,
        jobs=1,
    )
    result = results[0]
    if result.error is not None:
        raise result.error
    if result.fragment:
        raise InputError("is a xacro fragment (macros and properties, no links): no robot", file)
    found = ConfigFinder(config).for_file(file)
    robot = load(
        file,
        xacro_args=xacro_args,
        package_paths=package_paths,
        xacro_limits=XacroLimits.resolve(found.xacro, xacro_limits),
    )
    analysis = analyse(robot)
    poses = zero_pose(robot)
    table = MeshTable() if read_triangles is None else MeshTable(read_triangles)
    names = {link.name for link in robot.links}
    by_link: dict[str, list[Finding]] = {}
    elsewhere = []
    for finding in result.findings:
        if finding.link in names:
            by_link.setdefault(finding.link, []).append(finding)  # type: ignore[arg-type]
        else:
            elsewhere.append(finding)
    links = [
        _link_record(link, poses[link.name], table, by_link.get(link.name, []))
        for link in analysis.links
    ]
    decimated = table.within_budget(triangle_budget)
    scene = {
        "format": FORMAT,
        "robot": robot.name or file.name,
        "file": str(file),
        "links": links,
        "meshes": [mesh.to_json() for mesh in table.meshes],
        "findings_elsewhere": [_finding_record(f) for f in elsewhere],
        "budget": {
            "triangles": sum(mesh.triangles for mesh in table.meshes),
            "limit": triangle_budget,
            "decimated": decimated,
        },
    }
    if found.redact_environment if redact_environment is None else redact_environment:
        scene = _redacted(scene, robot.environment_values)
    return scene


def _redacted(scene: dict[str, Any], values: Sequence[str]) -> dict[str, Any]:
    """``scene`` with ``values`` kept out of every text and number, but the meshes' triangles
    (base64 of binary data: any four letters may occur there by chance)."""
    from inertia_kit.description.redaction import Redaction

    redaction = Redaction().with_values(values)
    binary = ("positions", "indices")
    meshes = [
        {
            **redaction.apply({k: v for k, v in mesh.items() if k not in binary}),
            **{k: mesh[k] for k in binary},
        }
        for mesh in scene["meshes"]
    ]
    return {**redaction.apply({k: v for k, v in scene.items() if k != "meshes"}), "meshes": meshes}


def _link_record(
    link: LinkAnalysis, world: np.ndarray, table: MeshTable, findings: list[Finding]
) -> dict[str, Any]:
    shown = "visual" if link.link.visuals else "collision" if link.link.collisions else None
    shapes = link.link.visuals or link.link.collisions
    visuals = [record for record in map(table.shape_visual, shapes) if record is not None]
    declared = link.declared
    geometry = _geometry_record(link)
    volume = link.geometry.volume
    implied = (
        declared.mass / volume
        if declared is not None and math.isfinite(declared.mass) and volume > 0
        else None
    )
    worst = max((f.severity for f in findings), default=None)
    return {
        "name": link.name,
        "parent": None if link.parent is None else link.parent.parent,
        "joint": None if link.parent is None else _joint_record(link.parent),
        "world": _floats(world),
        "shown": shown,
        "visuals": visuals,
        "declared": None if declared is None else _declared_record(link.link, declared),
        "geometry": geometry,
        "implied_density": _finite(implied),
        "findings": [_finding_record(f) for f in findings],
        "worst": None if worst is None else str(worst),
    }


def _mass_record(body: MassProperties) -> dict[str, Any]:
    """
    Mass, COM, the tensor about the COM in the link's axes (``tensor``: URDF's six values,
    ``ixy = -∫ x y dm``), principal moments and axes (``along``: the link axis each lies along,
    :func:`~inertia_kit.view.boxes.principal_directions`), and the equivalent box (sides along
    the principal axes, in moment order) or why there is none.
    """
    box = equivalent_box(body)
    tensor = body.inertia
    return {
        "mass": _finite(body.mass),
        "com": _floats(body.com),
        "tensor": {name: _finite(float(tensor[i, j])) for name, (i, j) in _TENSOR_ENTRIES.items()},
        "moments": _floats(box.moments),
        "axes": _floats(box.axes),
        "along": principal_directions(box),
        "box": None if box.sizes is None else _floats(box.sizes),
        "problem": box.problem,
    }


#: the six values of a tensor, as the page shows them: the moments, then the products
_TENSOR_ENTRIES = {
    "ixx": (0, 0), "iyy": (1, 1), "izz": (2, 2), "ixy": (0, 1), "ixz": (0, 2), "iyz": (1, 2)
}  # fmt: skip


def _declared_record(link: model.Link, body: MassProperties) -> dict[str, Any]:
    """
    The declared mass properties in the link's axes, and ``rpy``: the ``<inertial>``'s
    ``<origin rpy>`` the six values are written in (turned into the link's axes here), so the
    panel can say when its numbers are not the file's.
    """
    rpy = link.inertial.origin.rpy if link.inertial is not None else (0.0, 0.0, 0.0)
    return _mass_record(body) | {"rpy": _floats(rpy)}


def _geometry_record(link: LinkAnalysis) -> dict[str, Any] | None:
    """
    The geometry's mass properties at uniform density (the values IN020/IN021 compare with):
    at the declared mass when it is a positive number, else at the default density.
    """
    geometry = link.geometry
    unit = geometry.unit
    if unit is None or not unit.mass > 0:
        return None
    declared = link.declared
    if declared is not None and declared.mass > 0 and math.isfinite(declared.mass):
        body = unit.with_mass(declared.mass)
        basis = (
            f"{geometry.describe()} at uniform density, scaled to the declared "
            f"{fmt(declared.mass)} kg"
        )
    else:
        body = unit.with_mass(DEFAULT_DENSITY * unit.mass)
        why = "no declared mass" if declared is None else "the declared mass is not positive"
        basis = f"{geometry.describe()} at {fmt(DEFAULT_DENSITY)} kg/m³ ({why})"
    return _mass_record(body) | {"density": _finite(body.mass / unit.mass), "basis": basis}


def _joint_record(joint: model.Joint) -> dict[str, Any]:
    from inertia_kit.engines.lumping import joint_pose

    origin = joint_pose(joint)
    axis = joint.axis if isinstance(joint.axis, tuple) else None
    limit = joint.limit
    return {
        "name": joint.name,
        "type": joint.type,
        # a joint origin that is not a number: drawn at its parent's frame (IN004 says why)
        "origin": _floats(np.eye(4) if origin is None else origin),
        # URDF's default axis when absent; a broken one (IN004) is drawn as the default too
        "axis": list(axis) if axis is not None else [1.0, 0.0, 0.0],
        "lower": None if limit is None else _finite(limit.lower),
        "upper": None if limit is None else _finite(limit.upper),
    }


#: what the panel shows of a finding: the keys of its JSON (inertia-lint --output-format json)
_FINDING_KEYS = (
    "code",
    "name",
    "severity",
    "message",
    "detail",
    "help",
    "file",
    "line",
    "column",
)


def _finding_record(finding: Finding) -> dict[str, Any]:
    data = finding.to_json()
    return {key: data[key] for key in _FINDING_KEYS}


def _finite(value: Any) -> float | None:
    """A number JSON can carry (``NaN`` and infinities are not JSON), else ``None``."""
    return float(value) if isinstance(value, int | float) and math.isfinite(value) else None


def _floats(values: Any) -> list[float | None]:
    """An array flattened row-major, each entry JSON-ready."""
    return [_finite(float(v)) for v in np.asarray(values, dtype=np.float64).ravel()]
