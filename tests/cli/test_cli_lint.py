"""
`inertia-lint` (and `inertia-kit lint`): exit codes, selection, --fail-on, --exit-zero,
--statistics, folders and fragments, unreadable input, configuration errors, --explain.

Most tests run stub rules (an error, a warning and an info on the declared mass), so that they
do not depend on the rules still being written.
"""

from __future__ import annotations

import os
import subprocess
import sys
import types
from pathlib import Path

import pytest
from console_scripts import console_script
from kit import REPO
from kit.in_process import lint_in_process, run_split
from kit.urdf import inertial, link, robot_lines

from inertia_kit.cli import lint_main, main
from inertia_kit.lint import catalog
from inertia_kit.lint.findings import Severity

ROOT = REPO
IN002_DOC = ROOT / "rules" / "IN002-non-positive-mass.md"


def _rule(code, name, severity, test):
    rule = types.ModuleType(f"inertia_kit.lint.rules.{code.lower()}_{name.replace('-', '_')}")
    rule.CODE, rule.NAME, rule.SEVERITY, rule.SCOPE = code, name, severity, "link"
    rule.SUMMARY, rule.OPTIONS, rule.DEFAULTS = name, {}, {}

    def check(link, ctx):
        inertial = link.link.inertial
        mass = None if inertial is None else inertial.mass
        if isinstance(mass, float) and test(mass):
            yield ctx.finding(f"{link.name}: {mass:g} kg", inertial.mass_source, link=link.name)

    rule.check = check
    return rule


STUBS = (
    _rule("IN097", "stub-error", Severity.ERROR, lambda m: m <= 0),
    _rule("IN098", "stub-warning", Severity.WARNING, lambda m: m > 10),
    _rule("IN099", "stub-info", Severity.INFO, lambda m: 0 < m < 0.01),
)


def urdf(*masses: float) -> str:
    """Links `l0`, `l1`, ... of these masses, one a line, each with a unit tensor."""
    return robot_lines(*(f"  {link(f'l{i}', inertial(m, 1))}\n" for i, m in enumerate(masses)))


FRAGMENT = (
    '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
    '  <xacro:macro name="m" params="">\n    <link name="x"/>\n  </xacro:macro>\n</robot>\n'
)


@pytest.fixture
def here(tmp_path, monkeypatch):
    """An empty current folder, stub rules as the registry, no colour."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(catalog, "RULES", STUBS)
    lint_in_process(monkeypatch)
    monkeypatch.delenv("FORCE_COLOR", raising=False)
    return tmp_path


def write(name: str, text: str) -> str:
    Path(name).parent.mkdir(parents=True, exist_ok=True)
    Path(name).write_text(text)
    return name


def run(*args: str, command=lint_main) -> tuple[int, str, str]:
    return run_split(command, args)


# --- exit codes -------------------------------------------------------------------------------


def test_clean_file_exits_0(here):
    write("ok.urdf", urdf(1.0))
    assert run("ok.urdf") == (0, "", "No findings in 1 file.\n")


def test_findings_exit_1(here):
    write("bad.urdf", urdf(0.0))
    assert run("--output-format", "concise", "bad.urdf") == (
        1,
        "bad.urdf:2:29: IN097 l0: 0 kg\n",
        "Found 1 error in 1 file.\n",
    )


@pytest.mark.parametrize(
    ("fail_on", "masses", "code"),
    [
        (None, (20.0,), 1),  # a warning, default fail-on warning
        (None, (0.001,), 0),  # an info only
        ("error", (20.0,), 0),
        ("error", (0.0,), 1),
        ("info", (0.001,), 1),
        ("warning", (0.001, 20.0), 1),
    ],
)
def test_fail_on(here, fail_on, masses, code):
    write("r.urdf", urdf(*masses))
    args = ("r.urdf",) if fail_on is None else ("--fail-on", fail_on, "r.urdf")
    assert run("--output-format", "concise", *args)[0] == code


def test_fail_on_from_the_configuration_and_the_command_line_over_it(here):
    write("r.urdf", urdf(20.0))
    write("pyproject.toml", '[tool.inertia-kit]\nfail-on = "error"\n')
    assert run("r.urdf")[0] == 0
    assert run("--fail-on", "warning", "r.urdf")[0] == 1


def test_exit_zero_keeps_2_for_unreadable_input(here):
    write("bad.urdf", urdf(0.0))
    assert run("--exit-zero", "--output-format", "concise", "bad.urdf")[0] == 0
    assert run("--exit-zero", "bad.urdf", "missing.urdf")[0] == 2


def test_unreadable_file_among_good_ones_still_lints_them_and_exits_2(here):
    write("a.urdf", urdf(0.0))
    write("broken.urdf", "")
    write("c.urdf", urdf(20.0))
    assert run("--output-format", "concise", "a.urdf", "broken.urdf", "missing.urdf", "c.urdf") == (
        2,
        "a.urdf:2:29: IN097 l0: 0 kg\nc.urdf:2:29: IN098 l0: 20 kg\n",
        "error: broken.urdf: empty file: not a robot description\n"
        "error: missing.urdf: no such file\n"
        "Found 1 error, 1 warning in 2 files; 2 files could not be read.\n",
    )


def test_folders_fragments_and_hidden_folders(here):
    write("robots/b.urdf", urdf(0.0))
    write("robots/a/robot.urdf.xacro", urdf(20.0).replace("<robot", '<robot xmlns:xacro="x"'))
    write("robots/a/macros.xacro", FRAGMENT)
    write("robots/.git/ignored.urdf", urdf(0.0))
    write("robots/notes.txt", "not a robot")
    assert run("--output-format", "concise", "robots", "robots/b.urdf") == (
        1,
        "robots/a/robot.urdf.xacro:2:29: IN098 l0: 20 kg\nrobots/b.urdf:2:29: IN097 l0: 0 kg\n",
        # robots/.git makes robots/ the repository the fragment's robots are looked for in
        "note: robots/a/macros.xacro: a xacro fragment no robot in robots (the git top level) "
        "includes; nothing to lint\n"
        "Found 1 error, 1 warning in 2 files.\n",
    )


def test_a_folder_without_robots(here):
    Path("empty").mkdir()
    assert run("empty") == (
        0,
        "",
        "warning: no robot descriptions (*.urdf, *.xacro) in empty\nNo findings in 0 files.\n",
    )


# --- selection --------------------------------------------------------------------------------


def test_select_and_ignore(here):
    write("r.urdf", urdf(0.0, 20.0, 0.001))

    def codes(*args: str) -> list[str]:
        out = run("--output-format", "concise", "--fail-on", "info", *args, "r.urdf")[1]
        return [line.split()[1] for line in out.splitlines()]

    assert codes() == ["IN097", "IN098", "IN099"]
    assert codes("--select", "IN098") == ["IN098"]
    assert codes("--select", "IN097,stub-info") == ["IN097", "IN099"]
    assert codes("--select", "IN097", "--select", "in099") == ["IN097", "IN099"]
    assert codes("--ignore", "IN098") == ["IN097", "IN099"]
    assert codes("--select", "IN09", "--ignore", "stub-error,IN099") == ["IN098"]
    write("pyproject.toml", '[tool.inertia-kit]\nignore = ["IN097"]\n')
    assert codes() == ["IN098", "IN099"]
    assert codes("--select", "IN097") == ["IN097"]  # --select replaces the configured lists


def test_unknown_selector_is_a_usage_error(here):
    write("r.urdf", urdf(1.0))
    assert run("--select", "IN9x", "r.urdf") == (
        2,
        "",
        "error: --select: `IN9x` is not a rule code, code prefix or rule name\n",
    )


def test_statistics(here):
    write("r.urdf", urdf(0.0, -1.0, 20.0))
    assert run("--statistics", "r.urdf") == (
        1,
        "2  IN097  stub-error\n1  IN098  stub-warning\n",
        "Found 2 errors, 1 warning in 1 file.\n",
    )


# --- configuration and usage errors -----------------------------------------------------------


def test_bad_configuration_exits_2_before_linting(here):
    write("r.urdf", urdf(0.0))
    write("pyproject.toml", '[tool.inertia-kit]\nselect = ["IN097"]\nunknown = 1\n')
    code, stdout, stderr = run("r.urdf")
    assert (code, stdout) == (2, "")
    assert stderr.startswith(f"error: {here / 'pyproject.toml'}: `tool.inertia-kit.unknown`: ")


def test_explicit_config(here):
    write("r.urdf", urdf(0.0, 20.0))
    write("pyproject.toml", '[tool.inertia-kit]\nselect = ["IN097"]\n')
    write("ci/lint.toml", 'select = ["IN098"]\n')
    assert run("--output-format", "concise", "r.urdf")[1] == "r.urdf:2:29: IN097 l0: 0 kg\n"
    assert run("--output-format", "concise", "--config", "ci/lint.toml", "r.urdf")[1] == (
        "r.urdf:3:29: IN098 l1: 20 kg\n"
    )
    assert run("--config", "ci/missing.toml", "r.urdf") == (
        2,
        "",
        "error: ci/missing.toml: no such configuration file\n",
    )


@pytest.mark.parametrize(
    ("args", "message"),
    [
        ((), "error: give files or folders to lint (or --explain CODE)\n"),
        (
            ("--xacro-arg", "oops", "r.urdf"),
            "error: --xacro-arg takes NAME:=VALUE, got 'oops'\n",
        ),
    ],
)
def test_usage_errors_exit_2(here, args, message):
    write("r.urdf", urdf(1.0))
    assert run(*args) == (2, "", message)


def test_click_usage_errors_exit_2(here):
    code, stdout, stderr = run("--output-format", "xml", "r.urdf")
    assert (code, stdout) == (2, "")
    assert "Invalid value for '--output-format'" in stderr


def test_xacro_args_and_package_paths_reach_the_loader(here):
    write(
        "r.urdf.xacro",
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:arg name="m" default="1"/>\n'
        '  <xacro:include filename="$(find parts)/urdf/p.xacro"/>\n'
        '  <link name="a"><inertial><mass value="$(arg m)"/>'
        '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>\n'
        "</robot>\n",
    )
    write("deps/parts/package.xml", "<package><name>parts</name></package>")
    write("deps/parts/urdf/p.xacro", '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>')
    args = ("--output-format", "concise", "--package-path", "deps", "r.urdf.xacro")
    assert run(*args)[0] == 0
    assert run("--xacro-arg", "m:=0", *args)[1] == "r.urdf.xacro:4:28: IN097 a: 0 kg\n"
    code, _, stderr = run("r.urdf.xacro")  # parts not found
    assert code == 2 and "parts" in stderr


def test_suppression_notes_reach_stderr_once(here):
    write("p.xacro", FRAGMENT.replace("<link", "<!-- inertia-lint: ignore[IN5] --><link"))
    top = (
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="p.xacro"/>\n  <xacro:m/>\n</robot>\n'
    )
    write("a.xacro", top)
    write("b.xacro", top)
    assert run("a.xacro", "b.xacro", "p.xacro") == (
        0,
        "",
        "warning: p.xacro:3: inertia-lint comment ignored: `IN5` is not a rule code, code prefix "
        "or rule name\n"
        "note: p.xacro: linted through the robots that include it: a.xacro, b.xacro\n"
        "No findings in 2 files.\n",
    )


# --- the same command twice, the real scripts -------------------------------------------------


def test_inertia_kit_lint_is_the_same_command(here):
    write("r.urdf", urdf(0.0, 20.0))
    assert run("r.urdf", command=main) != run("r.urdf")  # main needs the subcommand name
    assert run("lint", "r.urdf", command=main) == run("r.urdf")


def test_console_script(tmp_path):
    bad = tmp_path / "bad.urdf"
    bad.write_text(urdf(0.0))
    done = subprocess.run(
        [
            console_script("inertia-lint"),
            "--select",
            "IN002",
            "--output-format",
            "concise",
            str(bad),
        ],
        capture_output=True,
        text=True,
        env={**os.environ, "NO_COLOR": "1"},
    )
    assert done.returncode == 1, done.stderr
    assert done.stdout == f"{bad}:2:29: IN002 link `l0`: mass = 0 kg is not positive\n"
    assert done.stderr == "Found 1 error in 1 file.\n"


# --- --explain --------------------------------------------------------------------------------


@pytest.mark.parametrize("selector", ["IN002", "in002", "non-positive-mass"])
def test_explain_prints_the_document(selector):
    assert run("--explain", selector) == (0, IN002_DOC.read_text(encoding="utf-8"), "")


def test_explain_unknown_or_undocumented(monkeypatch, tmp_path):
    assert run("--explain", "IN0") == (
        2,
        "",
        "error: --explain: `IN0` is not a rule code or name (did you mean `IN000`?)\n",
    )
    assert run("--explain", "non-positive-mas") == (
        2,
        "",
        "error: --explain: `non-positive-mas` is not a rule code or name (did you mean "
        "`non-positive-mass`?)\n",
    )
    from inertia_kit.lint import documents

    monkeypatch.setattr(documents, "documents_folder", lambda: tmp_path)  # no documents at all
    assert run("--explain", "IN002") == (
        2,
        "",
        "error: --explain: IN002 (non-positive-mass) has no document in this version\n",
    )


def test_explain_reads_the_package_data_folder():
    """In the source tree `inertia_kit/rule_docs` is a link to `rules/`, the folder a wheel
    fills with the documents; --explain reads whatever that folder holds."""
    from inertia_kit.lint.documents import documents_folder, rule_documents

    folder = documents_folder()
    assert folder == ROOT / "inertia_kit" / "rule_docs"
    assert folder.resolve() == (ROOT / "rules").resolve()
    assert rule_documents()["IN002"] == folder / IN002_DOC.name


def test_start_up_imports_no_numpy():
    """--explain, --help and usage errors stay fast: numpy and the rules load only to lint."""
    code = (
        "import sys; from inertia_kit.cli import lint_main;"
        "lint_main(['--explain', 'IN002'], standalone_mode=False);"
        "heavy = ('numpy', 'lxml', 'inertia_kit.analysis.links');"
        "print(sorted(m for m in heavy if m in sys.modules),"
        " file=sys.stderr)"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert done.returncode == 0, done.stderr
    assert done.stderr.strip() == "[]"
