"""
Which files a robot can include, read from its includes as written: never "no" for a file its
expansion reads (checked against the real xacro expansion), and "no" where the includes are
written out and reach none of them.
"""

from __future__ import annotations

import os

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from kit.xacro_projects import HEAD, LEAF, PACKAGE, XACRO, middle, project, robot

from inertia_kit.description.urdf import xacro_includes
from inertia_kit.description.urdf.reader import files_read
from inertia_kit.errors import InputError


def real(path) -> str:
    return os.path.realpath(os.path.abspath(path))


def may(robot_file, *wanted, xml_only=True) -> bool:
    return xacro_includes.may_include(
        real(robot_file), {real(file) for file in wanted}, xml_only=xml_only
    )


def _macro_file(include: str) -> str:
    """A fragment whose macro includes ``include`` when it is called."""
    return (
        f'{HEAD}<robot {XACRO}>\n  <xacro:macro name="parts">\n'
        f'    <xacro:include filename="{include}"/>\n  </xacro:macro>\n</robot>\n'
    )


def test_written_out_includes_are_followed(tmp_path):
    urdf = (
        project(
            tmp_path,
            {
                "urdf/leaf.xacro": LEAF,
                "urdf/middle.xacro": middle(f"$(find {PACKAGE})/urdf/leaf.xacro"),
                "urdf/arm.urdf.xacro": robot("middle.xacro", "a=1"),
                "urdf/other.xacro": LEAF,
            },
        )
        / "urdf"
    )
    arm = urdf / "arm.urdf.xacro"
    assert may(arm, urdf / "leaf.xacro")  # through middle.xacro and $(find)
    assert may(arm, urdf / "middle.xacro")
    assert not may(arm, urdf / "other.xacro")
    assert not may(arm, arm)  # not by itself
    assert not may(urdf / "middle.xacro", arm)


@pytest.mark.parametrize(
    "include",
    [
        "${name}.xacro",  # a property
        "$(arg part)",  # an argument
        "*.xacro",  # a glob
        "$(find no_such_package)/urdf/leaf.xacro",  # a package not found
        "missing.xacro",  # a file that cannot be read
    ],
)
def test_an_include_not_written_out_may_read_anything(tmp_path, include):
    urdf = project(tmp_path, {"urdf/arm.urdf.xacro": robot(include, "a=1"), "urdf/x.xacro": LEAF})
    assert may(urdf / "arm.urdf.xacro", urdf / "x.xacro")


def test_a_file_that_does_not_parse_may_read_anything(tmp_path):
    urdf = (
        project(
            tmp_path,
            {
                "urdf/arm.urdf.xacro": robot("broken.xacro", "a=1"),
                "urdf/broken.xacro": "<robot><xacro:include filename='x.xacro'>",
                "urdf/x.xacro": LEAF,
                "urdf/y.xacro": LEAF,
            },
        )
        / "urdf"
    )
    assert may(urdf / "arm.urdf.xacro", urdf / "y.xacro")


def test_an_include_in_a_macro_is_taken_from_every_file_that_may_call_it(tmp_path):
    # xacro opens a relative include of a macro from the folder of the file it is reading
    # when the macro is called: here the robot's folder, not the macro's
    package = project(
        tmp_path,
        {
            "lib/macros.xacro": _macro_file("parts.xacro"),
            "urdf/parts.xacro": LEAF,
            "lib/parts.xacro": LEAF,
            "urdf/arm.urdf.xacro": robot("../lib/macros.xacro").replace(
                '<link name="base"/>', '<link name="base"/>\n  <xacro:parts/>'
            ),
        },
    )
    arm = package / "urdf" / "arm.urdf.xacro"
    files, _ = files_read(arm)
    assert real(package / "urdf" / "parts.xacro") in {real(f) for f in files}
    assert may(arm, package / "urdf" / "parts.xacro")


def test_load_yaml_is_followed_only_for_a_file_that_is_not_xml(tmp_path):
    urdf = (
        project(
            tmp_path,
            {
                "urdf/arm.urdf.xacro": robot("leaf.xacro", "a=1").replace(
                    '<link name="base"/>',
                    '<xacro:property name="c" value="${xacro.load_yaml(\'c.yaml\')}"/>\n'
                    '  <link name="base"/>',
                ),
                "urdf/leaf.xacro": LEAF,
                "urdf/c.yaml": "a: 1\n",
                "urdf/other.xacro": LEAF,
            },
        )
        / "urdf"
    )
    arm = urdf / "arm.urdf.xacro"
    assert xacro_includes.is_xml(str(urdf / "other.xacro"))
    assert not xacro_includes.is_xml(str(urdf / "c.yaml"))
    assert not may(arm, urdf / "other.xacro")
    assert may(arm, urdf / "c.yaml", xml_only=False)


def test_only_a_regular_file_can_be_xml(tmp_path):
    fifo = tmp_path / "pipe.xacro"
    os.mkfifo(fifo)  # opened without a writer, a blocking read would wait for ever
    assert not xacro_includes.is_xml(str(fifo))
    assert not xacro_includes.is_xml(str(tmp_path))
    assert not xacro_includes.is_xml(str(tmp_path / "missing.xacro"))
    (tmp_path / "bom.xacro").write_bytes(b"\xef\xbb\xbf\n  <robot/>")
    assert xacro_includes.is_xml(str(tmp_path / "bom.xacro"))


def test_a_symbolic_link_is_known_by_its_target(tmp_path):
    urdf = (
        project(
            tmp_path,
            {"urdf/arm.urdf.xacro": robot("link.xacro", "a=1"), "shared/leaf.xacro": LEAF},
        )
        / "urdf"
    )
    os.symlink(urdf.parent / "shared" / "leaf.xacro", urdf / "link.xacro")
    assert may(urdf / "arm.urdf.xacro", urdf.parent / "shared" / "leaf.xacro")


def test_more_files_than_the_bound_may_read_anything(tmp_path, monkeypatch):
    monkeypatch.setattr(xacro_includes, "MAX_FILES", 3)
    files = {f"urdf/m{index}.xacro": middle(f"m{index + 1}.xacro") for index in range(5)}
    files["urdf/m5.xacro"] = LEAF
    files["urdf/other.xacro"] = LEAF
    urdf = project(tmp_path, {**files, "urdf/arm.urdf.xacro": robot("m0.xacro", "a=1")}) / "urdf"
    assert may(urdf / "arm.urdf.xacro", urdf / "other.xacro")
    monkeypatch.setattr(xacro_includes, "MAX_FILES", 256)
    assert not may(urdf / "arm.urdf.xacro", urdf / "other.xacro")


# --- never "no" for a file the expansion reads -------------------------------------------------

ORDER = tuple(f"{folder}/{name}.xacro" for folder in ("urdf", "lib") for name in "abc")


@st.composite
def repositories(draw):
    """Six fragments in two folders, each including later ones (no cycle, which xacro refuses)
    in the ways xacro allows: relative, through $(find), inside a macro it calls, under a
    false condition; and a robot that includes one of them."""
    files = {}
    for index, file in enumerate(ORDER):
        lines = []
        later = ORDER[index + 1 :]
        chosen = draw(st.lists(st.sampled_from(later), max_size=3, unique=True)) if later else []
        for number, other in enumerate(chosen):
            way = draw(st.sampled_from(("relative", "find", "macro", "unless")))
            path = f"$(find {PACKAGE})/{other}" if way == "find" else f"../{other}"
            include = f'<xacro:include filename="{path}"/>'
            if way == "macro":
                macro = f"m{index}_{number}"
                include = f'<xacro:macro name="{macro}">{include}</xacro:macro><xacro:{macro}/>'
            elif way == "unless":
                include = f'<xacro:if value="false">{include}</xacro:if>'
            lines.append("  " + include)
        body = "\n".join(lines)
        files[file] = f"{HEAD}<robot {XACRO}>\n{body}\n</robot>\n"
    files["urdf/robot.urdf.xacro"] = robot(f"../{draw(st.sampled_from(ORDER))}")
    return files


@settings(
    max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
@given(files=repositories())
def test_never_no_for_a_file_the_expansion_reads(tmp_path_factory, files):
    package = project(tmp_path_factory.mktemp("repo"), files)
    arm = package / "urdf" / "robot.urdf.xacro"
    try:
        read, _ = files_read(arm)
    except InputError:
        return  # a file included twice defines its macros twice: refused, nothing to compare
    read_keys = {real(file) for file in read}
    for name in files:
        file = real(package / name)
        if file in read_keys and file != real(arm):
            assert may(arm, package / name), name
