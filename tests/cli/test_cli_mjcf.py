"""
The command line on MJCF models (issue 22): read by content (root ``<mujoco>``), findings at
the MJCF file and line (an included file's when the value is written there), suppressions as
XML comments, and no fix written into the file until the MJCF writer exists.
"""

from __future__ import annotations

import json

from click.testing import CliRunner
from kit import write

from inertia_kit.cli import fill_main, lint_main, main

ARM = """<mujoco model="arm">
  <include file="parts.xml"/>
  <worldbody>
    <body name="base">
      <geom type="box" size="0.1 0.1 0.1"/>
      <body name="arm" pos="0 0 0.2">
        <joint name="shoulder" axis="0 0 1"/>
        <geom type="cylinder" size="0.05 0.2"/>
        <inertial pos="0 0 0" mass="2" diaginertia="-1 1 1"/>
      </body>
    </body>
  </worldbody>
</mujoco>
"""
PARTS = """<mujoco>
  <worldbody>
    <body name="tool" pos="1 0 0">
      <joint type="slide"/>
      <inertial pos="0 0 0" mass="-1" diaginertia="1 1 1"/>
      <geom type="sphere" size="0.05"/>
    </body>
  </worldbody>
</mujoco>
"""


def run(command, *args: str) -> tuple[int, str, str]:
    try:
        runner = CliRunner(mix_stderr=False)  # click < 8.2
    except TypeError:
        runner = CliRunner()
    result = runner.invoke(command, list(args), catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


def model(tmp_path):
    write(tmp_path / "parts.xml", PARTS)
    return write(tmp_path / "arm.xml", ARM)


def test_lint_reads_an_mjcf_model_and_locates_findings_in_the_file_that_writes_them(tmp_path):
    path = model(tmp_path)
    code, out, _ = run(lint_main, "--output-format", "json", "--select", "IN002,IN010", str(path))
    found = {(f["code"], f["file"].split("/")[-1], f["line"]) for f in json.loads(out)}
    assert code == 1
    assert found == {("IN010", "arm.xml", 9), ("IN002", "parts.xml", 5)}
    messages = [f["message"] for f in json.loads(out)]
    assert all(m.startswith("body `") for m in messages), messages


def test_a_folder_lints_its_mjcf_models_and_not_its_other_xml(tmp_path):
    model(tmp_path)
    write(tmp_path / "package.xml", "<package format='3'><name>arm</name></package>")
    code, out, _ = run(lint_main, "--output-format", "json", "--select", "IN002", str(tmp_path))
    files = sorted({f["file"].split("/")[-1] for f in json.loads(out)})
    # parts.xml is a model of its own too (a body welded to the world): linted twice is right,
    # each run for its own file
    assert code == 1 and files == ["parts.xml"]


def test_fixes_leave_an_mjcf_file_untouched_and_say_so(tmp_path):
    path = model(tmp_path)
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}
    code, out, err = run(lint_main, "--fix", "--unsafe-fixes", str(path))
    assert code == 1
    code, out, err = run(fill_main, "--fix", "all", str(path))
    assert "fixes are not written yet: nothing changed" in err + out
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == before


def test_a_suppression_comment_in_mjcf_silences_its_finding(tmp_path):
    path = model(tmp_path)
    run(lint_main, "--add-noqa", "--select", "IN010", str(path))
    text = path.read_text()
    assert "<!-- inertia-lint: ignore[IN010] -->" in text
    code, out, _ = run(lint_main, "--output-format", "json", "--select", "IN010", str(path))
    assert code == 0 and json.loads(out) == []


def test_report_and_view_read_an_mjcf_model(tmp_path):
    path = model(tmp_path)
    code, out, _ = run(main, "report", "--format", "json", str(path))
    assert code == 0
    names = [row["link"] for row in json.loads(out)["links"]]
    # MuJoCo's body order (the include stands before <worldbody>; the order is checked against
    # MuJoCo's on Menagerie in tests/description/mjcf/test_menagerie_reading.py)
    assert names == ["world", "tool", "base", "arm"]
    code, _, _ = run(main, "view", str(path), "-o", str(tmp_path / "page.html"))
    assert code == 0 and (tmp_path / "page.html").stat().st_size > 0
