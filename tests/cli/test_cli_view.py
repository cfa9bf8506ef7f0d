"""
``inertia-kit view``: the page is written whatever the findings (exit 0); bad input, usage and
a missing renderer for --png exit 2, saying why. A stand-in scene builder feeds these tests:
the real one (inertia_kit.view.scene) is tested on the examples in test_cli_view_examples.py.
"""

from __future__ import annotations

import sys
import types

import pytest
from click.testing import CliRunner
from kit.browser import open_page
from kit.scenes import two_box_scene

from inertia_kit.cli import main
from inertia_kit.errors import InputError
from inertia_kit.view.screenshot import find_chromium


@pytest.fixture
def calls(monkeypatch):
    """The keyword arguments of each build_scene call; an "unreadable" robot raises InputError."""
    seen: list[dict] = []

    def build_scene(path, **options):
        seen.append(dict(options, path=path))
        if "unreadable" in str(path):
            raise InputError("not well-formed (invalid token)", path, 3, 7)
        return two_box_scene()

    module = types.ModuleType("inertia_kit.view.scene")
    module.build_scene = build_scene
    monkeypatch.setitem(sys.modules, "inertia_kit.view.scene", module)
    return seen


def view(*args: str):
    return CliRunner().invoke(main, ["view", *args])


def test_writes_the_page_and_exits_0_despite_an_error_finding(calls, tmp_path):
    out = tmp_path / "review.html"
    result = view("robot.urdf", "-o", str(out))
    assert result.exit_code == 0, result.output
    text = out.read_text(encoding="utf-8")
    assert text.startswith("<!DOCTYPE html>") and '"worst":"error"' in text
    assert f"wrote {out}: 2 links, 2 findings" in result.output


def test_passes_the_lint_options_to_the_scene(calls, tmp_path):
    result = view(
        "robot.urdf.xacro", "-o", str(tmp_path / "r.html"), "--package-path", str(tmp_path),
        "--xacro-arg", "arm:=left", "--xacro-limit", "timeout=5", "--engine", "mujoco",
        "--select", "IN01,IN020", "--ignore", "IN015", "--config", "cfg.toml",
        "--triangle-budget", "1000",
    )  # fmt: skip
    assert result.exit_code == 0, result.output
    (call,) = calls
    assert call["path"] == "robot.urdf.xacro"
    assert call["package_paths"] == (str(tmp_path),)
    assert call["xacro_args"] == {"arm": "left"}
    assert call["xacro_limits"] == {"timeout": 5.0}
    assert call["engines"] == ("mujoco",)
    assert call["select"] == ("IN01", "IN020") and call["ignore"] == ("IN015",)
    assert call["config"] == "cfg.toml" and call["triangle_budget"] == 1000


def test_unreadable_input_exits_2_naming_file_and_line(calls, tmp_path):
    out = tmp_path / "review.html"
    result = view("unreadable.urdf", "-o", str(out))
    assert result.exit_code == 2
    assert "error: unreadable.urdf:3:7: not well-formed" in result.output
    assert "Traceback" not in result.output and not out.exists()


@pytest.mark.parametrize(
    ("args", "said"),
    [
        ((), "Missing option '-o'"),
        (("-o", "r.html", "--png", "r.png", "--png-size", "big"), "--png-size takes WIDTHxHEIGHT"),
        (("-o", "r.html", "--triangle-budget", "0"), "--triangle-budget"),
        (("-o", "r.html", "--xacro-arg", "oops"), "NAME:=VALUE"),
    ],
)
def test_usage_errors_exit_2(calls, tmp_path, monkeypatch, args, said):
    monkeypatch.chdir(tmp_path)
    result = view("robot.urdf", *args)
    assert result.exit_code == 2
    assert said in result.output


def test_no_renderer_for_png_exits_2_and_still_writes_the_page(calls, tmp_path, monkeypatch):
    monkeypatch.setenv("INERTIA_KIT_CHROMIUM", str(tmp_path / "no-chromium"))
    out, png = tmp_path / "review.html", tmp_path / "review.png"
    result = view("robot.urdf", "-o", str(out), "--png", str(png))
    assert result.exit_code == 2
    assert "error: --png:" in result.output and "apt-get install chromium" in result.output
    assert f"the page {out} is written" in result.output
    assert out.is_file() and not png.exists()


def test_png_of_the_asked_size(calls, tmp_path):
    if find_chromium() is None:
        open_page(tmp_path / "none.html")  # skips, saying why
    out, png = tmp_path / "review.html", tmp_path / "review.png"
    result = view("robot.urdf", "-o", str(out), "--png", str(png), "--png-size", "640x400")
    assert result.exit_code == 0, result.output
    from PIL import Image

    with Image.open(png) as image:
        assert image.size == (640, 400)


def test_help_says_findings_do_not_fail_it():
    result = view("--help")
    assert result.exit_code == 0
    assert "findings do not fail it" in " ".join(result.output.split())


@pytest.mark.parametrize(
    ("links", "said"),
    [(1, "1 link, 1 finding,"), (2, "2 links, 2 findings,")],
)
def test_the_summary_counts_in_words_that_agree(tmp_path, links, said):
    """Once "1 links, 1 findings": each link here has one finding (a zero mass)."""
    body = (
        '<inertial><mass value="0"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>'
        '</inertial><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
    )
    parts = [f'<link name="l{i}">{body}</link>' for i in range(links)]
    if links == 2:
        parts.append('<joint name="j" type="fixed"><parent link="l0"/><child link="l1"/></joint>')
    path = tmp_path / "r.urdf"
    path.write_text(f'<robot name="r">{"".join(parts)}</robot>')
    result = CliRunner().invoke(
        main, ["view", "--select", "IN002", str(path), "-o", str(tmp_path / "r.html")]
    )
    assert result.exit_code == 0, result.output
    assert f"wrote {tmp_path / 'r.html'}: {said}" in result.output
