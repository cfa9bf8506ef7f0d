"""Xacro expansion through the real xacro package: equality with xacro, source map (errors:
test_xacro_expand_errors.py)."""

from __future__ import annotations

import sys
import threading
from pathlib import Path

import pytest
import xacro
from kit import REPO, write
from lxml import etree
from xacro import substitution_args

from inertia_kit.description.model import Source
from inertia_kit.description.urdf.packages import PackageResolver
from inertia_kit.description.urdf.xacro_detect import is_xacro
from inertia_kit.description.urdf.xacro_expand import _LOCK, expand
from inertia_kit.description.urdf.xacro_session import Session, patched
from inertia_kit.errors import InputError

EXAMPLES = REPO / "examples"
XACRO_FILES = sorted(EXAMPLES.rglob("*.xacro"))
NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def include(filename: str) -> str:
    """An include line."""
    return f'  <xacro:include filename="{filename}"/>\n'


def structure(element: etree._Element) -> tuple:
    """Tags, attributes and order of an element tree; comments and whitespace left out."""
    return (
        element.tag,
        dict(element.attrib),
        tuple(structure(child) for child in element if isinstance(child.tag, str)),
    )


def plain_xacro(path: Path, resolver: PackageResolver, **kwargs) -> etree._Element:
    """
    What xacro itself produces, with ``$(find)`` through ``resolver`` and xacro's stderr
    collected: the reference our stamped expansion is compared with. It reaches into the
    expansion's private session because only this comparison needs plain xacro routed so.
    """
    session = Session(".", resolver)
    with _LOCK, patched(xacro, session, stamping=False):
        doc = xacro.process_file(str(path), **kwargs)
    return etree.fromstring(doc.documentElement.toxml().encode())


def where(source: Source) -> tuple:
    return (Path(source.path).name, source.line)


def by_name(expanded, tag: str, name: str) -> etree._Element:
    (element,) = expanded.root.iterfind(f"{tag}[@name='{name}']")
    return element


# --- the examples ---------------------------------------------------------------------------


@pytest.mark.parametrize("path", XACRO_FILES, ids=lambda p: str(p.relative_to(EXAMPLES)))
def test_examples_expand_as_xacro_does(path):
    resolver = PackageResolver(start=path, env={})
    expanded = expand(path, resolver=resolver)
    assert expanded.files[0] == str(path)
    if expanded.fragment:
        assert structure(expanded.root) == ("robot", {}, ())
        return
    assert structure(expanded.root) == structure(plain_xacro(path, resolver))
    assert expanded.root.find("link") is not None
    for element in expanded.root.iter(etree.Element):
        source = expanded.source_of(element)
        assert source.line is not None and Path(source.path) in map(Path, expanded.files)


def test_example_fragments_are_detected():
    fragments = {p.name for p in XACRO_FILES if expand(p).fragment}
    assert fragments == {
        "links_joints.xacro",
        "robot_parameters.xacro",
        "macros.xacro",
        "base.xacro",
        "wheels.xacro",
        "sensors.xacro",
    }


def test_mrm_links_point_into_the_macro_and_their_call():
    path = EXAMPLES / "mrm_description" / "urdf" / "mrm.xacro"
    expanded = expand(path)
    assert [Path(f).name for f in expanded.files] == [
        "mrm.xacro",
        "robot_parameters.xacro",
        "links_joints.xacro",
    ]
    link = by_name(expanded, "link", "link_01")
    source = expanded.source_of(link)
    assert where(source) == ("links_joints.xacro", 15)  # <link> in m_link_cylinder's body
    assert [where(call) for call in source.calls] == [("mrm.xacro", 24)]
    inertia = link.find("inertial/inertia")
    assert inertia.get("ixx") == "13.235"
    assert where(expanded.source_of(inertia)) == ("links_joints.xacro", 19)
    assert expanded.source_of(inertia).call_site.line == 24


def test_simple_arm_warning_is_collected_not_printed(capfd):
    expanded = expand(EXAMPLES / "simple_arm" / "urdf" / "simple_arm.urdf.xacro")
    assert any("redefining global symbol: pi" in w for w in expanded.warnings)
    assert capfd.readouterr().err == ""


# --- packages and includes ------------------------------------------------------------------


@pytest.fixture
def workspace(tmp_path: Path) -> dict[str, Path]:
    write(tmp_path / "ws/src/pkg_a/package.xml", "<package><name>pkg_a</name></package>\n")
    parts = write(
        tmp_path / "ws/src/pkg_a/urdf/parts.xacro",
        f"""<robot {NS}>
  <xacro:property name="m" value="2.5"/>
  <xacro:macro name="part" params="name">
    <link name="${{name}}">
      <inertial>
        <mass value="${{m}}"/>
      </inertial>
    </link>
  </xacro:macro>
  <link name="from_a"/>
</robot>
""",
    )
    write(tmp_path / "ws/src/pkg_b/package.xml", "<package><name>pkg_b</name></package>\n")
    robot = write(
        tmp_path / "ws/src/pkg_b/urdf/robot.xacro",
        f"""<robot name="b" {NS}>
  <xacro:include filename="$(find pkg_a)/urdf/parts.xacro"/>
  <link name="base"/>
  <xacro:part name="arm"/>
</robot>
""",
    )
    return {"parts": parts, "robot": robot, "pkg_a": parts.parent.parent}


def test_find_through_a_workspace(workspace):
    expanded = expand(workspace["robot"], resolver=PackageResolver(env={}))
    assert expanded.files == (str(workspace["robot"]), str(workspace["parts"]))
    assert [link.get("name") for link in expanded.root.iter("link")] == ["from_a", "base", "arm"]
    assert expanded.source_of(by_name(expanded, "link", "from_a")) == Source(
        str(workspace["parts"]), 10, 3
    )
    arm = by_name(expanded, "link", "arm")
    assert expanded.source_of(arm) == Source(
        str(workspace["parts"]), 4, 5, (Source(str(workspace["robot"]), 4, 3),)
    )
    mass = arm.find("inertial/mass")
    assert mass.get("value") == "2.5"
    assert where(expanded.source_of(mass)) == ("parts.xacro", 6)


@pytest.mark.parametrize("package_paths", [(), ("ws/src",)], ids=["discovered", "relative-path"])
def test_relative_input_gives_relative_locations(workspace, tmp_path, monkeypatch, package_paths):
    # $(find) must give xacro an absolute folder (xacro joins a relative include to the
    # including file's folder); locations are shown relative, like the input
    monkeypatch.chdir(tmp_path)
    robot = "ws/src/pkg_b/urdf/robot.xacro"
    expanded = expand(robot, resolver=PackageResolver(package_paths, start=robot, env={}))
    assert expanded.files == (robot, "ws/src/pkg_a/urdf/parts.xacro")
    source = expanded.source_of(by_name(expanded, "link", "arm"))
    assert (source.path, source.line, source.calls[0].path) == (expanded.files[1], 4, robot)


def test_find_prefers_the_explicit_package_path(workspace, tmp_path):
    write(tmp_path / "other/pkg_a/package.xml", "<package><name>pkg_a</name></package>\n")
    other = write(
        tmp_path / "other/pkg_a/urdf/parts.xacro",
        f'<robot {NS}>\n  <xacro:macro name="part" params="name">\n'
        '    <link name="${name}_other"/>\n  </xacro:macro>\n</robot>\n',
    )
    env = {"ROS_PACKAGE_PATH": str(workspace["pkg_a"].parent)}
    resolver = PackageResolver([tmp_path / "other"], env=env)
    expanded = expand(workspace["robot"], resolver=resolver)
    assert expanded.files[1] == str(other)
    assert by_name(expanded, "link", "arm_other") is not None


def test_unknown_package_names_the_file_and_hints(tmp_path):
    robot = write(
        tmp_path / "robot.xacro",
        f'<robot name="r" {NS}>\n  <link name="a"/>\n'
        '  <xacro:include filename="$(find no_such_pkg)/urdf/x.xacro"/>\n</robot>\n',
    )
    with pytest.raises(InputError) as caught:
        expand(robot, resolver=PackageResolver(env={}))
    error = caught.value
    assert (error.path, error.line) == (str(robot), 3)
    assert "`no_such_pkg` not found" in error.message
    assert "--package-path" in error.message


# --- args and macros ------------------------------------------------------------------------


def test_args_from_caller_and_defaults(tmp_path):
    robot = write(
        tmp_path / "robot.xacro",
        f"""<robot name="r" {NS}>
  <xacro:arg name="prefix" default="left"/>
  <xacro:arg name="mass" default="1.5"/>
  <link name="$(arg prefix)_link">
    <inertial><mass value="$(arg mass)"/></inertial>
  </link>
</robot>
""",
    )
    expanded = expand(robot)
    assert by_name(expanded, "link", "left_link").find("inertial/mass").get("value") == "1.5"
    expanded = expand(robot, args={"prefix": "right", "mass": "3"})
    assert by_name(expanded, "link", "right_link").find("inertial/mass").get("value") == "3"


def test_undefined_arg(tmp_path):
    robot = write(
        tmp_path / "r.xacro", f'<robot name="r" {NS}>\n  <link name="$(arg nope)"/>\n</robot>\n'
    )
    with pytest.raises(InputError) as caught:
        expand(robot)
    assert (caught.value.path, caught.value.line) == (str(robot), 2)
    assert "--xacro-arg nope:=VALUE" in caught.value.message


NESTED = f"""<robot name="r" {NS}>
  <xacro:macro name="inertial_block" params="m">
    <inertial>
      <mass value="${{m}}"/>
    </inertial>
  </xacro:macro>
  <xacro:macro name="wheel" params="side">
    <link name="${{side}}_wheel">
      <xacro:inertial_block m="0.5"/>
    </link>
  </xacro:macro>
  <xacro:macro name="axle" params="*extra">
    <xacro:wheel side="left"/>
    <xacro:wheel side="right"/>
    <xacro:insert_block name="extra"/>
  </xacro:macro>
  <link name="base"/>
  <xacro:axle>
    <link name="spare"/>
  </xacro:axle>
  <xacro:call macro="wheel" side="front"/>
</robot>
"""


def test_nested_macros_carry_every_call_site(tmp_path):
    robot = write(tmp_path / "nested.xacro", NESTED)
    expanded = expand(robot)
    assert structure(expanded.root) == structure(plain_xacro(robot, PackageResolver(env={})))
    right = by_name(expanded, "link", "right_wheel")
    assert where(expanded.source_of(right)) == ("nested.xacro", 8)
    assert [c.line for c in expanded.source_of(right).calls] == [18, 14]
    inertial = right.find("inertial")
    assert where(expanded.source_of(inertial)) == ("nested.xacro", 3)
    assert [c.line for c in expanded.source_of(inertial).calls] == [18, 14, 9]
    assert [c.line for c in expanded.source_of(inertial.find("mass")).calls] == [18, 14, 9]
    # a block passed to a macro keeps the location where it is written
    assert where(expanded.source_of(by_name(expanded, "link", "spare"))) == ("nested.xacro", 19)
    # xacro:call is stamped once
    front = by_name(expanded, "link", "front_wheel")
    assert [c.line for c in expanded.source_of(front).calls] == [21]
    assert [c.line for c in expanded.source_of(front.find("inertial")).calls] == [21, 9]
    # literal elements have no calls
    assert expanded.source_of(by_name(expanded, "link", "base")) == Source(str(robot), 17, 3)


def test_elements_from_includes_carry_their_file(tmp_path):
    write(
        tmp_path / "urdf/inc/legs.xacro",
        f'<robot {NS}>\n  <link name="leg"/>\n  <xacro:include filename="feet.xacro"/>\n</robot>\n',
    )
    write(tmp_path / "urdf/inc/feet.xacro", '<robot>\n\n  <link name="foot"/>\n</robot>\n')
    robot = write(
        tmp_path / "urdf/robot.xacro",
        f'<robot name="r" {NS}>\n  <xacro:include filename="inc/legs.xacro"/>\n</robot>\n',
    )
    expanded = expand(robot)
    assert [Path(f).name for f in expanded.files] == ["robot.xacro", "legs.xacro", "feet.xacro"]
    assert where(expanded.source_of(by_name(expanded, "link", "leg"))) == ("legs.xacro", 2)
    foot = expanded.source_of(by_name(expanded, "link", "foot"))
    assert (Path(foot.path), foot.line) == (tmp_path / "urdf/inc/feet.xacro", 3)
    # the fragment-with-includes rule: robot.xacro holds only an include, but produces links
    assert not expanded.fragment


# --- fragments, detection, isolation --------------------------------------------------------


def test_fragments(tmp_path):
    macros = write(
        tmp_path / "macros.xacro",
        f"""<robot {NS}>
  <xacro:arg name="where" default="$(find package_only_the_includer_knows)"/>
  <xacro:property name="r" value="${{defined_by_includer}}"/>
  <xacro:macro name="m" params=""><link name="x"/></xacro:macro>
</robot>
""",
    )
    expanded = expand(macros, resolver=PackageResolver(env={}))
    assert expanded.fragment
    assert structure(expanded.root) == ("robot", {}, ())
    assert expanded.files == (str(macros),)
    only_includes = write(
        tmp_path / "all.xacro",
        f'<robot {NS}>\n  <xacro:include filename="params.xacro"/>\n</robot>\n',
    )
    write(
        tmp_path / "params.xacro",
        f'<robot {NS}>\n  <xacro:property name="a" value="1"/>\n</robot>\n',
    )
    assert expand(only_includes).fragment
    robot = write(tmp_path / "robot.xacro", f'<robot name="r" {NS}>\n  <xacro:m/>\n</robot>\n')
    with pytest.raises(InputError, match="unknown macro"):
        expand(robot)


def test_is_xacro_by_content():
    assert is_xacro(b'<robot xmlns:xacro="http://ros.org/wiki/xacro"/>')
    assert is_xacro(b"<robot><xacro:include filename='a.xacro'/></robot>")
    assert not is_xacro(b'<robot name="plain"><link name="a"/></robot>')
    assert not is_xacro(b"<robot><!-- run xacro first --></robot>")


def test_xacro_is_left_as_it_was(tmp_path):
    originals = (
        xacro.parse,
        xacro.handle_macro_call,
        substitution_args._eval_find,
        substitution_args._eval_dict["find"],
        sys.stderr,
    )
    includes = len(xacro.all_includes)
    expand(EXAMPLES / "my_robot_description" / "urdf" / "robot.xacro")
    bad = write(
        tmp_path / "bad.xacro", f'<robot name="r" {NS}>\n  <link name="${{nope}}"/>\n</robot>\n'
    )
    with pytest.raises(InputError):
        expand(bad)
    assert (
        xacro.parse,
        xacro.handle_macro_call,
        substitution_args._eval_find,
        substitution_args._eval_dict["find"],
        sys.stderr,
    ) == originals
    assert len(xacro.all_includes) == includes
    assert xacro.substitution_args_context.get("arg", {}) == {}


def test_concurrent_expansions_agree():
    paths = [p for p in XACRO_FILES if p.name in ("mrm.xacro", "robot.xacro", "robot1_base.xacro")]
    expected = {p: structure(expand(p).root) for p in paths}
    failures: list[str] = []

    def work(path: Path) -> None:
        for _ in range(5):
            if structure(expand(path).root) != expected[path]:
                failures.append(str(path))

    threads = [threading.Thread(target=work, args=(p,)) for p in paths * 2]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert failures == []
