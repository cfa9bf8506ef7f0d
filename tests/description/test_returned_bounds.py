"""
The bounds apply to what an expansion returns, not only to the expansion: a 230-byte xacro with
``name="${'x'*10**8}"`` passed the memory limit and the lint then held 1.3 GB and wrote
200-400 MB. An attribute value over 65 536 characters, a name over 1024, or an expanded robot
over 50 MB is refused naming the place that made it, in a URDF as in a xacro expansion, in the
forked child and in-process alike; a deep tree is written without recursion.
"""

from __future__ import annotations

import pytest
from click.testing import CliRunner
from kit import write
from kit.runaway_xacro import EXPRESSION_LINE, NS, expression_robot

from inertia_kit.cli import lint_main
from inertia_kit.description import safexml
from inertia_kit.description.loader import load
from inertia_kit.description.urdf import xacro_sandbox
from inertia_kit.errors import InputError


@pytest.fixture(params=["child", "in-process"])
def mode(request, monkeypatch) -> str:
    if request.param == "in-process":
        monkeypatch.setattr(xacro_sandbox, "can_fork", lambda: False)
    elif not xacro_sandbox.can_fork():
        pytest.skip("no os.fork here")
    return request.param


def test_a_long_name_made_by_an_expression_is_refused_at_its_line(tmp_path, mode):
    robot = write(tmp_path / "long.xacro", expression_robot("'x'*10**8"))
    with pytest.raises(InputError) as caught:
        load(robot)
    error = caught.value
    assert (error.path, error.line) == (str(robot), EXPRESSION_LINE)
    assert "<link name> holds 100000001 characters, more than the 65536" in error.message


@pytest.mark.parametrize(
    ("expression", "words"),
    [
        ("'x'*65535", None),  # at the bound (the name is `a` and this): read
        ("'x'*65536", "<link name> holds 65537 characters"),
    ],
)
def test_the_value_bound(tmp_path, mode, expression, words):
    robot = write(tmp_path / "bound.xacro", expression_robot(expression))
    if words is None:
        assert len(load(robot).links[0].name) == 65536
        return
    with pytest.raises(InputError, match=words):
        load(robot)


def test_a_long_element_or_attribute_name_is_refused(tmp_path, mode):
    made = (
        f'<robot name="r" {NS}>\n  <link name="a"/>\n'
        "  <xacro:element xacro:name=\"${'e'*2000}\"/>\n</robot>\n"
    )
    with pytest.raises(InputError, match="an element name of 2000 characters") as caught:
        load(write(tmp_path / "element.xacro", made))
    assert caught.value.line == 3
    attribute = (
        f'<robot name="r" {NS}>\n  <link name="a">\n'
        '    <xacro:attribute name="${\'n\'*2000}" value="1"/>\n  </link>\n</robot>\n'
    )
    with pytest.raises(InputError, match="an attribute name of 2000 characters"):
        load(write(tmp_path / "attribute.xacro", attribute))


def test_an_expanded_robot_over_the_file_bound_is_refused(tmp_path, mode, monkeypatch):
    monkeypatch.setattr(safexml, "MAX_BYTES", 2000)
    links = "".join(f"<link name=\"l{i}${{'x'*1000}}\"/>" for i in range(3))
    robot = write(tmp_path / "many.xacro", f'<robot name="r" {NS}>{links}</robot>')
    with pytest.raises(InputError, match="the expanded robot is larger than 2000 bytes"):
        load(robot)


def test_a_urdf_value_over_the_bound_is_refused_at_its_place(tmp_path):
    robot = write(
        tmp_path / "long.urdf",
        f'<robot name="r">\n  <link name="a"/>\n  <link name="{"b" * 70_000}"/>\n</robot>\n',
    )
    result = CliRunner().invoke(lint_main, [str(robot)])
    assert result.exit_code == 2
    assert "long.urdf:3:3: <link name> holds 70000 characters, more than the 65536" in (
        result.output
    )
    assert len(result.output) < 1000


def test_what_the_lint_prints_of_a_long_name_is_bounded(tmp_path):
    robot = write(tmp_path / "long.xacro", expression_robot("'x'*10**8"))
    result = CliRunner().invoke(lint_main, [str(robot)])
    assert result.exit_code == 2 and len(result.output) < 1000


def test_a_deep_tree_is_written_without_recursion():
    import sys
    from xml.dom import minidom

    from inertia_kit.description.model import Source
    from inertia_kit.description.urdf.xacro_source_map import serialise

    document = minidom.Document()
    node = document.createElement("robot")
    document.appendChild(node)
    depth = sys.getrecursionlimit() * 3
    for _ in range(depth):
        node = node.appendChild(document.createElement("a"))
    text, sources = serialise(document.documentElement, Source("deep.xacro"))
    assert text == "<robot>" + "<a>" * (depth - 1) + "<a/>" + "</a>" * (depth - 1) + "</robot>"
    assert len(sources) == depth + 1
