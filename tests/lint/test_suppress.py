"""Suppression comments: what `ignore[...]` covers, `disable-file`, xacro files, bad comments."""

from __future__ import annotations

import os
import types
from pathlib import Path

import pytest
from kit import least_cpu, write
from kit.urdf import link_lines, robot_lines

from inertia_kit.lint import catalog
from inertia_kit.lint.findings import Severity
from inertia_kit.lint.runner import Selection, lint_file
from inertia_kit.lint.suppress import Ignore, directives


def _rule(code: str, name: str, where: str) -> types.ModuleType:
    """A stub rule firing on every link with an <inertial>, at its <mass> or its <link>."""
    rule = types.ModuleType(f"inertia_kit.lint.rules.{code.lower()}_{name.replace('-', '_')}")
    rule.CODE, rule.NAME, rule.SEVERITY, rule.SCOPE = code, name, Severity.WARNING, "link"
    rule.SUMMARY = name

    def check(link, ctx):
        inertial = link.link.inertial
        if inertial is not None:
            source = inertial.mass_source if where == "mass" else link.link.source
            yield ctx.finding(f"{code} on {link.name}", source, link=link.name)

    rule.check = check
    return rule


AT_MASS = _rule("IN098", "stub-at-mass", "mass")
AT_LINK = _rule("IN099", "stub-at-link", "link")


@pytest.fixture(autouse=True)
def stubs(monkeypatch):
    monkeypatch.setattr(catalog, "RULES", (AT_MASS, AT_LINK))


def link(name: str, before: str = "", indent: str = "  ") -> str:
    """A 1 kg link with a unit tensor, one element a line, ``before`` on its first line."""
    return link_lines(name, 1, 1, indent=indent, before=before)


def found(tmp_path: Path, text: str, name: str = "robot.urdf") -> set[tuple[str, str]]:
    path = tmp_path / name
    path.write_text(text)
    result = lint_file(path, Selection())
    assert result.error is None, result.error
    return {(f.code, f.link) for f in result.findings}


EVERYTHING = {("IN098", "a"), ("IN099", "a"), ("IN098", "b"), ("IN099", "b")}


@pytest.mark.parametrize(
    ("comment", "left"),
    [
        ("", EVERYTHING),
        ("<!-- inertia-lint: ignore[IN098] -->", EVERYTHING - {("IN098", "a")}),
        ("<!-- inertia-lint: ignore[stub-at-mass] -->", EVERYTHING - {("IN098", "a")}),
        ("<!-- inertia-lint: ignore[IN09] -->", {("IN098", "b"), ("IN099", "b")}),
        ("<!-- inertia-lint: ignore[ IN098 ,stub-at-link ] -->", {("IN098", "b"), ("IN099", "b")}),
        (
            "<!--inertia-lint:ignore[IN099] measured on a scale, 2024-->",
            EVERYTHING - {("IN099", "a")},
        ),
        ("<!-- inertia-lint: ignore[IN012] -->", EVERYTHING),  # another rule
        ("<!-- ignore[IN098] -->", EVERYTHING),  # not ours
    ],
)
def test_ignore_covers_the_next_element_and_its_inside(tmp_path, comment, left):
    text = robot_lines(f"  {comment}\n" + link("a"), link("b"))
    assert found(tmp_path, text) == left


def test_what_an_ignore_covers_and_does_not(tmp_path):
    # on the element's own line, several comments in a row, a multi-line start tag
    text = robot_lines(
        link("a", before="<!-- inertia-lint: ignore[IN099] -->"),
        "  <!-- inertia-lint: ignore[IN098] -->\n  <!-- a note -->\n"
        '  <!-- inertia-lint: ignore[IN099] -->\n  <link\n      name="b">\n'
        '    <inertial><mass value="1"/>\n'
        '      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>\n'
        "  </link>\n",
        link("c"),
    )
    assert found(tmp_path, text) == {("IN098", "a"), ("IN098", "c"), ("IN099", "c")}


def test_an_ignore_before_the_robot_covers_the_file_for_its_codes(tmp_path):
    text = robot_lines(
        link("a"), link("b"), head="<?xml version='1.0'?>\n<!-- inertia-lint: ignore[IN099] -->\n"
    )
    assert found(tmp_path, text) == {("IN098", "a"), ("IN098", "b")}


@pytest.mark.parametrize("where", ["top", "inside", "end"])
def test_disable_file_anywhere(tmp_path, where):
    directive = "<!-- inertia-lint: disable-file -->\n"
    text = robot_lines(link("a"), directive if where == "inside" else "", link("b"))
    text = directive + text if where == "top" else text + (directive if where == "end" else "")
    path = tmp_path / "robot.urdf"
    path.write_text(text)
    result = lint_file(path, Selection())
    assert (result.findings, result.disabled, result.error) == ([], True, None)


def test_line_spans(tmp_path):
    path = tmp_path / "spans.urdf"
    path.write_text(
        "<robot name='r'>\n"  # 1
        "  <!-- inertia-lint:\n"  # 2
        "       ignore[IN098] -->\n"  # 3
        "  <link\n"  # 4
        "     name='a'>\n"  # 5
        "    <visual><geometry>\n"  # 6
        "      <box size='1 1 1'/></geometry>\n"  # 7
        "    </visual>\n"  # 8
        "    <!-- last child a comment\n"  # 9
        "    -->\n"  # 10
        "  </link>\n"  # 11
        "  <!-- inertia-lint: ignore[IN099] --> <link name='b'/>\n"  # 12
        "  <!-- inertia-lint: ignore[IN098] --><link name='c'>text\n"  # 13
        "  more text</link>\n"  # 14
        "</robot>\n"
    )
    assert directives(path).ignores == (
        Ignore(("IN098",), 4, 11, 2),
        Ignore(("IN099",), 12, 12, 12),
        Ignore(("IN098",), 13, 14, 13),
    )


XACRO_MACROS = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="part" params="name">
    <link name="${name}">
      <inertial>
        MASS
        <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
      </inertial>
    </link>
  </xacro:macro>
</robot>
"""
XACRO_TOP = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="parts.xacro"/>
  CALL_A<xacro:part name="a"/>
  <xacro:part name="b"/>
</robot>
"""


@pytest.mark.parametrize(
    ("in_macro", "before_call", "left"),
    [
        ("", "", EVERYTHING),
        # in the macro body: every instance
        ("<!-- inertia-lint: ignore[IN098] -->", "", {("IN099", "a"), ("IN099", "b")}),
        # before one call: that instance, every code it covers
        ("", "<!-- inertia-lint: ignore[IN098,IN099] -->", {("IN098", "b"), ("IN099", "b")}),
        # disable-file in the included file: what its macros produce
        ("<!-- inertia-lint: disable-file -->", "", set()),
    ],
)
def test_xacro_comments_in_the_macro_body_and_before_the_call(
    tmp_path, in_macro, before_call, left
):
    (tmp_path / "parts.xacro").write_text(
        XACRO_MACROS.replace("MASS", f'{in_macro}<mass value="1"/>')
    )
    text = XACRO_TOP.replace("CALL_A", before_call)
    assert found(tmp_path, text, "robot.urdf.xacro") == left


def test_elements_of_an_included_file_read_its_comments(tmp_path):
    (tmp_path / "links.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        + link("a", before="<!-- inertia-lint: ignore[IN098] -->")
        + link("b")
        + "</robot>\n"
    )
    text = (
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="links.xacro"/>\n</robot>\n'
    )
    assert found(tmp_path, text, "robot.xacro") == EVERYTHING - {("IN098", "a")}


def test_comments_we_do_not_understand_become_notes(tmp_path):
    (tmp_path / "parts.xacro").write_text(
        XACRO_MACROS.replace("MASS", '<!-- inertia-lint: ignore[IN98] --><mass value="1"/>')
    )
    text = XACRO_TOP.replace("CALL_A", "<!-- inertia-lint: disable-line -->\n  ").replace(
        "</robot>",
        "  <!-- inertia-lint: ignore[] -->\n  <!-- inertia-lint: ignore[IN098] -->\n</robot>",
    )
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(text)
    result = lint_file(path, Selection())
    assert {(f.code, f.link) for f in result.findings} == EVERYTHING
    assert result.notes == [
        f"{path}:4: inertia-lint comment ignored: unknown directive `disable-line`: expected "
        "`ignore[CODE, ...]` or `disable-file`",
        f"{path}:7: inertia-lint comment ignored: `ignore[]` names no rule: give codes or names",
        f"{path}:8: inertia-lint comment ignored: `ignore[...]` is not followed by an element "
        "it could cover",
        f"{tmp_path / 'parts.xacro'}:6: inertia-lint comment ignored: `IN98` is not a rule code, "
        "code prefix or rule name (did you mean `IN098`?)",
    ]


def test_directives_are_read_once_per_content(tmp_path, monkeypatch):
    from inertia_kit.description import xmlparse

    path = tmp_path / "robot.urdf"
    path.write_text(robot_lines(link("a", before="<!-- inertia-lint: ignore[IN098] -->")))
    parsed = []
    real = xmlparse.parse_xml
    monkeypatch.setattr(xmlparse, "parse_xml", lambda data, p: parsed.append(p) or real(data, p))
    first = directives(path)
    assert directives(path) is first
    assert parsed == [str(path)]
    path.write_text(robot_lines(link("a", before="<!-- inertia-lint: disable-file -->")))
    stat = path.stat()
    os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns + 1_000_000_000))
    assert directives(path).disabled
    assert len(parsed) == 2


def test_files_without_directives_or_unreadable_cover_nothing(tmp_path):
    plain = tmp_path / "plain.urdf"
    plain.write_text(robot_lines(link("a")))
    broken = tmp_path / "broken.urdf"
    broken.write_text("<robot><!-- inertia-lint: disable-file --><link></robot>")
    for path in (plain, broken, tmp_path / "missing.urdf", tmp_path):
        covered = directives(path)
        assert (covered.disabled, covered.ignores, covered.problems) == (False, (), ())


def test_suppression_comments_are_read_from_the_overlay(tmp_path: Path):
    """The comments of a file on disk are cached by its size and time of change: a pass that
    holds another text of it must not be served the disk's."""
    from inertia_kit.description.overlay import overlaid

    comment = b"<robot>\n  <!-- inertia-lint: ignore[IN098] -->\n  <link name='a'/>\n</robot>\n"
    path = write(tmp_path / "a.urdf", comment)
    assert directives(path).holding(3)  # cached: the disk's text
    held = comment.replace(b"ignore[IN098]", b"the comment was removed")
    with overlaid({os.path.realpath(path): held}):
        assert not directives(path).holding(3)
    assert directives(path).holding(3)


def test_a_directive_with_a_long_run_of_blanks_is_read_in_linear_time(tmp_path: Path):
    """A directive with a run of blanks between its words (a hostile pull request): 8 times as
    many blanks take ~8 times as long to read (a lazy group before ``\\s*\\Z`` took ~64 times,
    4 s at 32 000), and the directive is read as before."""
    from inertia_kit.lint import suppress

    def seconds(blanks):
        comment = f"<!-- inertia-lint: ignore[IN098,{' ' * blanks}IN099] -->"
        text = robot_lines(link("a", before=comment))
        path = write(tmp_path / f"r{blanks}.urdf", text)
        # each read again, not from the cache
        spent, read = least_cpu(
            lambda: directives(str(path)), runs=5, before=suppress._directives.cache_clear
        )
        assert all([i.selectors for i in found.ignores] == [("IN098", "IN099")] for found in read)
        return spent

    assert seconds(32000) / max(seconds(4000), 1e-6) < 24
