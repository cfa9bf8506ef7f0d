"""
IN070 against the real MuJoCo: one URDF per defect (and clean ones), each loaded with
``mujoco.MjModel.from_xml_path`` and linted with ``--engine mujoco``. The predicted verdict must
be what MuJoCo does, and the quoted message what it says.

MuJoCo's error text is ``Error: <message>\\nElement name '<name>', id <n>[\\nThe static bodies
of the spec were fused before this error, and remain so.]`` from the compiler, or ``XML Error:
<message>\\nElement '<tag>', line <n>\\n`` from the parser. We compare ``<message>`` exactly and
the element (name, or tag and line) exactly; the framing words and the id (an index that fusion
renumbers) are dropped.
"""

from __future__ import annotations

import re
import struct
from pathlib import Path

import numpy as np
import pytest

from inertia_kit.lint.runner import Selection, lint_file

mujoco = pytest.importorskip("mujoco")


@pytest.fixture(autouse=True)
def _in_tmp_path(tmp_path, monkeypatch):
    """MuJoCo writes its warnings (`XML contains a 'NaN'`) to MUJOCO_LOG.TXT in the cwd."""
    monkeypatch.chdir(tmp_path)


# --- files --------------------------------------------------------------------------------------

# a 0.1 × 0.2 × 0.3 m box, centred: 8 vertices, 12 outward-wound triangles
_H = np.array([0.05, 0.1, 0.15])
VERTICES = (np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * _H).tolist()
FACES = [
    (0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1),
    (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3),
]  # fmt: skip


def binary_stl() -> bytes:
    records = b"".join(
        struct.pack("<12fH", 0, 0, 0, *VERTICES[a], *VERTICES[b], *VERTICES[c], 0)
        for a, b, c in FACES
    )
    return b"\0" * 80 + struct.pack("<I", len(FACES)) + records


def ascii_stl() -> str:
    facets = "".join(
        "facet normal 0 0 0\n outer loop\n"
        + "".join(f"  vertex {x!r} {y!r} {z!r}\n" for x, y, z in (VERTICES[i] for i in f))
        + " endloop\nendfacet\n"
        for f in FACES
    )
    return f"solid box\n{facets}endsolid box\n"


def obj() -> str:
    vertices = "".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in VERTICES)
    return vertices + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in FACES)


DAE = """<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="1"/><up_axis>Z_UP</up_axis></asset>
</COLLADA>
"""

FILES: dict[str, bytes | str] = {
    "box.stl": binary_stl(),
    "box_ascii.stl": ascii_stl(),
    "box.obj": obj(),
    "box.dae": DAE,
    "empty.stl": b"",
    "short.stl": b"\0" * 60,
    "padded.stl": binary_stl() + b"\0\0",
}

# --- robots ---------------------------------------------------------------------------------


def inertial(mass="1", ixx="0.01", iyy="0.01", izz="0.01", ixy="0", ixz="0", iyz="0", rpy=None):
    origin = "" if rpy is None else f'<origin rpy="{rpy}"/>'
    return (
        f'<inertial>{origin}<mass value="{mass}"/><inertia ixx="{ixx}" ixy="{ixy}" ixz="{ixz}" '
        f'iyy="{iyy}" iyz="{iyz}" izz="{izz}"/></inertial>'
    )


def collision(geometry: str, xyz: str = "0 0 0") -> str:
    return f'<collision><origin xyz="{xyz}"/><geometry>{geometry}</geometry></collision>'


def mesh(filename: str) -> str:
    return collision(f'<mesh filename="{filename}"/>')


def visual_mesh(filename: str) -> str:
    return f'<visual><geometry><mesh filename="{filename}"/></geometry></visual>'


def revolute(parent: str, child: str, kind: str = "revolute") -> str:
    return (
        f'<joint name="j_{child}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
        '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
    )


def fixed(parent: str, child: str, xyz: str = "0 0 0.1") -> str:
    return (
        f'<joint name="f_{child}" type="fixed"><parent link="{parent}"/><child link="{child}"/>'
        f'<origin xyz="{xyz}"/></joint>'
    )


def link(name: str, *body: str) -> str:
    return f'<link name="{name}">{"".join(body)}</link>'


def robot(*parts: str) -> str:
    return '<robot name="r">\n' + "\n".join(parts) + "\n</robot>\n"


def arm(*body: str) -> str:
    """A fixed base and one moving link `arm` holding ``body``."""
    return robot(link("base"), revolute("base", "arm"), link("arm", *body))


BAD_TRIANGLE = dict(ixx="0.001", iyy="0.001", izz="0.01")
NEGATIVE_EIGEN = dict(ixy="0.02")
ZERO = dict(ixx="0", iyy="0", izz="0")

# name -> (urdf, the verdict MuJoCo gives it: "loads" | "refuses", what the case is about)
CASES: dict[str, tuple[str, str]] = {
    # clean
    "clean-arm": (arm(inertial()), "loads"),
    "clean-binary-stl": (arm(inertial(), mesh("box.stl")), "loads"),
    "clean-obj": (arm(inertial(), mesh("box.obj")), "loads"),
    "clean-uppercase-stl-extension": (arm(inertial(), mesh("BOX.STL")), "loads"),
    "visual-dae-discarded": (arm(inertial(), visual_mesh("box.dae")), "loads"),
    "visual-mesh-missing-discarded": (arm(inertial(), visual_mesh("nowhere.stl")), "loads"),
    "triangle-exactly-on-bound": (arm(inertial(ixx="0.25", iyy="0.25", izz="0.5")), "loads"),
    "mass-exactly-mjminval": (arm(inertial(mass="1e-15")), "loads"),
    "eigenvalue-exactly-mjeps": (arm(inertial(ixx="1e-14")), "loads"),
    # the parser
    "no-mass-element": (
        arm('<inertial><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>'),
        "refuses",
    ),
    "no-inertia-element": (arm('<inertial><mass value="1"/></inertial>'), "refuses"),
    "inertia-attribute-missing": (
        arm(
            '<inertial><mass value="1"/><inertia ixx="1" ixz="0" iyy="1" iyz="0" izz="1"/>'
            "</inertial>"
        ),
        "refuses",
    ),
    "mass-not-a-number": (arm(inertial(mass="2kg")), "refuses"),
    "mass-nan": (arm(inertial(mass="nan")), "refuses"),
    # meshes
    "collision-dae": (arm(inertial(), mesh("box.dae")), "refuses"),
    "collision-ascii-stl": (arm(inertial(), mesh("box_ascii.stl")), "refuses"),
    "collision-empty-stl": (arm(inertial(), mesh("empty.stl")), "refuses"),
    "collision-short-stl": (arm(inertial(), mesh("short.stl")), "refuses"),
    "collision-padded-stl": (arm(inertial(), mesh("padded.stl")), "refuses"),
    "collision-mesh-missing": (arm(inertial(), mesh("nowhere.stl")), "refuses"),
    "collision-package-uri": (arm(inertial(), mesh("package://robot/meshes/box.stl")), "refuses"),
    "mesh-before-body-errors": (
        robot(
            link("base"),
            revolute("base", "a1"),
            link("a1", inertial(**BAD_TRIANGLE)),
            revolute("a1", "a2"),
            link("a2", inertial(), mesh("box.dae")),
        ),
        "refuses",
    ),
    # bodies: mass and moments
    "mass-below-mjminval": (arm(inertial(mass="1e-16")), "refuses"),
    "mass-zero": (arm(inertial(mass="0")), "refuses"),
    "mass-negative": (arm(inertial(mass="-1")), "refuses"),
    "moment-below-mjeps": (arm(inertial(ixx="5e-15")), "refuses"),
    "all-six-zero-on-moving-link": (arm(inertial(**ZERO)), "refuses"),
    "negative-eigenvalue": (arm(inertial(**NEGATIVE_EIGEN)), "refuses"),
    "negative-diagonal": (arm(inertial(ixx="-0.01")), "refuses"),
    "triangle-broken": (arm(inertial(**BAD_TRIANGLE)), "refuses"),
    # the diagonal satisfies A + B ≥ C, the principal moments (0.001, 0.001, 0.01) do not
    "triangle-broken-only-after-diagonalising": (
        arm(inertial(ixx="0.001", iyy="0.0055", izz="0.0055", iyz="-0.0045")),
        "refuses",
    ),
    "triangle-broken-rotated-axes": (arm(inertial(**BAD_TRIANGLE, rpy="0.3 0.2 0.1")), "refuses"),
    "zero-collision-box": (arm(inertial(), collision('<box size="0.1 0 0.1"/>')), "refuses"),
    "zero-cylinder-length": (
        arm(inertial(), collision('<cylinder radius="0.1" length="0"/>')),
        "refuses",
    ),
    "root-triangle-broken": (
        robot(
            link("base", inertial(**BAD_TRIANGLE)), revolute("base", "arm"), link("arm", inertial())
        ),
        "refuses",
    ),
    # no <inertial>: inertiafromgeom
    "no-inertial-no-geometry": (arm(), "refuses"),
    "no-inertial-visual-only": (
        arm('<visual><geometry><box size="0.1 0.2 0.3"/></geometry></visual>'),
        "refuses",
    ),
    "no-inertial-collision-box": (arm(collision('<box size="0.1 0.2 0.3"/>')), "loads"),
    "no-inertial-overlapping-boxes": (
        arm(
            collision('<box size="0.1 0.1 0.1"/>'),
            collision('<box size="0.1 0.1 0.1"/>', "0.05 0 0"),
        ),
        "loads",
    ),
    "no-inertial-collision-stl": (arm(mesh("box.stl")), "loads"),
    "no-inertial-primitives": (
        arm(
            collision('<sphere radius="0.1"/>'),
            collision('<cylinder radius="0.1" length="0.2"/>', "1 0 0"),
            collision('<capsule radius="0.1" length="0.2"/>', "0 1 0"),
        ),
        "loads",
    ),
    "no-inertial-mesh-in-mm": (
        arm(collision('<mesh filename="box.stl" scale="0.001 0.001 0.001"/>')),
        "refuses",
    ),
    # fusestatic
    "massless-sensor-on-fixed-joint": (
        robot(
            link("base"),
            revolute("base", "arm"),
            link("arm", inertial()),
            fixed("arm", "tool"),
            link("tool"),
        ),
        "loads",
    ),
    "massless-moving-link-with-welded-mass": (
        robot(
            link("base"),
            revolute("base", "arm"),
            link("arm"),
            fixed("arm", "tool"),
            link("tool", inertial()),
        ),
        "loads",
    ),
    "point-mass-welded-to-body": (
        robot(
            link("base"),
            revolute("base", "arm"),
            link("arm", inertial()),
            fixed("arm", "imu"),
            link("imu", inertial(mass="0.01", **ZERO)),
        ),
        "loads",
    ),
    "point-mass-welded-to-massless-link": (
        robot(
            link("base"),
            revolute("base", "arm"),
            link("arm"),
            fixed("arm", "tool"),
            link("tool", inertial(**ZERO)),
        ),
        "refuses",
    ),
    "two-point-masses-fused-in-turn": (
        robot(
            link("base"),
            revolute("base", "arm"),
            link("arm", inertial(**ZERO)),
            fixed("arm", "t1", "0 0 0.1"),
            link("t1", inertial(**ZERO)),
            fixed("arm", "t2", "0.1 0 0"),
            link("t2", inertial(**ZERO)),
        ),
        "refuses",
    ),
    "welded-link-triangle-broken": (
        robot(
            link("base"),
            revolute("base", "arm"),
            link("arm", inertial()),
            fixed("arm", "tool"),
            link("tool", inertial(**BAD_TRIANGLE)),
        ),
        "refuses",
    ),
    "welded-link-negative-mass": (
        robot(
            link("base"),
            revolute("base", "arm"),
            link("arm", inertial()),
            fixed("arm", "tool"),
            link("tool", inertial(mass="-0.5")),
        ),
        "loads",
    ),
    "welded-link-no-inertial-collision": (
        robot(
            link("base"),
            revolute("base", "arm"),
            link("arm", inertial()),
            fixed("arm", "tool"),
            link("tool", collision('<box size="0.1 0.1 0.1"/>')),
        ),
        "loads",
    ),
    "root-with-mass-dropped": (
        robot(link("base", inertial(mass="5")), revolute("base", "arm"), link("arm", inertial())),
        "loads",
    ),
    "world-link-fixed-base": (
        robot(
            link("world"),
            fixed("world", "base"),
            link("base", inertial()),
            revolute("base", "arm"),
            link("arm", inertial()),
        ),
        "loads",
    ),
    "planar-joint-massless": (
        robot(link("base"), revolute("base", "arm", "planar"), link("arm")),
        "refuses",
    ),
    # the first error stops the load
    "first-of-two-refusals-in-tree-order": (
        robot(
            link("base"),
            link("a2", inertial(**BAD_TRIANGLE)),
            revolute("base", "a1"),
            link("a1", inertial(**NEGATIVE_EIGEN)),
            revolute("a1", "a2"),
        ),
        "refuses",
    ),
    "body-errors-before-mjminval": (
        robot(
            link("base"),
            revolute("base", "a1"),
            link("a1", inertial(mass="0")),
            revolute("a1", "a2"),
            link("a2", inertial(**BAD_TRIANGLE)),
        ),
        "refuses",
    ),
    "children-in-joint-order": (
        robot(
            link("base"),
            revolute("base", "b"),
            revolute("base", "a"),
            link("a", inertial(**BAD_TRIANGLE)),
            link("b", inertial(**NEGATIVE_EIGEN)),
        ),
        "refuses",
    ),
}

# --- MuJoCo's side ----------------------------------------------------------------------------

_COMPILED = re.compile(r"Element name '(.*)', id \d+")
_PARSED = re.compile(r"Element '(.*)', line (\d+)")


def outcome(path: Path) -> tuple[str, str | None, dict | None, object]:
    """``(verdict, message, element, model)`` of loading ``path`` in MuJoCo."""
    try:
        loaded = mujoco.MjModel.from_xml_path(str(path))
    except ValueError as error:
        first, *rest = str(error).split("\n")
        prefix, _, message = first.partition(": ")
        assert prefix in ("Error", "XML Error"), str(error)
        element = None
        for line in rest:
            if found := _COMPILED.fullmatch(line):
                element = {"name": found[1]}
            elif found := _PARSED.fullmatch(line):
                element = {"tag": found[1], "line": int(found[2])}
        return "refuses", message, element, None
    return "loads", None, None, loaded


def write_case(tmp_path: Path, text: str) -> Path:
    for name, content in FILES.items():
        target = tmp_path / name
        if isinstance(content, bytes):
            target.write_bytes(content)
        else:
            target.write_text(content)
    (tmp_path / "BOX.STL").write_bytes(FILES["box.stl"])  # type: ignore[arg-type]
    path = tmp_path / "robot.urdf"
    path.write_text(text)
    return path


def predicted(path: Path):
    result = lint_file(path, Selection(select=(), engines=("mujoco",)))
    assert result.error is None, result.error
    assert {f.code for f in result.findings} <= {"IN070"}
    return result.findings


@pytest.mark.parametrize("case", list(CASES))
def test_prediction_matches_mujoco(case, tmp_path):
    text, expected_verdict = CASES[case]
    path = write_case(tmp_path, text)
    verdict, message, element, _ = outcome(path)
    assert verdict == expected_verdict, (verdict, message)  # the case is what it says
    findings = predicted(path)
    refusals = [f for f in findings if f.expected["verdict"] == "refuses"]
    if verdict == "loads":
        assert refusals == [], [f.message for f in refusals]
        return
    assert refusals, "MuJoCo refuses the model, IN070 predicted it loads"
    (first,) = [f for f in refusals if f.expected["first"]]
    assert first.expected["engine_message"] == message
    assert first.expected["engine_element"] == element
    assert first.message.startswith(f"MuJoCo refuses the model: {message}")
    assert str(first.severity) == "error"
    assert first.expected["engine"] == "mujoco"


def _body_masses(loaded) -> dict[str, float]:
    return {
        mujoco.mj_id2name(loaded, mujoco.mjtObj.mjOBJ_BODY, i): float(loaded.body_mass[i])
        for i in range(loaded.nbody)
    }


def test_inertia_from_geometry_is_the_mass_mujoco_computes(tmp_path):
    for case in (
        "no-inertial-collision-box",
        "no-inertial-overlapping-boxes",
        "no-inertial-collision-stl",
        "no-inertial-primitives",
    ):
        path = write_case(tmp_path, CASES[case][0])
        _, _, _, loaded = outcome(path)
        (change,) = [f for f in predicted(path) if f.expected["stage"] == "inertiafromgeom"]
        assert str(change.severity) == "warning"
        assert change.expected["engine_message"] is None
        assert change.expected["mass"] == pytest.approx(_body_masses(loaded)["arm"], rel=1e-6)
        moments = sorted(float(v) for v in loaded.body_inertia[1])
        assert change.expected["principal_moments"] == pytest.approx(moments, rel=1e-5)


def test_fused_links_give_the_body_mujoco_builds(tmp_path):
    # a welded link's geometry-derived mass and a clamped negative mass: the body's total mass
    for case, mass in (
        ("welded-link-no-inertial-collision", 1.0 + 1000 * 0.001),
        ("welded-link-negative-mass", 1.0),
        ("massless-moving-link-with-welded-mass", 1.0),
    ):
        path = write_case(tmp_path, CASES[case][0])
        _, _, _, loaded = outcome(path)
        assert loaded.nbody == 2  # world and arm: the welded link is fused into arm
        assert _body_masses(loaded)["arm"] == pytest.approx(mass)
    findings = predicted(write_case(tmp_path, CASES["welded-link-negative-mass"][0]))
    (clamp,) = findings
    assert clamp.expected["stage"] == "clamp" and clamp.link == "tool"
    assert clamp.message.startswith("MuJoCo silently changes the model: link `tool`'s negative")


def test_root_mass_is_dropped_and_said(tmp_path):
    path = write_case(tmp_path, CASES["root-with-mass-dropped"][0])
    _, _, _, loaded = outcome(path)
    assert loaded.nbody == 2 and loaded.njnt == 1  # base fused into the world, no free joint
    assert float(loaded.body_mass[0]) == 0.0 and loaded.body_subtreemass[0] == pytest.approx(1.0)
    (dropped,) = predicted(path)
    assert dropped.expected["stage"] == "root" and dropped.expected["dropped_mass"] == 5.0
    # fixed to a `world` link on purpose: nothing to say
    assert predicted(write_case(tmp_path, CASES["world-link-fixed-base"][0])) == []


def test_later_refusals_are_listed_after_the_first(tmp_path):
    path = write_case(tmp_path, CASES["body-errors-before-mjminval"][0])
    *_, element, _ = outcome(path)
    refusals = [f for f in predicted(path) if f.expected["verdict"] == "refuses"]
    first = [f for f in refusals if f.expected["first"]]
    assert [f.link for f in first] == ["a2"] and element == {"name": "a2"}
    later = [f for f in refusals if not f.expected["first"]]
    assert [f.link for f in later] == ["a1"]
    assert later[0].message.startswith("MuJoCo would also refuse the model: mass and inertia")
    assert "it stops at the first error, link `a2`" in later[0].message
