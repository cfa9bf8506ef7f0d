"""Xacro expansion through the real xacro package: what xacro refuses, and unsafe or oversized
files, as input errors naming the file and line at fault."""

from __future__ import annotations

from pathlib import Path

import pytest
from kit import write

from inertia_kit.description.urdf.xacro_expand import expand
from inertia_kit.errors import InputError

NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def include(filename: str) -> str:
    """An include line."""
    return f'  <xacro:include filename="{filename}"/>\n'


@pytest.mark.parametrize(
    ("body", "line", "fragment"),
    [
        ('  <link name="a"/>\n  <link name="${undefined_thing}"/>\n', 3, "undefined_thing"),
        ('  <link name="a"/>\n  <link name="${1 +* 2}"/>\n', 3, "1 +* 2"),
        ('  <link name="a"/>\n  <xacro:include filename="gone.xacro"/>\n', 3, "gone.xacro"),
        ('  <link name="a"/>\n  <xacro:no_such_macro/>\n', 3, "unknown macro name"),
        (
            '  <xacro:macro name="m" params="x">\n    <link name="${x}_${y}"/>\n'
            '  </xacro:macro>\n  <xacro:m x="1"/>\n',
            3,
            "called at",
        ),
    ],
    ids=["undefined-property", "bad-expression", "missing-include", "unknown-macro", "in-macro"],
)
def test_xacro_errors_name_the_file_and_line(tmp_path, body, line, fragment):
    robot = write(tmp_path / "bad.xacro", f'<robot name="r" {NS}>\n{body}</robot>\n')
    with pytest.raises(InputError) as caught:
        expand(robot)
    assert (caught.value.path, caught.value.line) == (str(robot), line)
    assert fragment in caught.value.message
    assert str(caught.value).startswith(f"{robot}:{line}:")


def test_runaway_recursion_is_an_input_error_with_a_short_message(tmp_path):
    robot = write(
        tmp_path / "loop.xacro",
        f'<robot name="r" {NS}>\n  <xacro:macro name="loop" params="n">\n'
        '    <xacro:loop n="${n+1}"/>\n  </xacro:macro>\n  <xacro:loop n="0"/>\n</robot>\n',
    )
    with pytest.raises(InputError) as caught:
        expand(robot)
    assert (caught.value.path, caught.value.line) == (str(robot), 3)
    assert "recursion" in caught.value.message
    assert "times)" in caught.value.message and len(caught.value.message) < 400


def test_error_in_an_include_names_the_include(tmp_path):
    write(tmp_path / "inc.xacro", f'<robot {NS}>\n\n  <link name="${{oops}}"/>\n</robot>\n')
    robot = write(
        tmp_path / "robot.xacro",
        f'<robot name="r" {NS}>\n  <xacro:include filename="inc.xacro"/>\n</robot>\n',
    )
    with pytest.raises(InputError) as caught:
        expand(robot)
    assert (Path(caught.value.path), caught.value.line) == (tmp_path / "inc.xacro", 3)


def test_malformed_include(tmp_path):
    write(tmp_path / "inc.xacro", '<robot>\n  <link name="x">\n</robot>\n')
    robot = write(
        tmp_path / "robot.xacro",
        f'<robot name="r" {NS}>\n  <link name="a"/>\n{include("inc.xacro")}</robot>\n',
    )
    with pytest.raises(InputError) as caught:
        expand(robot)
    assert (Path(caught.value.path), caught.value.line) == (tmp_path / "inc.xacro", 3)
    assert "not well-formed" in caught.value.message


def test_missing_input(tmp_path):
    with pytest.raises(InputError, match="cannot read"):
        expand(tmp_path / "nothing.xacro")


XXE = f"""<?xml version="1.0"?>
<!DOCTYPE robot [
  <!ENTITY secret SYSTEM "{{uri}}">
]>
<robot name="r" {NS}>
  <link name="&secret;"/>
</robot>
"""

LAUGHS = f"""<?xml version="1.0"?>
<!DOCTYPE robot [
  <!ENTITY lol "lol">
  <!ENTITY lol2 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">
  <!ENTITY lol3 "&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;">
  <!ENTITY lol4 "&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;">
  <!ENTITY lol5 "&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;">
  <!ENTITY lol6 "&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;">
  <!ENTITY lol7 "&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;">
  <!ENTITY lol8 "&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;">
  <!ENTITY lol9 "&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;">
]>
<robot name="r" {NS}>
  <link name="&lol9;"/>
</robot>
"""


@pytest.mark.parametrize("template", [XXE, LAUGHS], ids=["external-entity", "billion-laughs"])
@pytest.mark.parametrize("included", [False, True], ids=["input", "include"])
def test_entity_declarations_are_refused(tmp_path, template, included):
    secret = write(tmp_path / "secret.txt", "secret")
    evil = write(tmp_path / "evil.xacro", template.replace("{uri}", secret.as_uri()))
    path = evil
    if included:
        path = write(
            tmp_path / "robot.xacro",
            f'<robot name="r" {NS}>\n  <link name="a"/>\n{include("evil.xacro")}</robot>\n',
        )
    with pytest.raises(InputError) as caught:
        expand(path)
    assert (caught.value.path, caught.value.line) == (str(evil), 3)
    assert "entity declarations are not allowed: nothing was expanded" in caught.value.message


def test_entity_declaration_in_utf16_is_refused_unread(tmp_path):
    """xacro reads files as UTF-8: a UTF-16 one is refused before any entity is looked at."""
    text = XXE.replace("{uri}", "file:///etc/hostname").replace(
        ' version="1.0"', ' version="1.0" encoding="UTF-16"'
    )
    evil = tmp_path / "evil16.xacro"
    evil.write_bytes(text.encode("utf-16"))
    with pytest.raises(InputError, match="is UTF-16 or UTF-32: xacro reads every file as UTF-8"):
        expand(evil)


def test_oversized_files_are_refused(tmp_path, monkeypatch):
    from inertia_kit.description import safexml

    robot = write(tmp_path / "big.xacro", f'<robot name="r" {NS}>\n  <link name="a"/>\n</robot>\n')
    monkeypatch.setattr(safexml, "MAX_BYTES", 32)
    with pytest.raises(InputError, match="larger than 32 bytes"):
        expand(robot)
