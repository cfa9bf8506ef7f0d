"""
How `inertia-fill` writes: through symbolic links within the repository (the file a link points
to is edited, the link kept; a link that leads nowhere, out of the package, or out of the
repository without --follow-symlinks is refused with a message), and the temporary files a
killed run leaves behind (removed by the next run, never one a live run is writing).
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from click.testing import CliRunner
from console_scripts import console_script
from kit import write
from kit.urdf import joint, moving

from inertia_kit.cli.fill import fill_command

BOX = '<collision><geometry><box size="0.1 0.1 0.4"/></geometry></collision>'
ROBOT = moving(BOX, "")
XACRO = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
PACKAGE = "<package><name>{}</name></package>"


def filled(tmp_path: Path, text: str = ROBOT) -> bytes:
    """What inertia-fill makes of ``text`` in a plain file (the reference for a linked one)."""
    plain = write(tmp_path / "plain" / "robot.urdf", text)
    assert CliRunner().invoke(fill_command, [str(plain)]).exit_code == 1
    return plain.read_bytes()


def links_of(folder: Path) -> dict[str, str]:
    return {str(p.relative_to(folder)): os.readlink(p) for p in folder.rglob("*") if p.is_symlink()}


def temporaries(folder: Path) -> list[Path]:
    return sorted(folder.rglob(".*.tmp"))


# --- symbolic links ------------------------------------------------------------------------------


def test_symlink_install_layout_edits_the_source_and_keeps_the_links(tmp_path: Path):
    """colcon's --symlink-install: install/share/pkg/urdf/robot.urdf links to the source file;
    filling through it edits the source, as an editor would, and the link stays a link."""
    source = tmp_path / "ws" / "src" / "pkg"
    write(source / "package.xml", PACKAGE.format("pkg"))
    real = write(source / "urdf" / "robot.urdf", ROBOT)
    os.chmod(real, 0o640)
    installed = tmp_path / "ws" / "install" / "share" / "pkg"
    (installed / "urdf").mkdir(parents=True)
    write(tmp_path / "ws" / "install" / ".colcon_install_layout", "merged")  # colcon writes it
    (installed / "package.xml").symlink_to(source / "package.xml")
    (installed / "urdf" / "robot.urdf").symlink_to(real)
    links = links_of(tmp_path / "ws")

    result = CliRunner().invoke(fill_command, [str(installed / "urdf" / "robot.urdf")])

    assert result.exit_code == 1, result.stderr
    assert "Filled 1 link" in result.stderr
    assert f"is a symbolic link: the file it points to, {real}, was written" in result.stderr
    assert real.read_bytes() == filled(tmp_path)
    assert os.stat(real).st_mode & 0o777 == 0o640
    assert links_of(tmp_path / "ws") == links
    assert temporaries(tmp_path / "ws") == []


@pytest.mark.parametrize("follow", [False, True])
def test_a_link_out_of_its_repository_is_written_only_when_asked(tmp_path: Path, follow):
    """A link a pull request could plant: to a file outside the repository it stands in (an
    install space without colcon's marker is no workspace). Refused, nothing written, unless
    --follow-symlinks."""
    real = write(tmp_path / "elsewhere" / "robot.urdf", ROBOT)
    (tmp_path / "repo" / ".git").mkdir(parents=True)
    link = tmp_path / "repo" / "install" / "robot.urdf"
    link.parent.mkdir()
    link.symlink_to(real)

    result = CliRunner().invoke(fill_command, [str(link), *(["--follow-symlinks"] * follow)])

    if follow:
        assert result.exit_code == 1, result.stderr
        assert real.read_bytes() == filled(tmp_path)
    else:
        assert result.exit_code == 2
        assert result.stderr.splitlines()[0] == (
            f"error: {link}: is a symbolic link to {real}, outside its repository "
            f"{tmp_path / 'repo'}, the git top level: not written; --follow-symlinks writes "
            "through it"
        )
        assert real.read_text() == ROBOT
    assert link.is_symlink()


def test_a_chain_of_relative_links_is_followed(tmp_path: Path):
    (tmp_path / ".git").mkdir()  # the repository both ends of the chain are in
    real = write(tmp_path / "src" / "robot.urdf", ROBOT)
    (tmp_path / "ws").mkdir()
    (tmp_path / "ws" / "mid.urdf").symlink_to("../src/robot.urdf")
    (tmp_path / "ws" / "robot.urdf").symlink_to("mid.urdf")

    result = CliRunner().invoke(fill_command, [str(tmp_path / "ws" / "robot.urdf")])

    assert result.exit_code == 1, result.stderr
    assert real.read_bytes() == filled(tmp_path)
    assert links_of(tmp_path / "ws") == {"robot.urdf": "mid.urdf", "mid.urdf": "../src/robot.urdf"}


@pytest.mark.parametrize("kind", ["dangling", "loop"])
def test_a_link_that_leads_nowhere_exits_2_and_says_so(tmp_path: Path, kind: str):
    link = tmp_path / "robot.urdf"
    link.symlink_to("gone.urdf" if kind == "dangling" else "other.urdf")
    if kind == "loop":
        (tmp_path / "other.urdf").symlink_to("robot.urdf")

    result = CliRunner().invoke(fill_command, [str(link)])

    assert result.exit_code == 2
    expected = (
        f"error: {link}: is a symbolic link to gone.urdf ({tmp_path / 'gone.urdf'}), which "
        "does not exist: point the link at the file, or give the file itself"
        if kind == "dangling"
        else f"error: {link}: is a symbolic link that cannot be followed (a loop of links)"
    )
    assert result.stderr.startswith(expected)
    assert link.is_symlink() and not link.exists()


def test_output_through_a_link(tmp_path: Path):
    """-o OUT, OUT a link: refused (nothing written) unless --follow-symlinks, which writes the
    file it points to; a dangling OUT is refused either way."""
    path = write(tmp_path / "robot.urdf", ROBOT)
    real = write(tmp_path / "out" / "filled.urdf", "old\n")
    out = tmp_path / "filled.urdf"
    out.symlink_to("out/filled.urdf")

    refused = CliRunner().invoke(fill_command, ["-o", str(out), str(path)])
    assert refused.exit_code == 2
    assert refused.stderr == (
        f"error: -o: {out}: is a symbolic link to out/filled.urdf: not written; "
        "--follow-symlinks writes through it\n"
    )
    assert real.read_text() == "old\n"

    result = CliRunner().invoke(fill_command, ["--follow-symlinks", "-o", str(out), str(path)])

    assert result.exit_code == 1, result.stderr
    assert real.read_bytes() == filled(tmp_path) and out.is_symlink()
    assert path.read_text() == ROBOT

    dangling = tmp_path / "dangling.urdf"
    dangling.symlink_to("nowhere/filled.urdf")
    for follow in ([], ["--follow-symlinks"]):
        result = CliRunner().invoke(fill_command, [*follow, "-o", str(dangling), str(path)])
        assert result.exit_code == 2
        assert ("which does not exist" if follow else "is a symbolic link to") in result.stderr
        assert dangling.is_symlink() and not (tmp_path / "nowhere").exists()


def included(folder: Path) -> Path:
    """A package whose robot.xacro includes parts.xacro, where link `arm` is written."""
    write(folder / "package.xml", PACKAGE.format("robot"))
    return write(
        folder / "urdf" / "robot.xacro",
        f'<robot name="r" {XACRO}>\n  <xacro:include filename="parts.xacro"/>\n'
        f'  <link name="base"/>\n  {joint("base", "arm")}\n</robot>\n',
    )


PARTS = f'<robot {XACRO}>\n  <link name="arm">\n    {BOX}\n  </link>\n</robot>\n'


def test_an_included_link_into_the_package_is_edited_through(tmp_path: Path):
    package = tmp_path / "robot"
    path = included(package)
    real = write(package / "common" / "parts.xacro", PARTS)
    (package / "urdf" / "parts.xacro").symlink_to("../common/parts.xacro")

    result = CliRunner().invoke(fill_command, [str(path)])

    assert result.exit_code == 1, result.stderr
    assert "<inertial>" in real.read_text() and "<mass value=" in real.read_text()
    assert os.readlink(package / "urdf" / "parts.xacro") == "../common/parts.xacro"
    assert "parts.xacro is a symbolic link: the file it points to" in result.stderr


def test_an_included_link_out_of_the_package_is_refused(tmp_path: Path):
    """Fill edits only inside the input's package: a link does not carry it out of it."""
    package = tmp_path / "robot"
    path = included(package)
    real = write(tmp_path / "library" / "parts.xacro", PARTS)
    (package / "urdf" / "parts.xacro").symlink_to(real)

    result = CliRunner().invoke(fill_command, [str(path)])

    assert result.exit_code == 1
    assert (
        f"link `arm` not filled: its <link> is written in {package / 'urdf' / 'parts.xacro'}:2, "
        f"outside {package} (it is a symbolic link to {real})"
    ) in result.stderr
    assert real.read_text() == PARTS and (package / "urdf" / "parts.xacro").is_symlink()


# --- temporary files left by a killed run --------------------------------------------------------

# inertia-fill, stopped in the middle of its write (after its temporary file is written and
# synced, before the rename) until it is killed
STALLED_WRITER = """
import os, sys, time
synced = os.fsync
def stall(descriptor):
    synced(descriptor)
    print("writing", flush=True)
    time.sleep(300)
os.fsync = stall
from inertia_kit.cli import fill_main
fill_main([sys.argv[1]])
"""


def age(path: Path, seconds: float) -> None:
    when = time.time() - seconds
    os.utime(path, (when, when))


@pytest.mark.parametrize("through", ["file", "link"])
def test_a_killed_run_leaves_a_temporary_file_the_next_run_removes(tmp_path: Path, through):
    """
    The reproducer: a SIGKILL during the write leaves `.robot.urdf.*.tmp`. A run meanwhile
    (the killed one still alive, its file made to look two hours old) must not touch it; after
    the kill, the next run removes it (with a note), and leaves alone a temporary file too
    young to judge and another program's.
    """
    real = write(tmp_path / "src" / "robot.urdf", ROBOT)
    (tmp_path / ".git").mkdir()  # the repository the link and its target are in
    path = real
    if through == "link":
        (tmp_path / "ws").mkdir()
        path = tmp_path / "ws" / "robot.urdf"
        path.symlink_to(real)
    writer = subprocess.Popen(
        [sys.executable, "-c", STALLED_WRITER, str(path)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        assert writer.stdout.readline() == "writing\n", writer.stderr.read()
        # its temporary file is beside the real file, never beside the link
        [live] = temporaries(tmp_path)
        assert live.parent == real.parent and live.name.startswith(".robot.urdf.inertia-kit-")
        age(live, 2 * 3600)

        concurrent = subprocess.run(
            [console_script("inertia-fill"), str(path)], capture_output=True, text=True
        )
        assert concurrent.returncode == 1, concurrent.stderr
        assert live.exists()  # the live writer holds it
        assert "removed" not in concurrent.stderr
    finally:
        writer.send_signal(signal.SIGKILL)
        writer.wait()
        writer.stdout.close()
        writer.stderr.close()
    assert temporaries(tmp_path) == [live]  # what the kill left behind
    young = write(real.parent / ".robot.urdf.inertia-kit-0123456789ab.tmp", "half")
    theirs = write(real.parent / ".robot.urdf.x8k2j4mq.tmp", "another program's")
    age(theirs, 2 * 3600)

    after = subprocess.run(
        [console_script("inertia-fill"), str(path)], capture_output=True, text=True
    )

    assert after.returncode == 0, after.stderr  # filled by the concurrent run already
    assert not live.exists()
    assert after.stderr.splitlines() == [
        f"note: removed {live}, a temporary file left by an inertia-fill that was killed while "
        "writing",
        "inertia-fill: 1 file checked, nothing to change",
    ]
    assert young.exists() and theirs.exists()
    assert real.read_bytes() == filled(tmp_path)
    assert through == "file" or path.is_symlink()
