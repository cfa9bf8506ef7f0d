"""
Writes never follow a symbolic link planted in the tree, unless asked (``--follow-symlinks``):

- a named output file (``inertia-lint -o``, also for stdin; ``inertia-fill -o``; ``inertia-kit
  view -o`` and ``--png``) that is a link, or whose folder on the way is one, is refused: one
  line, exit 2, nothing written (the attack: ``results.sarif -> ../ci/deploy.sh`` in a pull
  request, CI writing its SARIF report there);
- a robot file that is a link out of its repository is not edited by ``inertia-fill``,
  ``inertia-lint --fix`` or ``--add-noqa``, given by name or found by a folder walk.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

import pytest
from click.testing import CliRunner
from kit import write
from kit.concurrency import PROJECTS

from inertia_kit.cli import main as umbrella

DEPLOY = "#!/bin/sh\necho deploying\n"


def planted(tmp_path: Path, monkeypatch) -> tuple[Path, Path]:
    """A checkout (the working folder) whose ``results.sarif`` links to ``../ci/deploy.sh``."""
    deploy = write(tmp_path / "ci" / "deploy.sh", DEPLOY)
    os.chmod(deploy, 0o755)
    repo = PROJECTS["urdf"].copy(tmp_path / "repo")
    (repo / "results.sarif").symlink_to("../ci/deploy.sh")
    monkeypatch.chdir(repo)
    return repo, deploy


def run(*args: str, input: bytes | None = None):
    return CliRunner().invoke(umbrella, list(args), input=input)


WRITING_COMMANDS = {
    "lint -o": ("lint", "--output-format", "sarif", "-o", "{out}", "."),
    "lint --output-file, stdin": (
        "lint", "--output-format", "sarif", "--output-file", "{out}", "--stdin-filename",
        "urdf/race.urdf", "-",
    ),
    "fill -o": ("fill", "-o", "{out}", "urdf/race.urdf"),
    "view -o": ("view", "urdf/race.urdf", "-o", "{out}"),
    "view --png": ("view", "urdf/race.urdf", "-o", "page.html", "--png", "{out}"),
}  # fmt: skip
OPTION = {"lint -o": "--output-file", "lint --output-file, stdin": "--output-file"}


@pytest.mark.parametrize("command", list(WRITING_COMMANDS))
def test_an_output_that_is_a_planted_link_is_refused(tmp_path: Path, monkeypatch, command):
    """The reproducer: the SARIF report replaced deploy.sh and kept its execute bit."""
    repo, deploy = planted(tmp_path, monkeypatch)
    args = [a.format(out="results.sarif") for a in WRITING_COMMANDS[command]]
    stdin = (repo / "urdf" / "race.urdf").read_bytes() if "-" in args else None

    result = run(*args, input=stdin)

    assert result.exit_code == 2, result.output
    option = OPTION.get(command, "--png" if "png" in command else "-o")
    assert result.stderr.splitlines() == [
        f"error: {option}: results.sarif: is a symbolic link to ../ci/deploy.sh: not written; "
        "--follow-symlinks writes through it"
    ]
    assert deploy.read_text() == DEPLOY
    assert (repo / "results.sarif").is_symlink()
    assert not (repo / "page.html").exists()  # view refuses before it writes anything


@pytest.mark.parametrize("command", list(WRITING_COMMANDS))
def test_an_output_through_a_planted_folder_link_is_refused(tmp_path: Path, monkeypatch, command):
    repo, _ = planted(tmp_path, monkeypatch)
    (tmp_path / "elsewhere").mkdir()
    (repo / "reports").symlink_to(tmp_path / "elsewhere")
    args = [a.format(out="reports/out.sarif") for a in WRITING_COMMANDS[command]]
    stdin = (repo / "urdf" / "race.urdf").read_bytes() if "-" in args else None

    result = run(*args, input=stdin)

    assert result.exit_code == 2, result.output
    assert result.stderr.splitlines()[0].endswith(
        f"reports/out.sarif: passes through reports, a symbolic link to {tmp_path / 'elsewhere'}"
        ": not written; --follow-symlinks writes through it"
    )
    assert list((tmp_path / "elsewhere").iterdir()) == []


def test_follow_symlinks_writes_the_report_through_the_link(tmp_path: Path, monkeypatch):
    repo, deploy = planted(tmp_path, monkeypatch)

    result = run(
        "lint", "--output-format", "sarif", "-o", "results.sarif", "--follow-symlinks", "."
    )

    assert result.exit_code == 1, result.output  # the robot's findings
    assert deploy.read_text().startswith("{")  # what the user asked for
    assert (repo / "results.sarif").is_symlink()


def test_an_output_outside_the_working_folder_checks_only_the_file(tmp_path: Path, monkeypatch):
    """Folders above or beside the working folder are the user's (``/tmp`` is a link on macOS):
    an absolute output path there is written through them."""
    PROJECTS["urdf"].copy(tmp_path / "repo")
    (tmp_path / "real-reports").mkdir()
    (tmp_path / "reports").symlink_to("real-reports")
    monkeypatch.chdir(tmp_path / "repo")
    out = tmp_path / "reports" / "out.json"

    result = run("lint", "--output-format", "json", "-o", str(out), ".")

    assert result.exit_code == 1, result.output
    assert (tmp_path / "real-reports" / "out.json").read_text().startswith("[")


# --- robot files that link out of their repository ---------------------------------------------

ROBOT_WRITERS = {
    "fill": ("fill",),
    "fill --fix all": ("fill", "--fix", "all"),
    "lint --fix": ("lint", "--fix"),
    "lint --fix --unsafe-fixes": ("lint", "--fix", "--unsafe-fixes"),
    "lint --add-noqa": ("lint", "--add-noqa"),
}


def linked_out(tmp_path: Path, monkeypatch) -> tuple[Path, Path, bytes]:
    """A repository whose ``urdf/race.urdf`` links to a robot in another folder."""
    other = PROJECTS["urdf"].copy(tmp_path / "other")
    target = other / "urdf" / "race.urdf"
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    (repo / "urdf").mkdir()
    link = repo / "urdf" / "race.urdf"
    link.symlink_to(os.path.relpath(target, link.parent))
    monkeypatch.chdir(repo)
    return link, target, target.read_bytes()


@pytest.mark.parametrize("given", ["file", "folder"])
@pytest.mark.parametrize("writer", list(ROBOT_WRITERS))
def test_a_robot_linking_out_of_the_repository_is_not_written(
    tmp_path: Path, monkeypatch, writer: str, given: str
):
    link, target, before = linked_out(tmp_path, monkeypatch)

    result = run(*ROBOT_WRITERS[writer], "urdf/race.urdf" if given == "file" else ".")

    assert result.exit_code == 2, result.output
    assert (
        f"error: urdf/race.urdf: is a symbolic link to {target}, outside its repository "
        f"{tmp_path / 'repo'}, the git top level: not written; --follow-symlinks writes through it"
    ) in result.stderr.splitlines()
    assert target.read_bytes() == before
    assert link.is_symlink()


@pytest.mark.parametrize("writer", list(ROBOT_WRITERS))
def test_follow_symlinks_writes_the_robot_through_the_link(tmp_path, monkeypatch, writer):
    link, target, before = linked_out(tmp_path, monkeypatch)

    result = run(*ROBOT_WRITERS[writer], "--follow-symlinks", "urdf/race.urdf")

    assert result.exit_code in (0, 1), result.output
    assert target.read_bytes() != before
    assert link.is_symlink()


def test_a_link_within_the_repository_is_written_through(tmp_path: Path, monkeypatch):
    """The link stays a link; what it points to is edited, as before."""
    repo = PROJECTS["urdf"].copy(tmp_path / "repo")
    real = repo / "urdf" / "race.urdf"
    before = real.read_bytes()
    (repo / "robot.urdf").symlink_to("urdf/race.urdf")
    monkeypatch.chdir(repo)

    result = run("lint", "--fix", "robot.urdf")

    assert result.exit_code == 1, result.output
    assert real.read_bytes() != before
    assert (repo / "robot.urdf").is_symlink()
    assert stat.S_ISREG(os.lstat(real).st_mode)
