"""
Workflow commands and terminal escapes planted in a robot (link and joint names, a value that
reaches a message, mesh file names, the robot's own folder) through every command and output
format: the text outputs show them escaped, each on its line; the machine-read formats stay
valid and carry the exact names.

GitHub Actions reads a line ``::error file=...::text`` on stdout or stderr as a workflow command,
whichever step printed it: a link name ``"\\n::error ..."`` printed as it is would annotate any
file with any text, and a terminal reads ``ESC [`` (or its one-byte form, U+009B) as a command.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from kit import write
from kit.in_process import run_split
from kit.meshes import box_triangles, write_binary_stl

from inertia_kit.cli import main
from inertia_kit.printable import UNPRINTABLE, printable

WORKFLOW = "::error file=pwned.py,line=1::INJECTED"
# in XML: a newline, the workflow command, a C1 CSI, a right-to-left override, a line
# separator, NEL and a CR (XML 1.0 holds no ESC, even as a reference: the file system does)
PLANTED = f"&#10;{WORKFLOW}&#x9b;31m&#x202e;&#x2028;&#x85;&#13;"
EXACT = f"\n{WORKFLOW}\x9b31m\u202e\u2028\x85\r"
# the robot's folder: ESC, a newline, the command, a line separator, an override
FOLDER = f"robots\x1b[31m\n{WORKFLOW}\u2028\u202e"
MESH = f"mesh\n{WORKFLOW}\x9b31m.stl"  # a file name (XML: PLANTED's first two parts)
ROBOT = f"""<?xml version="1.0"?>
<robot name="r{PLANTED}">
  <link name="base{PLANTED}"/>
  <joint name="j{PLANTED}" type="revolute">
    <parent link="base{PLANTED}"/><child link="arm{PLANTED}"/>
    <axis xyz="0 0 1"/>
  </joint>
  <link name="arm{PLANTED}">
    <inertial>
      <mass value="1{PLANTED}"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
    <collision><geometry><mesh filename="mesh&#10;{WORKFLOW}&#x9b;31m.stl"/></geometry></collision>
    <visual><geometry><mesh filename="gone{PLANTED}.stl"/></geometry></visual>
  </link>
</robot>
"""
ROBOT_FILE = f"{FOLDER}/robot.urdf"
BROKEN_FILE = f"{FOLDER}/broken{EXACT}.urdf"
NAMES = {f"base{EXACT}", f"arm{EXACT}", f"j{EXACT}"}  # as the machine formats carry them


@pytest.fixture
def robots(tmp_path, monkeypatch):
    """The robot, its mesh and an unreadable robot, in the planted folder under the cwd."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("CI_PROJECT_DIR", str(tmp_path))  # gitlab's paths: relative to it
    write(tmp_path / ROBOT_FILE, ROBOT)
    write_binary_stl(tmp_path / FOLDER / MESH, box_triangles((0.1, 0.1, 0.1)))
    write(tmp_path / BROKEN_FILE, "<robot><link name='x'>")
    return tmp_path


def run(*args: str, input: str | None = None) -> tuple[int, str, str]:
    return run_split(main, args, input)


def safe(text: str) -> str:
    """``text``, checked to be safe in a terminal and a CI log: no line is (or, indented,
    reads as) a workflow command, and nothing but its line feeds is a control character."""
    for line in text.splitlines():
        assert not line.lstrip().startswith("::"), line
    raw = {c for c in UNPRINTABLE.findall(text) if c != "\n"}
    assert not raw, f"raw {raw!r} in {text!r}"
    return text


def shown(text: str) -> str:
    """``text`` as the text outputs must show it."""
    return printable(text)


# --- inertia-lint: the text formats -------------------------------------------------------------


@pytest.mark.parametrize(
    "options",
    [
        ("--output-format", "full"),
        ("--output-format", "concise"),
        ("--statistics",),
        ("--diff", "--unsafe-fixes"),
        ("-q",),
    ],
    ids=lambda options: " ".join(options),
)
def test_lint_text_outputs(robots, options):
    code, out, err = run("lint", *options, ROBOT_FILE, BROKEN_FILE)
    assert code in (1, 2)
    safe(out), safe(err)
    # the unreadable file is told, its name escaped
    assert f"error: {shown(BROKEN_FILE)}:" in err
    if options[-1] in ("full", "concise", "-q"):
        assert f"link `{shown('arm' + EXACT)}`" in out
        assert f"joint `{shown('j' + EXACT)}`" in out
        assert f"{shown(ROBOT_FILE)}:" in out
    if options[-1] in ("full", "-q"):  # a value quoted in a detail (concise shows none)
        assert shown(f"gone{EXACT}.stl") in out  # a mesh name in a message
        assert repr(f"1{EXACT}").replace("\\r", "\\r") in out or shown(f"1{EXACT}") in out
    if "--diff" in options:
        assert f"--- a/{shown(ROBOT_FILE)}\n+++ b/{shown(ROBOT_FILE)}\n" in out


def test_lint_show_files_explain_and_output_file(robots):
    code, out, err = run("lint", "--show-files", ".")
    assert code == 0 and f"{shown(ROBOT_FILE)}\n" in safe(out)
    code, out, err = run("lint", "--explain", f"IN\n{WORKFLOW}")
    assert code == 2 and shown(WORKFLOW) in safe(err)
    code, out, err = run("lint", "-o", "report.txt", ROBOT_FILE)
    assert code == 1 and f"link `{shown('arm' + EXACT)}`" in safe(Path("report.txt").read_text())


def test_lint_add_noqa_and_fix_messages(robots):
    _, _, err = run("lint", "--add-noqa", ROBOT_FILE)
    assert "Added" in safe(err) and shown(ROBOT_FILE) in err
    _, out, err = run("lint", "--fix", "--unsafe-fixes", ROBOT_FILE)
    safe(out), safe(err)


# --- inertia-lint: the machine-read formats ---------------------------------------------------


def findings(robots) -> list[dict]:
    """The findings, as the json format gives them."""
    return json.loads(run("lint", "--output-format", "json", ROBOT_FILE, BROKEN_FILE)[1])


def test_json_carries_the_exact_names(robots):
    _, out, _ = run("lint", "--output-format", "json", ROBOT_FILE, BROKEN_FILE)
    data = json.loads(safe(out))
    assert {f["link"] for f in data} | {f["joint"] for f in data} >= NAMES
    assert {f["file"] for f in data} == {ROBOT_FILE, BROKEN_FILE}
    assert any(f"gone{EXACT}.stl" in f["message"] for f in data)


def test_sarif_carries_the_exact_names(robots):
    _, out, _ = run("lint", "--output-format", "sarif", ROBOT_FILE, BROKEN_FILE)
    run_ = json.loads(safe(out))["runs"][0]
    properties = [r["properties"] for r in run_["results"]]
    assert {p.get("link") for p in properties} | {p.get("joint") for p in properties} >= NAMES
    notification = run_["invocations"][0]["toolExecutionNotifications"][0]
    assert "%0A" in notification["locations"][0]["physicalLocation"]["artifactLocation"]["uri"]


def test_gitlab_carries_the_exact_names(robots):
    _, out, _ = run("lint", "--output-format", "gitlab", ROBOT_FILE, BROKEN_FILE)
    issues = json.loads(safe(out))
    assert {i["location"]["path"] for i in issues} == {ROBOT_FILE, BROKEN_FILE}
    assert any(f"link `arm{EXACT}`" in i["description"] for i in issues)


def test_junit_is_xml_with_the_names_xml_can_hold(robots):
    _, out, _ = run("lint", "--output-format", "junit", ROBOT_FILE, BROKEN_FILE)
    root = ET.fromstring(safe(out).encode())
    cases = root.iter("testcase")
    files = {case.get("file") for case in cases}
    # XML 1.0 holds the newline, the C1, the separators, the CR; not the ESC: shown as \x1b
    assert files == {p.replace("\x1b", "\\x1b") for p in (ROBOT_FILE, BROKEN_FILE)}
    messages = [f.get("message") for f in root.iter("failure")]
    assert any(f"link `arm{EXACT}`" in m for m in messages)
    texts = [f.text for f in root.iter("failure")]
    assert any(f"link `arm{EXACT}`" in t for t in texts)  # a CR in text content kept too


def _unescape(text: str) -> str:
    for escaped, char in (("%0D", "\r"), ("%0A", "\n"), ("%3A", ":"), ("%2C", ","), ("%25", "%")):
        text = text.replace(escaped, char)
    return text


def _as_github_shows(text: str) -> str:
    """CR and LF exact (GitHub escapes them, and decodes them in the annotation); the other
    characters that could disguise the log line as their escapes, as the text formats show."""
    return "".join(c if c in "\r\n" or "\ud800" <= c <= "\udfff" else printable(c) for c in text)


def test_github_is_one_command_a_line_with_the_names_shown_safely(robots):
    _, out, err = run("lint", "--output-format", "github", ROBOT_FILE, BROKEN_FILE)
    # the runner ends a line at LF or CR; ESC, C1 controls, U+2028 and bidirectional controls
    # would be written raw into the log (a colour code hides text there): shown as escapes
    assert "\r" not in out and out.endswith("\n")
    assert not UNPRINTABLE.search(out.replace("\n", ""))
    lines = out[:-1].split("\n")
    assert len(lines) == len(findings(robots))
    command = re.compile(r"::(error|warning|notice) ([^:]*)::(.*)")
    files, messages = set(), []
    for line in lines:
        match = command.fullmatch(line)
        assert match, line
        properties = dict(p.split("=", 1) for p in match[2].split(","))
        files.add(_unescape(properties["file"]))
        messages.append(_unescape(match[3]))
    assert files == {_as_github_shows(ROBOT_FILE), _as_github_shows(BROKEN_FILE)}
    assert any(f"link `arm{_as_github_shows(EXACT)}`" in m for m in messages)
    safe(err)


# --- inertia-fill ------------------------------------------------------------------------------


@pytest.mark.parametrize("options", [(), ("--diff",), ("--check",), ("--fix", "all")])
def test_fill_messages(robots, options):
    code, out, err = run("fill", *options, ROBOT_FILE, BROKEN_FILE)
    assert code == 2
    safe(err)
    assert f"error: {shown(BROKEN_FILE)}:" in err
    if "--diff" in options:
        assert f"--- a/{shown(ROBOT_FILE)}\n" in out
    if "--check" not in options:
        # the base has nothing to compute a mass from: refused, named
        assert f"link `{shown('base' + EXACT)}` not filled" in err


def test_fill_into_a_new_file_says_so_safely(robots):
    _, _, err = run("fill", "-o", f"out{EXACT}.urdf", ROBOT_FILE)
    assert shown(f"out{EXACT}.urdf") in safe(err)
    assert Path(f"out{EXACT}.urdf").is_file()


# --- inertia-kit report, mass, view, rules ----------------------------------------------------


@pytest.mark.parametrize("lumped", [(), ("--lumped",)], ids=["links", "lumped"])
@pytest.mark.parametrize("output_format", ["text", "markdown", "json"])
def test_report(robots, output_format, lumped):
    code, out, err = run("report", "--format", output_format, *lumped, ROBOT_FILE)
    assert code == 0
    safe(out), safe(err)
    if output_format == "json":
        data = json.loads(out)
        if lumped:
            names = {link for engine in data["engines"] for body in engine["bodies"]
                     for link in body["links"]}  # fmt: skip
        else:
            names = {row["link"] for row in data["links"]}
        assert {f"base{EXACT}", f"arm{EXACT}"} <= names
    else:
        assert shown(f"arm{EXACT}") in out


def test_report_of_an_unreadable_file(robots):
    code, _, err = run("report", BROKEN_FILE)
    assert code == 2 and f"error: {shown(BROKEN_FILE)}:" in safe(err)


@pytest.mark.parametrize("output_format", ["text", "json"])
def test_mass_of_a_mesh(robots, output_format):
    code, out, err = run("mass", "mesh", f"{FOLDER}/{MESH}", "--format", output_format)
    assert code == 0, err
    safe(out), safe(err)
    if output_format == "json":
        assert json.loads(out)["path"] == f"{FOLDER}/{MESH}"
    else:
        assert shown(f"{FOLDER}/{MESH}") in out


def test_view_messages(robots):
    code, _, err = run("view", ROBOT_FILE, "-o", f"page{EXACT}.html")
    assert code == 0 and f"wrote {shown(f'page{EXACT}.html')}:" in safe(err)
    code, _, err = run("view", BROKEN_FILE, "-o", "page.html")
    assert code == 2 and f"error: {shown(BROKEN_FILE)}:" in safe(err)


def test_a_folder_given_and_a_fragment_note(robots):
    fragment = Path(FOLDER) / f"parts{EXACT}.xacro"
    fragment.write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro '
                        'name="m"><link name="x"/></xacro:macro></robot>')  # fmt: skip
    shutil.rmtree(Path(BROKEN_FILE).parent / "__pycache__", ignore_errors=True)
    _, out, err = run("lint", "--output-format", "concise", ".")
    safe(out), safe(err)
    assert shown(str(fragment)) in err  # the fragment's note


# --- a file name that is no UTF-8 --------------------------------------------------------------

UNDECODABLE = os.fsdecode(b"robot\xff.urdf")  # Python's name for it: "robot\udcff.urdf"


@pytest.mark.skipif(os.name != "posix", reason="POSIX file names are bytes")
@pytest.mark.parametrize("output_format", ["full", "concise", "json", "github", "sarif", "junit",
                                           "gitlab"])  # fmt: skip
def test_a_file_name_that_is_no_utf8_in_every_format(tmp_path, monkeypatch, output_format):
    monkeypatch.chdir(tmp_path)
    write(tmp_path / UNDECODABLE, ROBOT.replace(PLANTED, ""))
    code, _, err = run("lint", "--output-format", output_format, "-o", "report", UNDECODABLE)
    assert code == 1, err
    report = Path("report").read_bytes()
    if output_format == "github":  # file= is the name's own bytes, as GitHub reads the file
        assert b",file=robot\xff.urdf," in report
    else:
        text = report.decode("utf-8")  # no other format holds anything but UTF-8
        assert "robot\\udcff.urdf" in text or "robot%FF.urdf" in text


@pytest.mark.skipif(os.name != "posix", reason="POSIX file names are bytes")
def test_a_file_name_that_is_no_utf8_in_the_review_page(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write(tmp_path / UNDECODABLE, ROBOT.replace(PLANTED, ""))
    code, _, err = run("view", UNDECODABLE, "-o", "page.html")
    assert code == 0, err
    assert '"file":"robot\\udcff.urdf"' in Path("page.html").read_text(encoding="utf-8")


def test_a_robot_read_from_stdin_is_told_by_its_name_escaped(robots):
    name = f"{FOLDER}/stdin{EXACT}.urdf"
    options = ("--output-format", "concise", "--stdin-filename", name, "-")
    code, out, err = run("lint", *options, input=ROBOT)
    assert code == 1 and safe(out).startswith(f"{shown(name)}:3:3: IN001")
    safe(err)
