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
from pathlib import Path

import pytest
from kit import urdf
from kit.meshes import ascii_stl, binary_stl, box_triangles, obj
from kit.urdf import box, collision, cylinder, inertial, joint, link, mesh, sphere, visual

from inertia_kit.lint.runner import Selection, lint_file

mujoco = pytest.importorskip("mujoco")


@pytest.fixture(autouse=True)
def _in_tmp_path(tmp_path, monkeypatch):
    """MuJoCo writes its warnings (`XML contains a 'NaN'`) to MUJOCO_LOG.TXT in the cwd."""
    monkeypatch.chdir(tmp_path)


# --- files --------------------------------------------------------------------------------------

# a 0.1 × 0.2 × 0.3 m box, centred: 12 outward-wound triangles
BOX = box_triangles((0.1, 0.2, 0.3), low=(-0.05, -0.1, -0.15))

DAE = """<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="1"/><up_axis>Z_UP</up_axis></asset>
</COLLADA>
"""

FILES: dict[str, bytes | str] = {
    "box.stl": binary_stl(BOX),
    "box_ascii.stl": ascii_stl(BOX),
    "box.obj": obj(BOX),
    "box.dae": DAE,
    "empty.stl": b"",
    "short.stl": b"\0" * 60,
    "padded.stl": binary_stl(BOX) + b"\0\0",
}

# --- robots ---------------------------------------------------------------------------------


def fixed(parent: str, child: str, xyz: str = "0 0 0.1") -> str:
    """A weld, 0.1 m up unless told otherwise."""
    return joint(parent, child, "fixed", xyz=xyz)


def robot(*parts: str) -> str:
    """One part a line, so that a parser error's line names one element."""
    return urdf.robot(*parts, sep="\n")


def arm(*body: str) -> str:
    """A fixed base and one moving link `arm` holding ``body``."""
    return robot(link("base"), joint("base", "arm"), link("arm", *body))


UNIT = inertial(1, 0.01)  # 1 kg, 0.01 kg·m² about every axis
BAD_TRIANGLE = inertial(1, 0.001, 0.001, 0.01)
NEGATIVE_EIGEN = inertial(1, 0.01, ixy=0.02)
ZERO = inertial(1, 0)

# name -> (urdf, the verdict MuJoCo gives it: "loads" | "refuses", what the case is about)
CASES: dict[str, tuple[str, str]] = {
    # clean
    "clean-arm": (arm(UNIT), "loads"),
    "clean-binary-stl": (arm(UNIT, collision(mesh("box.stl"))), "loads"),
    "clean-obj": (arm(UNIT, collision(mesh("box.obj"))), "loads"),
    "clean-uppercase-stl-extension": (arm(UNIT, collision(mesh("BOX.STL"))), "loads"),
    "visual-dae-discarded": (arm(UNIT, visual(mesh("box.dae"))), "loads"),
    "visual-mesh-missing-discarded": (arm(UNIT, visual(mesh("nowhere.stl"))), "loads"),
    "triangle-exactly-on-bound": (arm(inertial(1, 0.25, 0.25, 0.5)), "loads"),
    "mass-exactly-mjminval": (arm(inertial("1e-15", 0.01)), "loads"),
    "eigenvalue-exactly-mjeps": (arm(inertial(1, "1e-14", 0.01, 0.01)), "loads"),
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
    "mass-not-a-number": (arm(inertial("2kg", 0.01)), "refuses"),
    "mass-nan": (arm(inertial("nan", 0.01)), "refuses"),
    # meshes
    "collision-dae": (arm(UNIT, collision(mesh("box.dae"))), "refuses"),
    "collision-ascii-stl": (arm(UNIT, collision(mesh("box_ascii.stl"))), "refuses"),
    "collision-empty-stl": (arm(UNIT, collision(mesh("empty.stl"))), "refuses"),
    "collision-short-stl": (arm(UNIT, collision(mesh("short.stl"))), "refuses"),
    "collision-padded-stl": (arm(UNIT, collision(mesh("padded.stl"))), "refuses"),
    "collision-mesh-missing": (arm(UNIT, collision(mesh("nowhere.stl"))), "refuses"),
    "collision-package-uri": (
        arm(UNIT, collision(mesh("package://robot/meshes/box.stl"))),
        "refuses",
    ),
    "mesh-before-body-errors": (
        robot(
            link("base"),
            joint("base", "a1"),
            link("a1", BAD_TRIANGLE),
            joint("a1", "a2"),
            link("a2", UNIT, collision(mesh("box.dae"))),
        ),
        "refuses",
    ),
    # bodies: mass and moments
    "mass-below-mjminval": (arm(inertial("1e-16", 0.01)), "refuses"),
    "mass-zero": (arm(inertial("0", 0.01)), "refuses"),
    "mass-negative": (arm(inertial("-1", 0.01)), "refuses"),
    "moment-below-mjeps": (arm(inertial(1, "5e-15", 0.01, 0.01)), "refuses"),
    "all-six-zero-on-moving-link": (arm(ZERO), "refuses"),
    "negative-eigenvalue": (arm(NEGATIVE_EIGEN), "refuses"),
    "negative-diagonal": (arm(inertial(1, -0.01, 0.01, 0.01)), "refuses"),
    "triangle-broken": (arm(BAD_TRIANGLE), "refuses"),
    # the diagonal satisfies A + B ≥ C, the principal moments (0.001, 0.001, 0.01) do not
    "triangle-broken-only-after-diagonalising": (
        arm(inertial(1, 0.001, 0.0055, 0.0055, iyz=-0.0045)),
        "refuses",
    ),
    "triangle-broken-rotated-axes": (
        arm(inertial(1, 0.001, 0.001, 0.01, rpy="0.3 0.2 0.1")),
        "refuses",
    ),
    "zero-collision-box": (arm(UNIT, collision(box(0.1, 0, 0.1))), "refuses"),
    "zero-cylinder-length": (
        arm(UNIT, collision(cylinder(0.1, 0))),
        "refuses",
    ),
    "root-triangle-broken": (
        robot(link("base", BAD_TRIANGLE), joint("base", "arm"), link("arm", UNIT)),
        "refuses",
    ),
    # no <inertial>: inertiafromgeom
    "no-inertial-no-geometry": (arm(), "refuses"),
    "no-inertial-visual-only": (
        arm(visual(box(0.1, 0.2, 0.3))),
        "refuses",
    ),
    "no-inertial-collision-box": (arm(collision(box(0.1, 0.2, 0.3))), "loads"),
    "no-inertial-overlapping-boxes": (
        arm(
            collision(box(0.1, 0.1, 0.1)),
            collision(box(0.1, 0.1, 0.1), xyz="0.05 0 0"),
        ),
        "loads",
    ),
    "no-inertial-collision-stl": (arm(collision(mesh("box.stl"))), "loads"),
    "no-inertial-primitives": (
        arm(
            collision(sphere(0.1)),
            collision(cylinder(0.1, 0.2), xyz="1 0 0"),
            collision('<capsule radius="0.1" length="0.2"/>', xyz="0 1 0"),
        ),
        "loads",
    ),
    "no-inertial-mesh-in-mm": (
        arm(collision(mesh("box.stl", scale="0.001 0.001 0.001"))),
        "refuses",
    ),
    # fusestatic
    "massless-sensor-on-fixed-joint": (
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
    "point-mass-welded-to-body": (
        robot(
            link("base"),
            joint("base", "arm"),
            link("arm", UNIT),
            fixed("arm", "imu"),
            link("imu", inertial(0.01, 0)),
        ),
        "loads",
    ),
    "point-mass-welded-to-massless-link": (
        robot(
            link("base"),
            joint("base", "arm"),
            link("arm"),
            fixed("arm", "tool"),
            link("tool", ZERO),
        ),
        "refuses",
    ),
    "two-point-masses-fused-in-turn": (
        robot(
            link("base"),
            joint("base", "arm"),
            link("arm", ZERO),
            fixed("arm", "t1", "0 0 0.1"),
            link("t1", ZERO),
            fixed("arm", "t2", "0.1 0 0"),
            link("t2", ZERO),
        ),
        "refuses",
    ),
    "welded-link-triangle-broken": (
        robot(
            link("base"),
            joint("base", "arm"),
            link("arm", UNIT),
            fixed("arm", "tool"),
            link("tool", BAD_TRIANGLE),
        ),
        "refuses",
    ),
    "welded-link-negative-mass": (
        robot(
            link("base"),
            joint("base", "arm"),
            link("arm", UNIT),
            fixed("arm", "tool"),
            link("tool", inertial("-0.5", 0.01)),
        ),
        "loads",
    ),
    "welded-link-no-inertial-collision": (
        robot(
            link("base"),
            joint("base", "arm"),
            link("arm", UNIT),
            fixed("arm", "tool"),
            link("tool", collision(box(0.1, 0.1, 0.1))),
        ),
        "loads",
    ),
    "root-with-mass-dropped": (
        robot(link("base", inertial("5", 0.01)), joint("base", "arm"), link("arm", UNIT)),
        "loads",
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
    "planar-joint-massless": (
        robot(link("base"), joint("base", "arm", "planar"), link("arm")),
        "refuses",
    ),
    # the first error stops the load
    "first-of-two-refusals-in-tree-order": (
        robot(
            link("base"),
            link("a2", BAD_TRIANGLE),
            joint("base", "a1"),
            link("a1", NEGATIVE_EIGEN),
            joint("a1", "a2"),
        ),
        "refuses",
    ),
    "body-errors-before-mjminval": (
        robot(
            link("base"),
            joint("base", "a1"),
            link("a1", inertial("0", 0.01)),
            joint("a1", "a2"),
            link("a2", BAD_TRIANGLE),
        ),
        "refuses",
    ),
    "children-in-joint-order": (
        robot(
            link("base"),
            joint("base", "b"),
            joint("base", "a"),
            link("a", BAD_TRIANGLE),
            link("b", NEGATIVE_EIGEN),
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
    for finding in findings:
        assert len(finding.message) <= 100 and "\n" not in finding.message, finding.message
    refusals = [f for f in findings if f.expected["verdict"] == "refuses"]
    if verdict == "loads":
        assert refusals == [], [f.message for f in refusals]
        return
    assert refusals, "MuJoCo refuses the model, IN070 predicted it loads"
    (first,) = [f for f in refusals if f.expected["first"]]
    assert first.expected["engine_message"] == message
    assert first.expected["engine_element"] == element
    assert first.message.startswith(f"link `{first.link}`: MuJoCo refuses the model: ")
    assert first.detail.endswith(f'MuJoCo says: "{message}"')
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
    assert clamp.message == "link `tool`: MuJoCo clamps its mass -0.5 kg to 0"
    assert (
        "negative mass (-0.5 kg) of link `tool` to 0 (boundmass) before it is fused" in clamp.detail
    )


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
    assert later[0].message.startswith("link `a1`: MuJoCo would also refuse the model: ")
    assert "it stops at the first error, link `a2`" not in later[0].message
    assert "MuJoCo stops at the first error, link `a2`" in later[0].detail
    assert later[0].detail.endswith(
        'MuJoCo says: "mass and inertia of moving bodies must be larger than mjMINVAL"'
    )
