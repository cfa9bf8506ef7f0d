"""
IN072 against the real Drake: one URDF per defect (and clean ones), each loaded as a Drake user
loads a robot for simulation (``pydrake``: ``Parser`` into a ``MultibodyPlant`` with a
``SceneGraph``, Drake's default discrete plant (1 ms steps), the root link welded to the world
unless it is ``world``, ``Finalize``, then one simulation step) and linted with
``--engine drake``. The predicted verdict must be what Drake does, and the quoted message what it
says.

Drake's verdicts: ``refuses`` (the parser, the plant or forward dynamics throws: the first
refusal IN072 predicts must quote the exception), ``changes`` (it loads and logs warnings: the
IN072 warnings must quote exactly those), ``loads`` (silent: no IN072 finding). Drake writes its
parser diagnostics as ``<file>:<line>: error|warning: <message>``: the line must be the
finding's, the message the finding's ``engine_message`` (which IN072 writes on one line: white
space runs compare as one space, and principal moments, which Eigen's and LAPACK's eigensolvers
may round differently in the last bit, to 1e-12).

Each case loads in this process (about 5 ms): Drake's assertion failures reach Python as
exceptions (``SystemExit`` for a ``DRAKE_THROW_UNLESS``), none aborts.
"""

from __future__ import annotations

import base64
import importlib.metadata
import json
import logging
import math
import re
from pathlib import Path

import numpy as np
import pytest
from kit import urdf
from kit.meshes import ascii_stl, binary_stl, box_triangles, obj
from kit.urdf import box, collision, cylinder, inertial, joint, link, mesh, sphere, visual

from inertia_kit.engines import drake_reading
from inertia_kit.lint.runner import Selection, lint_file

try:  # absent, or present but unusable (a wheel for a newer glibc): skip, saying which
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
    from pydrake.multibody.tree import BodyIndex
    from pydrake.systems.analysis import Simulator
    from pydrake.systems.framework import DiagramBuilder
except ImportError as error:
    pytest.skip(
        f"drake is not usable here ({error}): pip install drake==1.51.1 (wheels for Linux "
        "x86_64 with glibc >= 2.34 and macOS arm64 with CPython >= 3.13); IN072's predictions "
        "are then checked against Drake's sources only",
        allow_module_level=True,
    )

DRAKE_VERSION = drake_reading.VERSION
STEP = 0.001  # s: MultibodyPlantConfig's default, a discrete plant (SAP, lagged contact)

# --- files --------------------------------------------------------------------------------------

# a 0.1 × 0.2 × 0.3 m box, centred: 12 outward-wound triangles
BOX = box_triangles((0.1, 0.2, 0.3), low=(-0.05, -0.1, -0.15))


def gltf(triangles) -> str:
    """A glTF 2.0 file holding the triangles, its one buffer inline (base64)."""
    flat = np.asarray(triangles, dtype=np.float32).reshape(-1, 3)
    vertices, index = np.unique(flat, axis=0, return_inverse=True)
    points, indices = vertices.tobytes(), index.reshape(-1).astype("<u2").tobytes()
    data = points + indices
    return json.dumps(
        {
            "asset": {"version": "2.0"},
            "buffers": [
                {
                    "uri": "data:application/octet-stream;base64,"
                    + base64.b64encode(data).decode(),
                    "byteLength": len(data),
                }
            ],
            "bufferViews": [
                {"buffer": 0, "byteOffset": 0, "byteLength": len(points), "target": 34962},
                {
                    "buffer": 0,
                    "byteOffset": len(points),
                    "byteLength": len(indices),
                    "target": 34963,
                },
            ],
            "accessors": [
                {
                    "bufferView": 0,
                    "componentType": 5126,
                    "count": len(vertices),
                    "type": "VEC3",
                    "min": vertices.min(axis=0).tolist(),
                    "max": vertices.max(axis=0).tolist(),
                },
                {"bufferView": 1, "componentType": 5123, "count": len(flat), "type": "SCALAR"},
            ],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
            "nodes": [{"mesh": 0}],
            "scenes": [{"nodes": [0]}],
            "scene": 0,
        }
    )


DAE = """<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="1"/><up_axis>Z_UP</up_axis></asset>
</COLLADA>
"""

PACKAGE_XML = """<?xml version="1.0"?>
<package format="2"><name>robot</name><version>1.0.0</version><description>a test package
</description><maintainer email="a@example.com">a</maintainer><license>MIT</license></package>
"""

FILES: dict[str, bytes | str] = {
    "box.stl": binary_stl(BOX),
    "BOX.STL": binary_stl(BOX),
    "box_ascii.stl": ascii_stl(BOX),
    "empty.stl": b"",
    "box.obj": obj(BOX),
    "BOX.OBJ": obj(BOX),
    "box.gltf": gltf(BOX),
    "box.dae": DAE,
    "robot/package.xml": PACKAGE_XML,
    "robot/meshes/box.obj": obj(BOX),
}

# --- robots ---------------------------------------------------------------------------------


def robot(*parts: str) -> str:
    """One part a line, so that a parser diagnostic's line names one element."""
    return urdf.robot(*parts, sep="\n")


def arm(*body: str, kind: str = "revolute") -> str:
    """A root `base` and one link `arm` moving on it, holding ``body``."""
    return robot(link("base"), joint("base", "arm", kind), link("arm", *body))


def fixed(parent: str, child: str, xyz: str = "0 0 0.1") -> str:
    return joint(parent, child, "fixed", xyz=xyz)


def about(axis: str, parent: str, child: str, xyz: str = "0 0 0") -> str:
    """A revolute joint turning about ``axis``."""
    return (
        f'<joint name="j_{child}" type="revolute"><parent link="{parent}"/><child link="{child}"/>'
        f'<origin xyz="{xyz}"/><axis xyz="{axis}"/>{urdf.LIMIT}</joint>'
    )


def raw_inertial(mass: str, **attributes: str) -> str:
    """An ``<inertial>`` written as given: ``mass=None`` leaves out ``<mass>``."""
    values = {"ixx": "0.01", "ixy": "0", "ixz": "0", "iyy": "0.01", "iyz": "0", "izz": "0.01"}
    values.update(attributes)
    tensor = " ".join(f'{k}="{v}"' for k, v in values.items() if v is not None)
    head = "" if mass is None else f'<mass value="{mass}"/>'
    return f"<inertial>{head}<inertia {tensor}/></inertial>"


def moving(child: str, limit: str = "", *, dynamics: str = "", kind: str = "revolute") -> str:
    """A joint from `base` about z with ``limit`` attributes replacing the kit's (and
    ``dynamics``), and its link ``child`` of 1 kg."""
    values = {"lower": "-1", "upper": "1", "effort": "10", "velocity": "1"}
    values.update(re.findall(r'(\w+)="([^"]*)"', limit))
    limits = " ".join(f'{k}="{v}"' for k, v in values.items())
    extra = f"<dynamics {dynamics}/>" if dynamics else ""
    return (
        f'<joint name="j_{child}" type="{kind}"><parent link="base"/><child link="{child}"/>'
        f'<axis xyz="0 0 1"/><limit {limits}/>{extra}</joint>\n{link(child, UNIT)}'
    )


UNIT = inertial(1, 0.01)  # 1 kg, 0.01 kg·m² about every axis
BAD_TRIANGLE = inertial(1, 0.001, 0.001, 0.01)
NEGATIVE_EIGEN = inertial(1, 0.01, ixy=0.02)
POINT = inertial(1, 0)  # 1 kg, no moment of inertia

# name -> (urdf, the verdict Drake gives it: "loads" | "changes" | "refuses")
CASES: dict[str, tuple[str, str]] = {
    # clean
    "clean-arm": (arm(UNIT), "loads"),
    "clean-obj-collision": (arm(UNIT, collision(mesh("box.obj"))), "loads"),
    "clean-uppercase-obj": (arm(UNIT, collision(mesh("BOX.OBJ"))), "loads"),
    "clean-gltf-collision": (arm(UNIT, collision(mesh("box.gltf"))), "loads"),
    "clean-package-uri": (arm(UNIT, collision(mesh("package://robot/meshes/box.obj"))), "loads"),
    "visual-stl-dae-kept": (
        arm(UNIT, visual(mesh("box.stl")), visual(mesh("box.dae"))),
        "loads",
    ),
    "collision-primitives": (
        arm(
            UNIT, collision(box(0.1, 0.2, 0.3)), collision(cylinder(0.1, 0.2)), collision(sphere(0))
        ),
        "loads",
    ),
    "mesh-scale-one-number": (arm(UNIT, collision(mesh("box.obj", scale="0.5"))), "loads"),
    "mesh-scale-negative": (arm(UNIT, collision(mesh("box.obj", scale="-1 1 1"))), "loads"),
    # <inertial> values as Drake reads them
    "triangle-exactly-on-bound": (arm(inertial(1, 0.25, 0.25, 0.5)), "loads"),
    "moment-negative-within-epsilon": (arm(inertial(1, "-1e-16", 0.01, 0.01)), "loads"),
    "tiny-moments": (arm(inertial("1e-6", "1e-12")), "loads"),
    "tinier-moments": (arm(inertial("1e-9", "1e-20")), "loads"),
    "huge-values": (arm(inertial("1e20", "1e20")), "loads"),
    "point-mass-off-axis": (arm(inertial(1, 0, xyz="0.1 0 0")), "loads"),
    "missing-ixx-reads-0": (arm(raw_inertial("1", ixx=None)), "loads"),
    "missing-products-read-0": (arm(raw_inertial("1", ixy=None, ixz=None, iyz=None)), "loads"),
    "mass-with-unit-reads-2": (arm(raw_inertial("2kg")), "loads"),
    "mass-with-comma-reads-1": (arm(raw_inertial("1,5")), "loads"),
    "mass-leading-point": (arm(raw_inertial(".5")), "loads"),
    "mass-trailing-point-and-spaces": (arm(raw_inertial(" 5. ")), "loads"),
    "mass-not-a-number": (arm(raw_inertial("abc")), "refuses"),
    "mass-nan": (arm(raw_inertial("nan")), "refuses"),
    "mass-inf": (arm(raw_inertial("inf")), "refuses"),
    "mass-overflows": (arm(raw_inertial("1e999")), "refuses"),
    "mass-empty": (arm(raw_inertial("")), "refuses"),
    "mass-two-numbers": (arm(raw_inertial("1 2")), "refuses"),
    "mass-dangling-exponent": (arm(raw_inertial("1e")), "refuses"),
    "izz-inf": (arm(raw_inertial("1", izz="inf")), "refuses"),
    "inertial-origin-two-numbers": (
        arm(
            '<inertial><origin xyz="0 0"/><mass value="1"/>'
            '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>'
        ),
        "refuses",
    ),
    "mass-subnormal-sphere-radius-0": (arm(raw_inertial("1e-320")), "refuses"),
    "mass-hex-reads-0": (arm(raw_inertial("0x10")), "changes"),
    "mass-underflows-to-0": (arm(raw_inertial("1e-400")), "changes"),
    "no-mass-element": (arm(raw_inertial(None)), "changes"),
    "mass-zero": (arm(inertial(0, 0.01)), "changes"),
    "mass-negative": (arm(inertial(-1, 0.01)), "changes"),
    "mass-negative-no-tensor": (arm(inertial(-1, 0)), "changes"),
    "negative-eigenvalue": (arm(NEGATIVE_EIGEN), "changes"),
    "negative-diagonal": (arm(inertial(1, -0.01, 0.01, 0.01)), "changes"),
    "moment-negative-beyond-epsilon": (arm(inertial(1, "-4e-15", 0.001, 0.001)), "changes"),
    "triangle-broken": (arm(BAD_TRIANGLE), "changes"),
    "triangle-broken-just": (arm(inertial(1, 0.25, 0.25, "0.5000000001")), "changes"),
    # the diagonal satisfies A + B ≥ C, the principal moments (0.001, 0.001, 0.01) do not
    "triangle-broken-only-after-diagonalising": (
        arm(inertial(1, 0.001, 0.0055, 0.0055, iyz=-0.0045)),
        "changes",
    ),
    "triangle-broken-rotated-axes": (
        arm(inertial(1, 0.001, 0.001, 0.01, rpy="0.3 0.2 0.1")),
        "changes",
    ),
    "triangle-broken-com-offset": (
        arm(inertial(2, 0.001, 0.001, 0.01, xyz="0.1 0.2 0.3")),
        "changes",
    ),
    "triangle-broken-formatting": (arm(inertial(1, "1e-05", "1e-05", "1e16")), "changes"),
    "two-links-replaced": (
        robot(
            link("base", BAD_TRIANGLE),
            joint("base", "arm"),
            link("arm", NEGATIVE_EIGEN),
        ),
        "changes",
    ),
    # forward dynamics: the articulated-body hinge inertia of each moving joint
    "no-inertial-moving-leaf": (arm(), "refuses"),
    "all-zero-moving-leaf": (arm(inertial(0, 0)), "refuses"),
    "no-inertia-element-point-mass-on-axis": (
        arm(raw_inertial("1", **dict.fromkeys(("ixx", "ixy", "ixz", "iyy", "iyz", "izz")))),
        "refuses",
    ),
    "point-mass-on-revolute-axis": (arm(POINT), "refuses"),
    "rod-along-revolute-axis": (arm(inertial(1, 0.01, 0.01, 0)), "refuses"),
    "point-mass-on-continuous-axis": (arm(POINT, kind="continuous"), "refuses"),
    "point-mass-on-prismatic": (arm(POINT, kind="prismatic"), "loads"),
    "massless-prismatic": (arm(kind="prismatic"), "refuses"),
    "massless-planar": (arm(kind="planar"), "refuses"),
    "point-mass-planar": (arm(POINT, kind="planar"), "refuses"),
    "clean-planar": (arm(UNIT, kind="planar"), "loads"),
    "floating-joint-left-out": (arm(UNIT, kind="floating"), "changes"),
    "floating-joint-massless-free-body": (arm(kind="floating"), "refuses"),
    "massless-leaf-welded-to-moving-link": (
        robot(
            link("base"),
            joint("base", "arm"),
            link("arm", UNIT),
            fixed("arm", "tool"),
            link("tool"),
        ),
        "loads",
    ),
    "massless-moving-link-with-welded-mass": (
        robot(
            link("base"),
            joint("base", "arm"),
            link("arm"),
            fixed("arm", "tool"),
            link("tool", UNIT),
        ),
        "loads",
    ),
    "massless-welded-chain-to-mass": (
        robot(
            link("base"),
            joint("base", "arm"),
            link("arm"),
            fixed("arm", "f1"),
            link("f1"),
            fixed("f1", "f2", xyz="0.2 0 0"),
            link("f2", POINT),
            fixed("f2", "f3"),
            link("f3"),
        ),
        "loads",
    ),
    "point-mass-welded-on-axis": (
        robot(
            link("base"),
            joint("base", "arm"),
            link("arm"),
            fixed("arm", "tool", "0 0 0.1"),
            link("tool", POINT),
        ),
        "refuses",
    ),
    "massless-link-with-mass-outboard-on-another-axis": (
        robot(
            link("base"),
            about("0 0 1", "base", "a"),
            link("a"),
            about("1 0 0", "a", "b"),
            link("b", UNIT),
        ),
        "loads",
    ),
    "massless-link-with-mass-outboard-on-the-same-axis": (
        robot(
            link("base"),
            about("0 0 1", "base", "a"),
            link("a"),
            about("0 0 1", "a", "b"),
            link("b", UNIT),
        ),
        "refuses",
    ),
    "massless-link-same-axis-offset": (
        robot(
            link("base"),
            about("0 0 1", "base", "a"),
            link("a"),
            about("0 0 1", "a", "b", "0.2 0 0"),
            link("b", UNIT),
        ),
        "loads",
    ),
    "massless-root-welded": (robot(link("base"), joint("base", "arm"), link("arm", UNIT)), "loads"),
    "root-with-mass-welded": (
        robot(link("base", inertial(5, 0.01)), joint("base", "arm"), link("arm", UNIT)),
        "loads",
    ),
    "root-triangle-broken": (
        robot(link("base", BAD_TRIANGLE), joint("base", "arm"), link("arm", UNIT)),
        "changes",
    ),
    "world-link-fixed-base": (
        robot(
            link("world"),
            fixed("world", "base"),
            link("base", UNIT),
            joint("base", "arm"),
            link("arm", UNIT),
        ),
        "loads",
    ),
    "world-link-moving-child": (
        robot(link("world"), joint("world", "arm"), link("arm", UNIT)),
        "loads",
    ),
    "world-link-inertial-ignored": (
        robot(
            link("world", UNIT),
            fixed("world", "base"),
            link("base", UNIT),
            joint("base", "arm"),
            link("arm", UNIT),
        ),
        "changes",
    ),
    # joints
    "joint-axis-zero": (
        robot(link("base"), about("0 0 0", "base", "arm"), link("arm", UNIT)),
        "refuses",
    ),
    "joint-type-unknown": (arm(UNIT, kind="hinge"), "refuses"),
    "joint-type-drake-only": (arm(UNIT, kind="ball"), "refuses"),
    "joint-limits-inverted": (
        robot(link("base"), moving("arm", 'lower="1" upper="-1"')),
        "refuses",
    ),
    "joint-limits-equal": (robot(link("base"), moving("arm", 'lower="1" upper="1"')), "loads"),
    "continuous-limits-inverted": (
        robot(link("base"), moving("arm", 'lower="1" upper="-1"', kind="continuous")),
        "refuses",
    ),
    "prismatic-limits-inverted": (
        robot(link("base"), moving("arm", 'lower="1" upper="-1"', kind="prismatic")),
        "refuses",
    ),
    "planar-limits-ignored": (
        robot(link("base"), moving("arm", 'lower="1" upper="-1"', kind="planar")),
        "loads",
    ),
    "joint-velocity-negative": (robot(link("base"), moving("arm", 'velocity="-1"')), "refuses"),
    "joint-effort-negative-kept": (robot(link("base"), moving("arm", 'effort="-1"')), "loads"),
    "joint-effort-not-a-number": (robot(link("base"), moving("arm", 'effort="abc"')), "refuses"),
    "joint-damping-negative": (
        robot(link("base"), moving("arm", dynamics='damping="-1"')),
        "refuses",
    ),
    "prismatic-damping-negative": (
        robot(link("base"), moving("arm", dynamics='damping="-1"', kind="prismatic")),
        "refuses",
    ),
    "joint-friction-ignored": (
        robot(link("base"), moving("arm", dynamics='damping="0.1" friction="0.5"')),
        "changes",
    ),
    "joint-friction-zero": (robot(link("base"), moving("arm", dynamics='friction="0"')), "loads"),
    "limits-before-damping": (
        robot(link("base"), moving("arm", 'lower="1" upper="-1"', dynamics='damping="-1"')),
        "refuses",
    ),
    # meshes
    "collision-stl": (arm(UNIT, collision(mesh("box.stl"))), "refuses"),
    "collision-uppercase-stl": (arm(UNIT, collision(mesh("BOX.STL"))), "refuses"),
    "collision-ascii-stl": (arm(UNIT, collision(mesh("box_ascii.stl"))), "refuses"),
    "collision-empty-stl": (arm(UNIT, collision(mesh("empty.stl"))), "refuses"),
    "collision-dae": (arm(UNIT, collision(mesh("box.dae"))), "refuses"),
    "collision-file-uri-stl": (arm(UNIT, collision(mesh("file://{dir}/box.stl"))), "refuses"),
    "collision-mesh-missing": (arm(UNIT, collision(mesh("nowhere.obj"))), "refuses"),
    "collision-mesh-missing-in-folder": (
        arm(UNIT, collision(mesh("meshes/../nowhere.obj"))),
        "refuses",
    ),
    "visual-mesh-missing": (arm(UNIT, visual(mesh("nowhere.stl"))), "refuses"),
    "mesh-next-to-the-file-only": (arm(UNIT, collision(mesh("meshes/box.obj"))), "refuses"),
    "file-uri-missing": (arm(UNIT, visual(mesh("file:///nowhere/at/all.obj"))), "refuses"),
    "package-uri-unknown-package": (
        arm(UNIT, collision(mesh("package://elsewhere/box.obj"))),
        "refuses",
    ),
    "mesh-scale-zero": (arm(UNIT, visual(mesh("box.obj", scale="0 0 0"))), "refuses"),
    "mesh-scale-below-1e-8": (arm(UNIT, collision(mesh("box.obj", scale="1e-9 1 1"))), "refuses"),
    "mesh-scale-two-numbers": (arm(UNIT, collision(mesh("box.obj", scale="1 1"))), "refuses"),
    # shapes
    "collision-box-zero": (arm(UNIT, collision(box(0.1, 0, 0.1))), "refuses"),
    "visual-box-negative-height": (arm(UNIT, visual(box(0.1, 0.1, -1))), "refuses"),
    "cylinder-length-zero": (arm(UNIT, collision(cylinder(0.1, 0))), "refuses"),
    "cylinder-radius-negative": (arm(UNIT, collision(cylinder(-0.1, 1))), "refuses"),
    "capsule-length-zero": (
        arm(UNIT, collision('<capsule radius="0.1" length="0"/>')),
        "refuses",
    ),
    "sphere-radius-negative": (arm(UNIT, visual(sphere(-1))), "refuses"),
    "box-without-size": (arm(UNIT, collision("<box/>")), "refuses"),
    "box-two-sizes": (arm(UNIT, collision('<box size="1 1"/>')), "refuses"),
    "cylinder-without-length": (arm(UNIT, collision('<cylinder radius="0.1"/>')), "refuses"),
    "sphere-without-radius": (arm(UNIT, visual("<sphere/>")), "refuses"),
    "geometry-empty": (arm(UNIT, collision("")), "refuses"),
    "geometry-unknown-shape": (arm(UNIT, visual("<foo/>")), "refuses"),
    "collision-without-geometry": (arm(UNIT, "<collision/>"), "refuses"),
    "visual-without-geometry": (arm(UNIT, "<visual/>"), "refuses"),
    "robot-without-name": (arm(UNIT).replace('<robot name="r">', "<robot>"), "refuses"),
    "robot-name-before-links": (
        arm(raw_inertial("abc")).replace('<robot name="r">', "<robot>"),
        "refuses",
    ),
    # the first refusal: links in document order (inertial, visuals, collisions), then joints,
    # then forward dynamics (deepest joint first, then depth first)
    "first-in-document-order": (
        robot(
            link("base"),
            joint("base", "a1"),
            link("a1", UNIT, collision(mesh("box.stl"))),
            joint("a1", "a2"),
            link("a2", raw_inertial("abc")),
        ),
        "refuses",
    ),
    "visual-before-collision": (
        arm(UNIT, collision(mesh("box.stl")), visual(box(0, 1, 1))),
        "refuses",
    ),
    "links-before-joints": (
        robot(
            link("base"),
            about("0 0 0", "base", "arm"),
            link("arm", UNIT, collision(mesh("box.dae"))),
        ),
        "refuses",
    ),
    "parser-before-dynamics": (
        robot(
            link("base"),
            joint("base", "a1"),
            link("a1"),
            joint("base", "a2"),
            link("a2", UNIT, collision(mesh("box.stl"))),
        ),
        "refuses",
    ),
    "deepest-joint-first": (
        robot(
            link("base"),
            joint("base", "a1"),
            link("a1"),
            joint("base", "b1"),
            link("b1", UNIT),
            joint("b1", "b2"),
            link("b2"),
        ),
        "refuses",
    ),
    "same-depth-in-joint-order": (
        robot(
            link("base"),
            joint("base", "b"),
            joint("base", "a"),
            link("a"),
            link("b"),
        ),
        "refuses",
    ),
}

# --- Drake's side -----------------------------------------------------------------------------

_DIAGNOSTIC = re.compile(r"(?P<file>.+?):(?P<line>\d+): (?:error|warning): (?P<message>.*)", re.S)


def _split(text: str) -> tuple[int | None, str]:
    """A Drake diagnostic's line (``None`` when it names none) and its message."""
    found = _DIAGNOSTIC.fullmatch(text)
    if found:
        return int(found["line"]), found["message"]
    return None, text


class _Warnings(logging.Handler):
    def __init__(self):
        super().__init__(logging.WARNING)
        self.records: list[str] = []

    def emit(self, record):
        self.records.append(record.getMessage())


def outcome(path: Path, root: str | None = "base", packages: Path | None = None):
    """``(verdict, (line, message) of the refusal or None, [(line, message)] warnings, plant)``."""
    warnings = _Warnings()
    logger = logging.getLogger("drake")
    logger.addHandler(warnings)
    builder = DiagramBuilder()
    plant, _ = AddMultibodyPlantSceneGraph(builder, time_step=STEP)
    parser = Parser(plant)
    if packages is not None:
        parser.package_map().PopulateFromFolder(str(packages))
    try:
        parser.AddModels(str(path))
        if root is not None and plant.HasBodyNamed(root):
            plant.WeldFrames(plant.world_frame(), plant.GetFrameByName(root))
        plant.Finalize()
        diagram = builder.Build()
        Simulator(diagram, diagram.CreateDefaultContext()).AdvanceTo(STEP)
    except (RuntimeError, ValueError, SystemExit) as error:
        return "refuses", _split(str(error)), [_split(w) for w in warnings.records], plant
    finally:
        logger.removeHandler(warnings)
    said = [_split(w) for w in warnings.records]
    return ("changes" if said else "loads"), None, said, plant


def write_case(tmp_path: Path, text: str) -> Path:
    for name, content in FILES.items():
        target = tmp_path / name
        target.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(content, bytes):
            target.write_bytes(content)
        else:
            target.write_text(content)
    path = tmp_path / "robot.urdf"
    path.write_text(text.replace("{dir}", str(tmp_path)))
    return path


def predicted(path: Path):
    # the package `robot` is found, and so would be `meshes/box.obj` where a relative path is
    # also looked up under each package path (PyBullet's search path), which Drake does not do
    paths = [path.parent, path.parent / "robot"]
    result = lint_file(path, Selection(select=(), engines=("drake",)), package_paths=paths)
    assert result.error is None, result.error
    assert {f.code for f in result.findings} <= {"IN072"}
    return result.findings


_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:e[-+]?\d+)?")


def same_message(ours: str | None, drakes: str) -> bool:
    """
    Equal, white space runs as one space (none after ``[``), numbers alone in a word to 1e-12.
    """
    if ours is None:
        return False
    mine, theirs = ours.split(), re.sub(r"\[\s+", "[", drakes).split()
    if len(mine) != len(theirs):
        return False
    for a, b in zip(mine, theirs, strict=True):
        if a == b:
            continue
        if not (_NUMBER.fullmatch(a) and _NUMBER.fullmatch(b)):
            return False
        if not math.isclose(float(a), float(b), rel_tol=1e-12, abs_tol=1e-300):
            return False
    return True


# case -> the help texts of its findings (one per kind of event), as the matrix found them
HELPS_SEEN: dict[str, set[str]] = {}

# the words Drake uses for a package:// URI depend on the user's package map: IN072 does not
# quote them
UNQUOTED = {"package-uri-unknown-package"}


@pytest.mark.parametrize("case", list(CASES))
def test_prediction_matches_drake(case, tmp_path):
    text, expected_verdict = CASES[case]
    path = write_case(tmp_path, text)
    root = None if '<link name="world"' in text else "base"
    verdict, refusal, warnings, _ = outcome(path, root, packages=tmp_path / "robot")
    assert verdict == expected_verdict, (verdict, refusal, warnings)  # the case is what it says
    findings = predicted(path)
    HELPS_SEEN[case] = {f.help for f in findings}
    refusals = [f for f in findings if f.expected["verdict"] == "refuses"]
    changes = [f for f in findings if f.expected["verdict"] == "changes"]
    for finding in findings:
        assert finding.expected["engine"] == "drake"
        assert len(finding.message) <= 100 and "\n" not in finding.message, finding.message
        assert (
            str(finding.severity)
            == {"refuses": "error", "changes": "warning"}[finding.expected["verdict"]]
        )
    if verdict == "refuses":
        assert refusals, f"Drake refuses the model ({refusal}), IN072 predicted it loads"
        (first,) = [f for f in refusals if f.expected["first"]]
        line, message = refusal
        if case in UNQUOTED:
            assert first.expected["engine_message"] is None
            return
        assert same_message(first.expected["engine_message"], message), (
            first.expected["engine_message"],
            message,
        )
        # the one-line message has our words, the detail quotes Drake
        assert first.expected["engine_message"] not in first.message
        assert first.detail.endswith(f'Drake says: "{first.expected["engine_message"]}"')
        if line is not None:
            assert first.line == line
        return
    assert refusals == [], [f.message for f in refusals]
    unmatched = list(changes)
    for line, message in warnings:
        match = next(
            (f for f in unmatched if same_message(f.expected["engine_message"], message)), None
        )
        assert match is not None, (message, [f.expected["engine_message"] for f in unmatched])
        assert line is None or match.line == line
        unmatched.remove(match)
    assert unmatched == [], [f.message for f in unmatched]


def _body(plant, name: str):
    for index in range(plant.num_bodies()):
        body = plant.get_body(BodyIndex(index))
        if body.name() == name:
            return body
    raise KeyError(name)


@pytest.mark.parametrize(
    "case",
    [
        "triangle-broken",
        "triangle-broken-com-offset",
        "negative-eigenvalue",
        "mass-zero",
        "mass-negative",
        "mass-hex-reads-0",
        "no-mass-element",
    ],
)
def test_stand_in_sphere_is_the_one_drake_builds(case, tmp_path):
    path = write_case(tmp_path, CASES[case][0])
    *_, plant = outcome(path)
    (sphere,) = [f for f in predicted(path) if f.link == "arm"]
    spatial = _body(plant, "arm").default_spatial_inertia()
    assert spatial.get_mass() == pytest.approx(sphere.expected["mass"], rel=1e-12)
    com = spatial.get_com()
    central = spatial.CalcRotationalInertia().ShiftToCenterOfMass(spatial.get_mass(), com)
    moments = central.CalcPrincipalMomentsOfInertia()
    assert moments == pytest.approx([sphere.expected["ixx"]] * 3, rel=1e-9)
    radius = math.sqrt(sphere.expected["ixx"] / (0.4 * sphere.expected["mass"]))
    assert radius == pytest.approx(sphere.expected["radius"], rel=1e-12)


def test_declared_values_are_what_drake_reads(tmp_path):
    # the numbers Drake takes from odd texts: what IN072 predicts from them
    for case, mass in (
        ("mass-with-unit-reads-2", 2.0),
        ("mass-with-comma-reads-1", 1.0),
        ("mass-leading-point", 0.5),
        ("mass-trailing-point-and-spaces", 5.0),
    ):
        *_, plant = outcome(write_case(tmp_path, CASES[case][0]))
        assert _body(plant, "arm").default_mass() == mass
        assert drake_reading.read_numbers(re.search(r'value="([^"]*)"', CASES[case][0])[1]) == [
            mass
        ]


def test_the_matrix_covers_every_kind_of_event(tmp_path):
    from inertia_kit.lint.rules.in072_drake_verdict import HELP

    for case, (text, _) in CASES.items():
        if case not in HELPS_SEEN:  # run alone: lint what the matrix did not
            HELPS_SEEN[case] = {f.help for f in predicted(write_case(tmp_path, text))}
    assert set().union(*HELPS_SEEN.values()) == set(HELP.values())


def test_installed_drake_is_the_one_quoted():
    installed = importlib.metadata.version("drake")
    assert installed == DRAKE_VERSION, (
        f"IN072 quotes Drake {DRAKE_VERSION} (its messages carry source lines), {installed} is "
        "installed: re-run this matrix and update engines/drake_reading.py and the rule document"
    )
