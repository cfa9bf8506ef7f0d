"""
`inertia-lint` and `inertia-fill` on a xacro fragment, as a pre-commit hook hands one over: the
robots of the repository that include it are linted (filled), and what lands in the fragment
is reported (written), saying via which robot (issue 12, item 1).

Real rules: IN002 (a non-positive mass) only, so that the findings are the mass the test broke.
"""

from __future__ import annotations

import json
import math
import os

import pytest
from kit.in_process import run_split
from kit.urdf import link_lines, robot_lines
from kit.xacro_projects import (
    HEAD,
    LEAF,
    LEAF_MASS_LINE,
    XACRO,
    age,
    middle,
    project,
    robot,
    seed_wheeled_robot,
    wheel_macro_span,
)

from inertia_kit.cli import fill_main, lint_main
from inertia_kit.lint import include_graph

MASS_MESSAGE = "IN002 link `{link}`: mass = {mass:g} kg is not positive"


def run(command, *args: str) -> tuple[int, str, str]:
    return run_split(command, args)


def lint(*args: str) -> tuple[int, str, str]:
    return run(lint_main, "--select", "IN002", "--output-format", "concise", *args)


@pytest.fixture
def repo(tmp_path, monkeypatch):
    """An empty repository (a folder with .git) as the current folder, no colour."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("FORCE_COLOR", raising=False)
    monkeypatch.delenv("INERTIA_KIT_NO_CACHE", raising=False)
    return tmp_path


def mass_line(path: str, link: str, mass: float, line: int = LEAF_MASS_LINE) -> str:
    """The concise line of IN002 on ``link`` located in ``path``, up to the message's end."""
    return f"{path}:{line}: {MASS_MESSAGE.format(link=link, mass=mass)}"


def findings(stdout: str) -> list[str]:
    return stdout.splitlines()


# --- lint: which robots, which findings -------------------------------------------------------


def test_a_fragment_included_directly_is_linted_through_its_robot(repo):
    project(repo, {"urdf/leaf.xacro": LEAF, "urdf/arm.urdf.xacro": robot("leaf.xacro", "a=-2")})
    code, out, err = lint("arm_description/urdf/leaf.xacro")
    (line,) = findings(out)
    assert line.startswith(mass_line("arm_description/urdf/leaf.xacro", "a", -2))
    assert line.endswith("(via arm_description/urdf/arm.urdf.xacro)")
    assert code == 1
    assert err == (
        "note: arm_description/urdf/leaf.xacro: linted through the robots that include it: "
        "arm_description/urdf/arm.urdf.xacro\nFound 1 error in 1 file.\n"
    )


def test_a_fragment_included_through_another_fragment(repo):
    project(
        repo,
        {
            "urdf/parts/leaf.xacro": LEAF,
            "urdf/middle.xacro": middle("parts/leaf.xacro"),
            "urdf/arm.urdf.xacro": robot("middle.xacro", "a=1", "b=-3"),
        },
    )
    code, out, _ = lint("arm_description/urdf/parts/leaf.xacro")
    (line,) = findings(out)
    assert line.startswith(mass_line("arm_description/urdf/parts/leaf.xacro", "b", -3))
    assert line.endswith("(via arm_description/urdf/arm.urdf.xacro)")
    assert code == 1
    # the middle fragment produces no element: nothing is located in it
    code, out, err = lint("arm_description/urdf/middle.xacro")
    assert (code, out) == (0, "")
    assert "linted through the robots that include it: arm_description/urdf/arm.urdf.xacro" in err


def test_a_fragment_included_through_find_package(repo):
    include = "$(find arm_description)/urdf/leaf.xacro"
    project(repo, {"urdf/leaf.xacro": LEAF, "robots/arm.urdf.xacro": robot(include, "a=-1")})
    code, out, _ = lint("arm_description/urdf/leaf.xacro")
    (line,) = findings(out)
    assert line.startswith(mass_line("arm_description/urdf/leaf.xacro", "a", -1))
    assert line.endswith("(via arm_description/robots/arm.urdf.xacro)")
    assert code == 1


def test_a_finding_two_robots_report_is_told_once_naming_both(repo):
    project(
        repo,
        {
            "urdf/leaf.xacro": LEAF,
            "urdf/one.urdf.xacro": robot("leaf.xacro", "a=-1", name="one"),
            "urdf/two.urdf.xacro": robot("leaf.xacro", "a=-1", "b=2", name="two"),
        },
    )
    code, out, _ = lint("arm_description/urdf/leaf.xacro")
    (line,) = findings(out)
    assert line.endswith(
        "(via arm_description/urdf/one.urdf.xacro, arm_description/urdf/two.urdf.xacro)"
    )
    assert code == 1
    code, out, _ = lint("--output-format", "json", "arm_description/urdf/leaf.xacro")
    (finding,) = json.loads(out)
    assert finding["file"] == "arm_description/urdf/leaf.xacro"
    assert finding["line"] == LEAF_MASS_LINE
    assert finding["macro"] is None  # moved from the call site to the macro body
    assert finding["via"] == [
        "arm_description/urdf/one.urdf.xacro",
        "arm_description/urdf/two.urdf.xacro",
    ]


def test_a_fragment_no_robot_includes_gets_a_note(repo):
    project(repo, {"urdf/leaf.xacro": LEAF})
    assert lint("arm_description/urdf/leaf.xacro") == (
        0,
        "",
        f"note: arm_description/urdf/leaf.xacro: a xacro fragment no robot in {repo} "
        "(the git top level) includes; nothing to lint\nNo findings in 0 files.\n",
    )


def test_a_fragment_given_with_its_robot_gives_each_finding_once(repo):
    project(repo, {"urdf/leaf.xacro": LEAF, "urdf/arm.urdf.xacro": robot("leaf.xacro", "a=-1")})
    alone = lint("arm_description/urdf/arm.urdf.xacro")
    both = lint("arm_description/urdf/arm.urdf.xacro", "arm_description/urdf/leaf.xacro")
    assert both[:2] == alone[:2]
    (line,) = findings(both[1])
    assert line.startswith("arm_description/urdf/arm.urdf.xacro:5:3:")  # the call: as itself
    assert "via" not in line


def test_an_included_file_that_is_a_robot_itself_is_linted_as_itself_too(repo):
    """Its own findings are told once, as its own (no `via`); its robots add what their
    macros put in it."""
    links = robot("leaf.xacro", "own=-1", name="links")
    arm = """<?xml version="1.0"?>
<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="links.xacro"/>
  <xacro:arm_link name="b" mass="-4"/>
</robot>
"""
    project(repo, {"urdf/leaf.xacro": LEAF, "urdf/links.xacro": links, "urdf/arm.xacro": arm})
    code, out, _ = lint("arm_description/urdf/links.xacro", "arm_description/urdf/leaf.xacro")
    assert code == 1
    assert findings(out) == [
        "arm_description/urdf/links.xacro:5:3: IN002 link `own`: mass = -1 kg is not positive",
        "arm_description/urdf/leaf.xacro:6: IN002 link `b`: mass = -4 kg is not positive "
        "(via arm_description/urdf/arm.xacro)",
    ]


def test_a_fragment_that_cannot_load_alone_is_linted_through_its_robot(repo):
    """A fragment using its robot's properties is refused by xacro on its own: no error."""
    needy = LEAF.replace(
        "</robot>", '  <xacro:property name="twice" value="${base_mass*2}"/>\n</robot>'
    )
    arm = robot("leaf.xacro", "a=-1").replace(
        "  <xacro:include", '  <xacro:property name="base_mass" value="1"/>\n  <xacro:include'
    )
    project(repo, {"urdf/leaf.xacro": needy, "urdf/arm.urdf.xacro": arm})
    code, out, err = lint("arm_description/urdf/leaf.xacro")
    assert code == 1
    assert "error" not in err.lower().replace("found 1 error", "")
    (line,) = findings(out)
    assert line.startswith(mass_line("arm_description/urdf/leaf.xacro", "a", -1))


def test_sarif_names_the_robot_in_message_and_properties(repo):
    project(repo, {"urdf/leaf.xacro": LEAF, "urdf/arm.urdf.xacro": robot("leaf.xacro", "a=-1")})
    code, out, _ = lint("--output-format", "sarif", "arm_description/urdf/leaf.xacro")
    assert code == 1
    (result,) = json.loads(out)["runs"][0]["results"]
    assert result["message"]["text"].endswith("(via arm_description/urdf/arm.urdf.xacro)")
    assert result["properties"]["via"] == ["arm_description/urdf/arm.urdf.xacro"]
    location = result["locations"][0]["physicalLocation"]
    assert location["artifactLocation"]["uri"] == "arm_description/urdf/leaf.xacro"
    assert location["region"]["startLine"] == LEAF_MASS_LINE


# --- the include graph's cache ----------------------------------------------------------------


def _layered(repo):
    package = project(
        repo,
        {
            "urdf/leaf.xacro": LEAF,
            "urdf/middle.xacro": middle("leaf.xacro"),
            "urdf/arm.urdf.xacro": robot("middle.xacro", "a=-1"),
        },
    )
    age(repo)
    return package


def test_a_warm_cache_expands_nothing(repo, monkeypatch):
    _layered(repo)
    cold = lint("arm_description/urdf/leaf.xacro")
    assert cold[0] == 1

    def no_scan(*args, **kwargs):
        raise AssertionError(f"scanned {args[0]} though the cache holds it")

    monkeypatch.setattr(include_graph, "_scan", no_scan)
    assert lint("arm_description/urdf/leaf.xacro") == cold


def test_an_edit_of_an_include_rescans_the_robot(repo):
    package = _layered(repo)
    assert lint("arm_description/urdf/leaf.xacro")[0] == 1
    # the middle fragment no longer includes the leaf: the robot's entry is stale
    (package / "urdf" / "middle.xacro").write_text(middle("other.xacro"))
    (package / "urdf" / "other.xacro").write_text(LEAF)
    graph = include_graph.include_graph(repo)
    assert graph.scanned == 3  # middle.xacro, the robot that read it, the new other.xacro
    assert graph.reused == 1  # leaf.xacro
    assert graph.includers(package / "urdf" / "leaf.xacro") == []
    code, out, err = lint("arm_description/urdf/leaf.xacro")
    assert (code, out) == (0, "")
    assert "a xacro fragment no robot in" in err


def test_no_cache_when_turned_off(repo, monkeypatch, tmp_path_factory):
    cache = tmp_path_factory.mktemp("cache")
    monkeypatch.setenv("INERTIA_KIT_CACHE_DIR", str(cache))
    _layered(repo)
    lint("arm_description/urdf/leaf.xacro")
    assert list((cache / "includes-v2").glob("*.json"))
    monkeypatch.setenv("INERTIA_KIT_NO_CACHE", "1")
    for entry in (cache / "includes-v2").glob("*.json"):
        os.unlink(entry)
    assert lint("arm_description/urdf/leaf.xacro")[0] == 1
    assert not list((cache / "includes-v2").glob("*.json"))


# --- fill -------------------------------------------------------------------------------------


def test_fill_on_a_fragment_fills_the_fragment_and_settles(repo):
    """
    The seed wheeled robot with the wheel macro's <inertial> removed: filling wheels.xacro
    fills the wheels there (not the base, whose block belongs in base.xacro), and a second run
    changes nothing.
    """
    urdf = seed_wheeled_robot(repo)
    wheels = urdf / "wheels.xacro"
    text = wheels.read_text()
    start, end = wheel_macro_span(text)
    block = text[text.index("<inertial>", start) : text.index("</inertial>", start) + 11]
    wheels.write_text(text[:start] + text[start:end].replace(block, "") + text[end:])
    before = {p.name: p.read_bytes() for p in urdf.iterdir() if p.name != "wheels.xacro"}

    code, out, err = run(fill_main, "my_robot_description/urdf/wheels.xacro")
    assert code == 1
    # the wheel: a solid cylinder, r = 0.05 m, l = 0.02 m (macros.xacro), 1000 kg/m³
    mass = f"{math.pi * 0.05**2 * 0.02 * 1000:.6g}"
    assert (
        f"Filled 2 links in my_robot_description/urdf/wheels.xacro via "
        f"my_robot_description/urdf/robot.xacro: left_wheel_link {mass} kg, "
        f"right_wheel_link {mass} kg"
    ) in err
    filled = wheels.read_text()
    start, end = wheel_macro_span(filled)
    assert f'<mass value="{mass}"/>' in filled[start:end]
    assert {p.name: p.read_bytes() for p in urdf.iterdir() if p.name != "wheels.xacro"} == before

    code, out, err = run(fill_main, "my_robot_description/urdf/wheels.xacro")
    assert (code, out) == (0, ""), err
    assert wheels.read_text() == filled


def test_fill_on_a_fragment_no_robot_includes(repo):
    project(repo, {"urdf/leaf.xacro": LEAF})
    code, out, err = run(fill_main, "arm_description/urdf/leaf.xacro")
    assert (code, out) == (0, "")
    assert err == (
        f"note: arm_description/urdf/leaf.xacro: a xacro fragment no robot in {repo} "
        "(the git top level) includes; nothing to fill\n"
        "inertia-fill: 1 file checked, nothing to change\n"
    )


def test_a_fragment_that_breaks_its_robot_fails_with_the_error(repo, monkeypatch):
    """The edit makes the fragment malformed: the robot that includes it cannot be expanded,
    and the hook says so (exit 2) rather than finding nothing to lint."""
    package = project(
        repo, {"urdf/leaf.xacro": LEAF, "urdf/arm.urdf.xacro": robot("leaf.xacro", "a=1")}
    )
    age(repo)
    assert lint("arm_description/urdf/leaf.xacro")[0] == 0  # the cache knows the robot
    (package / "urdf" / "leaf.xacro").write_text(LEAF.replace("</xacro:macro>", ""))
    for cache in ("warm", "off"):  # the robot's reads known from before the break, or not
        if cache == "off":
            monkeypatch.setenv("INERTIA_KIT_NO_CACHE", "1")
        code, out, err = lint("arm_description/urdf/leaf.xacro")
        assert (code, out) == (2, ""), err
        assert "error: arm_description/urdf/leaf.xacro:" in err


def test_a_plain_urdf_is_linted_without_scanning_the_repository(repo, monkeypatch):
    project(repo, {"urdf/leaf.xacro": LEAF, "urdf/plain.urdf": robot_lines(link_lines("p", 1, 1))})

    def no_graph(*args, **kwargs):
        raise AssertionError("scanned the repository for a plain URDF")

    monkeypatch.setattr("inertia_kit.lint.fragments.include_graph", no_graph)
    code, _, err = lint("arm_description/urdf/plain.urdf")
    assert (code, err) == (0, "No findings in 1 file.\n")


def test_fill_on_a_fragment_tells_the_refusals_of_its_links_only(repo):
    """Links without geometry: the one the fragment's macro makes is refused for the fragment;
    those written in the robot are the robot's business."""
    bare = (
        '<?xml version="1.0"?>\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:macro name="bare" params="name">\n    <link name="${name}"/>\n'
        "  </xacro:macro>\n</robot>\n"
    )
    arm = robot("bare.xacro", "from_macro=1", "literal=1")
    arm = arm.replace(
        '<xacro:arm_link name="from_macro" mass="1"/>', '<xacro:bare name="from_macro"/>'
    )
    arm = arm.replace('<xacro:arm_link name="literal" mass="1"/>', '<link name="literal"/>')
    project(repo, {"urdf/bare.xacro": bare, "urdf/arm.urdf.xacro": arm})
    code, out, err = run(fill_main, "arm_description/urdf/bare.xacro")
    assert (code, out) == (1, "")
    refusals = [line for line in err.splitlines() if "not filled" in line]
    assert refusals == [
        "arm_description/urdf/arm.urdf.xacro: link `from_macro` not filled: it has no <visual> "
        "or <collision> geometry to compute from: write its <inertial> by hand, or give it "
        "geometry"
    ]
    # the robot itself: its base, the macro's link and its own
    code, _, err = run(fill_main, "arm_description/urdf/arm.urdf.xacro")
    assert code == 1
    refused = [line.split("`")[1] for line in err.splitlines() if "not filled" in line]
    assert refused == ["base", "from_macro", "literal"]


# --- files without links: placeholders and property files ---------------------------------------

#: husky_description's empty.urdf: plain URDF, no link, what `$(arg urdf_extras)` names by default
PLACEHOLDER = "<robot>\n  <!-- set HUSKY_URDF_EXTRAS to the file to include instead -->\n</robot>\n"


def extras_robot() -> str:
    """A robot that includes `$(arg urdf_extras)`, the placeholder by default (husky's way)."""
    return (
        f'{HEAD}<robot name="arm" {XACRO}>\n'
        '  <xacro:arg name="urdf_extras" default="$(optenv ARM_URDF_EXTRAS empty.urdf)"/>\n'
        '  <xacro:include filename="leaf.xacro"/>\n  <link name="base"/>\n'
        '  <xacro:arm_link name="a" mass="-2"/>\n'
        '  <joint name="j" type="fixed"><parent link="base"/><child link="a"/></joint>\n'
        '  <xacro:include filename="$(arg urdf_extras)"/>\n</robot>\n'
    )


def test_a_placeholder_a_robot_includes_is_linted_through_it_not_refused(repo, monkeypatch):
    monkeypatch.delenv("ARM_URDF_EXTRAS", raising=False)
    project(
        repo,
        {
            "urdf/leaf.xacro": LEAF,
            "urdf/arm.urdf.xacro": extras_robot(),
            "urdf/empty.urdf": PLACEHOLDER,
        },
    )
    code, out, err = run(lint_main, "--output-format", "concise", "arm_description/urdf/empty.urdf")
    assert (code, out) == (0, "")
    assert err == (
        "note: arm_description/urdf/empty.urdf: linted through the robots that include it: "
        "arm_description/urdf/arm.urdf.xacro\nNo findings in 1 file.\n"
    )
    # the whole repository: the robot's finding, and still no IN040 for the placeholder
    code, out, _ = run(lint_main, "--output-format", "concise", ".")
    assert code == 1 and "IN040" not in out and "IN002 link `a`" in out


def test_fill_on_a_placeholder_fills_through_its_robot_and_leaves_it_as_it_is(repo, monkeypatch):
    monkeypatch.delenv("ARM_URDF_EXTRAS", raising=False)
    package = project(
        repo,
        {
            "urdf/leaf.xacro": LEAF,
            "urdf/arm.urdf.xacro": extras_robot(),
            "urdf/empty.urdf": PLACEHOLDER,
        },
    )
    code, out, err = run(fill_main, "arm_description/urdf/empty.urdf")
    assert code == 0, err
    assert (
        "note: arm_description/urdf/empty.urdf: filled through the robots that include it: "
        "arm_description/urdf/arm.urdf.xacro"
    ) in err + out
    assert (package / "urdf" / "empty.urdf").read_text() == PLACEHOLDER


def test_a_placeholder_no_robot_includes_is_a_robot_with_no_link(repo):
    project(repo, {"urdf/empty.urdf": PLACEHOLDER})
    code, out, _ = run(lint_main, "--output-format", "concise", "arm_description/urdf/empty.urdf")
    assert code == 1 and "IN040 the robot has no <link>" in out


def test_a_materials_file_declaring_xacro_is_a_fragment_not_a_broken_robot(repo):
    """turtlebot3's common_properties.urdf: materials only, the xacro namespace declared."""
    materials = (
        f'{HEAD}<robot name="xacro_properties" {XACRO}>\n'
        '  <material name="blue"><color rgba="0 0 0.8 1"/></material>\n</robot>\n'
    )
    project(repo, {"urdf/common_properties.urdf": materials})
    assert run(lint_main, "arm_description/urdf/common_properties.urdf") == (
        0,
        "",
        f"note: arm_description/urdf/common_properties.urdf: a xacro fragment no robot in {repo} "
        "(the git top level) includes; nothing to lint\nNo findings in 0 files.\n",
    )
