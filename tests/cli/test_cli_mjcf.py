"""
The command line on MJCF models (issue 22): read by content (root ``<mujoco>``), findings at
the MJCF file and line (an included file's when the value is written there), suppressions as
XML comments, fixes written into the MJCF where the values are (a fixed point MuJoCo compiles).
"""

from __future__ import annotations

import json

import mujoco
import numpy as np
import pytest
from kit import write
from kit.in_process import run_split

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
    return run_split(command, args)


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


def test_fixes_are_written_where_the_values_are_and_a_second_run_changes_nothing(tmp_path):
    path = model(tmp_path)
    run(lint_main, "--fix", "--unsafe-fixes", "--select", "IN002,IN010", str(path))
    parts, arm = (tmp_path / "parts.xml").read_text(), path.read_text()
    # each <inertial> replaced in the file that writes it, on its own line, nothing else
    sphere = 'mass="0.523599" diaginertia="0.000523599 0.000523599 0.000523599"'
    assert PARTS.replace('mass="-1" diaginertia="1 1 1"', sphere) == parts
    assert arm.count("<inertial") == 1 and 'diaginertia="-1 1 1"' not in arm
    assert arm.replace(arm.splitlines()[8], ARM.splitlines()[8]) == ARM
    mujoco.MjModel.from_xml_path(str(path))  # compiles
    again = ("--fix", "--unsafe-fixes", "--diff", "--select", "IN002,IN010", str(path))
    _, out, _ = run(lint_main, *again)
    assert "@@" not in out


def test_fill_writes_an_inertial_into_a_body_mujoco_infers(tmp_path):
    path = write(
        tmp_path / "m.xml",
        '<mujoco>\n  <worldbody>\n    <body name="b">\n      <joint axis="0 0 1"/>\n'
        '      <geom type="box" size="0.1 0.2 0.3"/>\n    </body>\n  </worldbody>\n</mujoco>\n',
    )
    inferred = mujoco.MjModel.from_xml_path(str(path))
    run(fill_main, "--density", "1000", str(path))
    lines = path.read_text().splitlines()
    assert lines[3].startswith('      <inertial pos="0 0 0" mass="48" diaginertia="')
    written = mujoco.MjModel.from_xml_path(str(path))
    assert written.body_mass[1] == pytest.approx(inferred.body_mass[1], rel=1e-6)
    np.testing.assert_allclose(written.body_inertia[1], inferred.body_inertia[1], rtol=1e-5)
    before = path.read_bytes()
    run(fill_main, "--density", "1000", "--fix", "all", str(path))
    assert path.read_bytes() == before  # a fixed point


def test_a_fullinertia_stays_fullinertia(tmp_path):
    path = write(
        tmp_path / "m.xml",
        '<mujoco><worldbody><body name="b"><joint axis="0 0 1"/>'
        '<geom type="box" size="0.1 0.2 0.3"/>'
        '<inertial pos="0 0 0" mass="48" fullinertia="-1 1 1 0 0 0"/>'
        "</body></worldbody></mujoco>",
    )
    run(lint_main, "--fix", "--unsafe-fixes", "--select", "IN010", str(path))
    assert 'fullinertia="2.08 1.6 0.8 0 0 0"' in path.read_text()
    mujoco.MjModel.from_xml_path(str(path))


def test_an_element_that_makes_several_bodies_is_written_only_for_them_all(tmp_path):
    path = write(
        tmp_path / "m.xml",
        '<mujoco><worldbody><replicate count="2" offset="1 0 0"><body name="b">'
        '<joint axis="0 0 1"/><geom type="box" size="0.1 0.2 0.3"/>'
        '<inertial pos="0 0 0" mass="-1" diaginertia="1 1 1"/>'
        "</body></replicate></worldbody></mujoco>",
    )
    before = path.read_bytes()
    run(lint_main, "--fix", "--unsafe-fixes", "--select", "IN002", str(path))
    # both copies want the same values: one edit writes them
    assert path.read_bytes() != before and 'mass="48"' in path.read_text()


def test_inertiafromgeom_true_gets_no_inertial_written(tmp_path):
    path = write(
        tmp_path / "m.xml",
        '<mujoco><compiler inertiafromgeom="true"/><worldbody><body name="b">'
        '<joint axis="0 0 1"/><geom type="box" size="0.1 0.2 0.3"/>'
        '<inertial pos="0 0 0" mass="-1" diaginertia="1 1 1"/></body></worldbody></mujoco>',
    )
    before = path.read_bytes()
    run(lint_main, "--fix", "--unsafe-fixes", "--select", "IN002", str(path))
    assert path.read_bytes() == before


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


def test_report_gives_an_inferred_body_what_mujoco_compiles(tmp_path):
    path = write(
        tmp_path / "m.xml",
        '<mujoco><worldbody><body name="b"><joint axis="0 0 1"/>'
        '<geom type="box" size="0.1 0.2 0.3" density="2700"/>'
        '<geom type="sphere" size="0.1" pos="0 0 0.3"/></body></worldbody></mujoco>',
    )
    code, out, _ = run(main, "report", "--format", "json", str(path))
    (row,) = [row for row in json.loads(out)["links"] if row["link"] == "b"]
    compiled = mujoco.MjModel.from_xml_path(str(path))
    assert code == 0 and row["inertial"] == "inferred"
    assert row["mass"] == pytest.approx(compiled.body_mass[1], rel=1e-12)
    np.testing.assert_allclose(
        row["principal_moments"], sorted(compiled.body_inertia[1]), rtol=1e-9
    )
    code, out, _ = run(main, "report", str(path))
    assert f"{compiled.body_mass[1]:.6g} inferred" in out


def test_an_mjcf_model_given_is_linted_as_itself_without_a_repository_scan(tmp_path, monkeypatch):
    # a model has no <link>: it must not pass for a URDF placeholder robots may include, whose
    # includers are looked for over the whole repository (here, every file of tmp_path)
    from inertia_kit.lint import fragments

    def scanned(*_args, **_kwargs):
        raise AssertionError("the repository was scanned for robots including an MJCF model")

    monkeypatch.setattr(fragments, "include_graph", scanned)
    path = model(tmp_path)
    code, out, _ = run(lint_main, "--select", "IN002", str(path))
    assert code == 1 and "parts.xml:5:7: IN002" in out
