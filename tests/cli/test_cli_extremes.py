"""
Issue 11, "no traceback, for any input": each reproducer through the real commands. Extreme
numbers are findings with the value and its place (IN004, IN026), encodings are read or
refused naming the file, and fill never writes a number the linter would refuse.
"""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner
from kit import write
from kit.urdf import box, collision, cylinder, inertial, joint, link, robot_lines, visual

from inertia_kit.cli import fill_main, lint_main, main

FORMATS = ["full", "concise", "json", "github", "sarif"]
BOX = collision(box(0.1, 0.1, 0.1))


def moving(*body: str) -> str:
    """A massless base and a link `arm` on a revolute joint, the arm on line 4."""
    return robot_lines(
        "  " + link("base") + "\n",
        "  " + joint("base", "arm") + "\n",
        "  " + link("arm", *body) + "\n",
    )


def lint(path, *args):
    return CliRunner().invoke(lint_main, [*args, str(path)])


def only(result, code):
    """The findings of ``code`` in a JSON run, checking nothing else went wrong."""
    assert "Traceback" not in result.output
    return [f for f in json.loads(result.stdout) if f["code"] == code]


@pytest.mark.parametrize(
    ("body", "element", "text"),
    [
        # OverflowError in IN011's rounding bound
        (inertial(1, 0.01, 0.01, "-1e308"), "<inertia izz>", "-1e308"),
        # LinAlgError in the principal moments
        (inertial(1, 0.01, "-1e308", 0.01), "<inertia iyy>", "-1e308"),
        # LinAlgError in forensics
        (inertial(1, 0.01, xyz="1e308 1e308 1e308"), "<inertial><origin xyz>", "1e308 1e308 1e308"),
        # the volume overflowed, and the message blamed the density
        (collision(box("1e308", "1e308", "1e308")), "<box size>", "1e308 1e308 1e308"),
        # accepted, and fill would have written 3e-319 kg
        (collision(cylinder(0.1, "1e-320")), "<cylinder length>", "1e-320"),
        (inertial("5e-324", 0.01), "<mass value>", "5e-324"),
        (inertial("1e51", 0.01), "<mass value>", "1e51"),
    ],
)
def test_extreme_numbers_are_invalid_numbers(tmp_path, body, element, text):
    path = write(tmp_path / "robot.urdf", moving(body, BOX if "collision" not in body else ""))
    for output_format in FORMATS:
        result = lint(path, "--output-format", output_format)
        assert result.exit_code == 1, result.output
        assert "Traceback" not in result.output
    (finding,) = only(lint(path, "--output-format", "json"), "IN004")
    assert (finding["line"], finding["link"]) == (4, "arm")
    assert f"`{element}` = {text!r} (" in finding["message"]
    assert "density" not in finding["message"]
    why = "subnormal" if "e-3" in text else "beyond ±1e50"
    assert why in finding["message"] and "no robot has such a value" in finding["detail"]


def test_report_of_an_extreme_tensor(tmp_path):
    path = write(tmp_path / "robot.urdf", moving(inertial(1, 0.01, "-1e308", 0.01), BOX))
    for args in ([], ["--format", "json"], ["--lumped"]):
        result = CliRunner().invoke(main, ["report", *args, str(path)])
        assert result.exit_code == 0 and "Traceback" not in result.output
    result = CliRunner().invoke(main, ["report", "--format", "json", str(path)])
    arm = json.loads(result.stdout)["links"][1]
    assert (arm["inertial"], arm["mass"]) == ("invalid", None)


def test_large_but_usable_numbers_are_computed(tmp_path):
    """1e50 is the largest usable magnitude: a 1e50 m box is a finding of its size, no error."""
    path = write(tmp_path / "robot.urdf", moving(inertial(1, 0.01), collision(box(1e50, 1, 1))))
    result = lint(path, "--output-format", "json")
    assert result.exit_code == 1
    assert only(result, "IN004") == [] and only(result, "IN026") == []


def test_joint_limits_keep_any_finite_number(tmp_path):
    """Limits are only compared: `1e16` for "unlimited" (real robots) or even 1e308 is fine."""
    text = moving(inertial(1, 0.01), BOX).replace('upper="1"', 'upper="1e308"')
    result = lint(write(tmp_path / "robot.urdf", text), "--output-format", "json")
    assert only(result, "IN004") == []


@pytest.mark.parametrize("length", ["1e-12", "1e-11"])
def test_a_dimension_thinner_than_an_atom_is_degenerate(tmp_path, length):
    path = write(
        tmp_path / "robot.urdf", moving(inertial(1, 0.01), collision(cylinder(0.1, length)))
    )
    (finding,) = only(lint(path, "--output-format", "json"), "IN026")
    assert f"a dimension of {length} m is below 1e-10 m, the size of an atom" in finding["detail"]


def test_contact_point_spheres_are_solids(tmp_path):
    """Drake's examples put 1e-7 m spheres at a block's corners as contact points."""
    shapes = collision('<sphere radius="1e-7"/>', xyz=(0.03, 0.03, -0.03))
    path = write(tmp_path / "robot.urdf", moving(inertial(1, 0.01), BOX, shapes))
    assert only(lint(path, "--output-format", "json"), "IN026") == []


# --- fill -----------------------------------------------------------------------------------


@pytest.mark.parametrize("fix", ["missing", "invalid", "all"])
def test_fill_refuses_a_subnormal_dimension(tmp_path, fix):
    """It wrote `cannot write nan` (with --fix all) or 3e-319 kg; now the link is refused."""
    text = moving(collision(cylinder(0.1, "1e-320")))
    path = write(tmp_path / "robot.urdf", text)
    result = CliRunner().invoke(fill_main, ["--fix", fix, str(path)])
    assert result.exit_code == 1 and "Traceback" not in result.output
    assert (
        "link `arm` not filled: its collision cylinder (r = 0.1 m, l = ? m): invalid number: "
        "its <cylinder length> is '1e-320', not a usable number (IN004)" in result.stderr
    )
    assert path.read_text() == text


def test_fill_refuses_what_the_linter_would_refuse(tmp_path):
    """Usable density and sizes whose product is not: the link is refused, not written."""
    text = moving(collision(box(1e-10, 1e-10, 1e-10)))
    path = write(tmp_path / "robot.urdf", text)
    result = CliRunner().invoke(fill_main, ["--density", "1e-20", str(path)])
    assert result.exit_code == 1
    assert (
        "link `arm` not filled: its computed mass would be written as 1e-50 (" not in result.stderr
    )
    assert (
        "link `arm` not filled: its computed ixx would be written as 1.66667e-71 (non-zero below "
        "1e-50), a number the linter refuses (IN004)" in result.stderr
    )
    assert path.read_text() == text


def test_fill_writes_at_the_edge(tmp_path):
    """An atom-sized cube of water: 1e-27 kg, 1.7e-48 kg·m², written and read back clean."""
    path = write(tmp_path / "robot.urdf", moving(collision(box(1e-10, 1e-10, 1e-10))))
    result = CliRunner().invoke(fill_main, ["--density", "1000", str(path)])
    assert result.exit_code == 1
    assert '<mass value="1e-27"/>' in path.read_text()
    again = lint(path, "--select", "IN004,IN026", "--output-format", "json")
    assert json.loads(again.stdout) == []


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--density", "1e308"], "'1e308' is beyond ±1e50"),
        (["--density", "nan"], "'nan' is not a number"),
        (["--total-mass", "1e-320"], "'1e-320' is subnormal"),
        (["--mass", "arm=1e300"], "--mass takes LINK=KG with a positive mass from 1e-50 to 1e50"),
        (["--density", "1e-51"], "'1e-51' is non-zero below 1e-50"),
    ],
)
def test_fill_options_take_usable_numbers(tmp_path, args, message):
    path = write(tmp_path / "robot.urdf", moving(BOX))
    result = CliRunner().invoke(fill_main, [*args, str(path)])
    assert result.exit_code == 2 and message in result.output


# --- encodings ------------------------------------------------------------------------------

XACRO = (
    '<?xml version="1.0" encoding="{encoding}"?>\n'
    '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
    "  <!-- {comment} -->\n"
    '  <xacro:property name="m" value="1"/>\n'
    '  <link name="base"/>\n'
    '  <link name="arm"><inertial><mass value="${{m}}"/>'
    '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>\n'
    '  <joint name="j" type="fixed"><parent link="base"/><child link="arm"/></joint>\n'
    "</robot>\n"
)


@pytest.mark.parametrize(
    ("encoding", "comment", "codec", "shown"),
    [
        # a ValueError from expat: "multi-byte encodings are not supported"
        ("shift_jis", "ロボット", "shift_jis", 'byte 0x83, declared encoding="shift_jis"'),
        ("iso-8859-1", "bras articulé", "latin-1", 'byte 0xe9, declared encoding="iso-8859-1"'),
        ("UTF-16", "arm", "utf-16", "is UTF-16 or UTF-32"),
    ],
)
def test_xacro_in_an_encoding_xacro_cannot_read_is_refused(
    tmp_path, encoding, comment, codec, shown
):
    """xacro reads every file as UTF-8 (it opens files as text) and fails on these."""
    path = write(
        tmp_path / "robot.urdf.xacro",
        XACRO.format(encoding=encoding, comment=comment).encode(codec),
    )
    for command in (lint_main, fill_main):
        result = CliRunner().invoke(command, [str(path)])
        assert result.exit_code == 2 and "Traceback" not in result.output
        assert f"error: {path}:" in result.stderr and shown in result.stderr
        assert "xacro reads every file as UTF-8" in result.stderr
    result = CliRunner().invoke(main, ["report", str(path)])
    assert result.exit_code == 2 and shown in result.stderr


@pytest.mark.parametrize("encoding", ["no-such-encoding", "shift_jis", "UTF-8", "ascii", "x" * 40])
def test_xacro_declaring_any_encoding_is_read_as_xacro_reads_it(tmp_path, encoding):
    """xacro ignores the declaration (a LookupError from expat before): so does the linter."""
    path = write(tmp_path / "robot.urdf.xacro", XACRO.format(encoding=encoding, comment="arm"))
    result = CliRunner().invoke(lint_main, ["--select", "IN002", str(path)])
    assert result.exit_code == 0, result.output


def test_urdf_declaring_an_unknown_encoding_is_read_as_tinyxml2_reads_it(tmp_path):
    """urdfdom, Gazebo, PyBullet, MuJoCo and Drake (TinyXML2) ignore the declaration."""
    text = XACRO.format(encoding="no-such-encoding", comment="arm").replace("${m}", "1")
    text = text.replace(' xmlns:xacro="http://www.ros.org/wiki/xacro"', "")
    text = text.replace('  <xacro:property name="m" value="1"/>\n', "")
    path = write(tmp_path / "robot.urdf", text)
    result = CliRunner().invoke(lint_main, ["--select", "IN002", str(path)])
    assert result.exit_code == 0, result.output
    # fill edits the text as the parser read it (UTF-8, the declaration ignored): the bytes
    # outside the edit, the declaration and the non-ASCII comment kept
    arm = text[text.index('  <link name="arm">') : text.index("</link>\n  <joint") + 8]
    box = '<geometry><box size="0.1 0.2 0.3"/></geometry>'
    bare = f'  <link name="arm"><collision>{box}</collision></link>\n'
    original = text.replace("<!-- arm -->", "<!-- ärm -->").replace(arm, bare).encode("utf-8")
    path.write_bytes(original)
    result = CliRunner().invoke(fill_main, ["--density", "1000", str(path)])
    assert result.exit_code == 1 and "Filled 1 link" in result.output, result.output
    written = path.read_bytes()
    head, tail = original.split(bare.encode())
    assert written.startswith(head) and written.endswith(tail)
    assert b'<mass value="6"/>' in written
    written.decode("utf-8")


def test_a_sphere_at_the_edge_of_float32_no_warning(tmp_path):
    """Found by hypothesis: the union of a 3.4e38 m sphere and a box warned of a float32 cast."""
    import warnings

    from inertia_kit.lint.runner import Selection, lint_file

    shapes = visual('<sphere radius="3.4016088931775435e+38"/>') + visual(box(1, 1, 1))
    path = write(tmp_path / "robot.urdf", moving(inertial(1, 0.01), shapes))
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        result = lint_file(path, Selection(select=("IN0",)))
    assert result.error is None and "IN022" in {f.code for f in result.findings}


@pytest.mark.parametrize("tiny", ["1e-300", "5e-324"])
def test_a_floating_child_with_a_vanishing_moment_under_every_engine(tmp_path, tiny):
    """Issue 19: a massless base with a floating child whose izz is 1e-300 was an internal
    error under --engine drake (LinAlgError: Eigenvalues did not converge)."""
    body = inertial(1, 0.01, 0.01, tiny)
    text = robot_lines(
        "  " + link("base") + "\n",
        "  " + joint("base", "arm", "floating") + "\n",
        "  " + link("arm", body) + "\n",
    )
    path = write(tmp_path / "robot.urdf", text)
    for engine in ("drake", "all"):
        result = lint(path, "--engine", engine, "--output-format", "json")
        assert result.exit_code == 1, result.output
        assert only(result, "IN004")  # the value itself


@pytest.mark.parametrize(("rule", "option"), [("IN020", "factor_below"), ("IN073", "factor")])
def test_a_factor_below_one_is_refused_naming_the_key(tmp_path, rule, option):
    """factor_below = 0 divided by zero (an internal error; found by the fuzz run)."""
    write(tmp_path / "pyproject.toml", f"[tool.inertia-kit.rules.{rule}]\n{option} = 0.0\n")
    path = write(tmp_path / "robot.urdf", moving(inertial(1, 0.01), visual(box(1, 1, 1))))
    result = CliRunner().invoke(lint_main, [str(path)])
    assert result.exit_code == 2 and "Traceback" not in result.output
    assert f"rules.{rule}.{option}`: expected a number from 1 up, got 0.0" in result.stderr


def test_a_fix_after_non_ascii_on_its_line_in_a_file_declaring_latin_1(tmp_path):
    """
    The parser reads ISO-8859-1 a byte a character; UTF-8 bytes before the element on its line
    (`é` is two of them) put its column two characters off in a UTF-8 reading: "no start tag",
    an internal error (found by the fuzz run, seed s1, input 4944).
    """
    text = (
        '<?xml version="1.0" encoding="ISO-8859-1"?>\n<robot name="r">\n'
        '  <link name="base"><inertial><mass value="1"/>'
        '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>\n'
        '  <joint name="j" type="fixed"><parent link="base"/><child link="arm"/></joint>\n'
        '  <link name="arm"><inertial><!-- \u00e9\u00fc --><mass value="1"/>'
        '<inertia ixx="1666.67" ixy="0" ixz="0" iyy="1666.67" iyz="0" izz="1666.67"/>'
        "</inertial>\n"
        '    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>\n'
        "</robot>\n"
    )
    original = text.encode("utf-8")
    path = tmp_path / "robot.urdf"
    path.write_bytes(original)
    result = CliRunner().invoke(lint_main, ["--fix", "--select", "IN063", str(path)])
    assert result.exit_code == 0, result.output
    fixed = original.replace(b'"1666.67"', b'"0.00166667"')
    assert path.read_bytes() == fixed
