"""
Line endings and encodings through every writer: a lone CR ends a line (as XML and expat count,
not as lxml does), so a robot written with CR-only, CRLF, LF, mixed endings or in UTF-16 gets
the same findings at the same lines, its fixes land where they belong, and the comments
``--add-noqa`` writes suppress what they were written for: a second run adds nothing, and the
bytes outside the comments are kept.
"""

from __future__ import annotations

import json
import re

import pytest
from click.testing import CliRunner
from kit import write

from inertia_kit.cli import fill_main, lint_main

ROBOT = """\
<?xml version="1.0"?>
<robot name="r">
  <!-- a comment -->
  <link name="world"/>
  <joint name="j_base" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="base">
    <inertial><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <joint name="j_arm" type="revolute">
    <parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <link name="arm">
    <inertial>
      <mass value="2"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
    <collision><geometry><box size="0.1 0.2 0.3"/></geometry></collision>
  </link>
  <link name="hand">
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
  <joint name="j_hand" type="revolute">
    <parent link="arm"/><child link="hand"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
</robot>
"""

XACRO = ROBOT.replace(
    '<robot name="r">', '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
).replace('<mass value="2"/>', '<xacro:property name="m" value="2"/><mass value="${m}"/>')


def _mixed(text: str) -> str:
    """Lone CRs here and there before the links that get fixes, LF elsewhere."""
    lines = text.split("\n")
    return "".join(line + ("\r" if i % 3 == 1 else "\n") for i, line in enumerate(lines[:-1]))


ENDINGS = {
    "lf": lambda t: t,
    "crlf": lambda t: t.replace("\n", "\r\n"),
    "cr": lambda t: t.replace("\n", "\r"),
    "mixed": _mixed,
    "lf-cr": lambda t: t.replace("\n", "\n\r"),  # a blank line each: LF, then a lone CR
}
ENCODINGS = {
    "utf-8": lambda t: t.encode("utf-8"),
    "utf-8-sig": lambda t: t.encode("utf-8-sig"),
    "utf-16": lambda t: t.encode("utf-16"),
    "utf-16-be": lambda t: b"\xfe\xff" + t.encode("utf-16-be"),
}


def declared(text: str, encoding: str) -> str:
    """``text`` with the XML declaration a file in ``encoding`` has."""
    if encoding.startswith("utf-16"):
        return text.replace('version="1.0"', 'version="1.0" encoding="UTF-16"', 1)
    return text


_COMMENT = re.compile(r"[ \t]*<!-- inertia-lint: ignore\[[A-Z0-9, ]*\] -->(\r\n|\r|\n)?")


def variants():
    """``(suffix, ending, encoding)``: xacro reads its files as UTF-8 only."""
    for suffix in ("urdf", "xacro"):
        for ending in ENDINGS:
            for encoding in ENCODINGS if suffix == "urdf" else ("utf-8", "utf-8-sig"):
                yield pytest.param(suffix, ending, encoding, id=f"{suffix}-{ending}-{encoding}")


def decoded(data: bytes, encoding: str) -> str:
    if encoding == "utf-16-be":
        return data[2:].decode("utf-16-be")
    return data.decode(encoding)


def lint(*args) -> object:
    return CliRunner().invoke(lint_main, [*map(str, args)])


def findings(path) -> list[tuple[str, int, int]]:
    result = lint("--output-format", "json", "--exit-zero", path)
    assert result.exit_code == 0, result.output
    return sorted((f["code"], f["line"], f["column"]) for f in json.loads(result.stdout))


@pytest.fixture(scope="module")
def reference(tmp_path_factory) -> dict[str, list]:
    """The findings of the LF, UTF-8 files: what every variant must report."""
    folder = tmp_path_factory.mktemp("reference")
    return {
        suffix: findings(write(folder / f"robot.{suffix}", text))
        for suffix, text in (("urdf", ROBOT), ("xacro", XACRO))
    }


@pytest.mark.parametrize(("suffix", "ending", "encoding"), variants())
def test_findings_stand_at_the_same_lines(tmp_path, reference, suffix, ending, encoding):
    text = declared(ENDINGS[ending](ROBOT if suffix == "urdf" else XACRO), encoding)
    path = write(tmp_path / f"robot.{suffix}", ENCODINGS[encoding](text))
    found = findings(path)
    if ending == "lf-cr":  # every line is followed by an empty one: line n is line 2n - 1
        found = sorted((code, (line + 1) // 2, column) for code, line, column in found)
    assert found == reference[suffix]
    assert found, "the robot has findings"


@pytest.mark.parametrize(("suffix", "ending", "encoding"), variants())
def test_add_noqa_suppresses_once_and_keeps_every_other_byte(tmp_path, suffix, ending, encoding):
    text = declared(ENDINGS[ending](ROBOT if suffix == "urdf" else XACRO), encoding)
    before = ENCODINGS[encoding](text)
    path = write(tmp_path / f"robot.{suffix}", before)
    assert lint(path).exit_code == 1
    result = lint("--add-noqa", path)
    assert result.exit_code == 0, result.output
    after = path.read_bytes()
    assert after != before
    assert after[:2] == before[:2], "the byte-order mark is kept"
    assert _COMMENT.sub("", decoded(after, encoding)) == decoded(before, encoding)
    assert lint(path).exit_code == 0, lint(path).output  # the comments suppress
    again = lint("--add-noqa", path)
    assert again.exit_code == 0
    assert path.read_bytes() == after, "a second run added comments"


@pytest.mark.parametrize(("suffix", "ending", "encoding"), variants())
def test_fixes_land_where_they_belong(tmp_path, suffix, ending, encoding):
    convert = ENDINGS[ending]
    lf = write(tmp_path / "lf" / f"robot.{suffix}", ROBOT if suffix == "urdf" else XACRO)
    variant = ENCODINGS[encoding](declared(convert(lf.read_text()), encoding))
    path = write(tmp_path / "v" / f"robot.{suffix}", variant)
    for command in (lint_main, fill_main):
        args = ["--fix", "--unsafe-fixes"] if command is lint_main else ["--fix", "all"]
        for target in (lf, path):
            result = CliRunner().invoke(command, [*args, str(target)])
            assert result.exit_code in (0, 1), result.output
            assert "internal error" not in result.output
    fixed = lf.read_text()
    assert fixed != (ROBOT if suffix == "urdf" else XACRO)
    # the same edits, the encoding kept; lines compared as lines (the lf-cr variant's blank
    # ones left out: a new block takes the file's first line ending only)
    got = decoded(path.read_bytes(), encoding)
    assert re.sub(r"(\r\n|\r|\n)+", "\n", got) == declared(fixed, encoding)
    assert lint(path).exit_code == lint(lf).exit_code
