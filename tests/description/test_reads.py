"""What a load read (description.reads): a digest of every file, the input and each xacro
include (read in the forked expansion), and the refusal of a file that holds other bytes now."""

from __future__ import annotations

from pathlib import Path

import pytest
from kit import write

from inertia_kit.description.edits import ChangedWhileEditing
from inertia_kit.description.loader import load
from inertia_kit.description.reads import as_loaded, combined, digest, key, record

XACRO = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
PART = f'<robot {XACRO}><xacro:macro name="arm"><link name="arm"/></xacro:macro></robot>\n'
MAIN = (
    f'<robot name="r" {XACRO}><xacro:include filename="part.xacro"/><link name="base"/>'
    '<xacro:arm/><joint name="j" type="fixed"><parent link="base"/><child link="arm"/></joint>'
    "</robot>\n"
)


def test_a_urdf_load_records_its_bytes(tmp_path: Path):
    path = write(tmp_path / "r.urdf", '<robot name="r"><link name="a"/></robot>\n')
    robot = load(path)
    assert dict(robot.reads) == {key(path): digest(path.read_bytes())}


@pytest.mark.parametrize("sandboxed", [True, False])
def test_a_xacro_load_records_every_include(tmp_path: Path, monkeypatch, sandboxed: bool):
    """From the forked child too: what it read comes back with the expansion."""
    from inertia_kit.description.urdf import xacro_sandbox

    if not sandboxed:
        monkeypatch.setattr(xacro_sandbox, "can_fork", lambda: False)
    main = write(tmp_path / "robot.xacro", MAIN)
    part = write(tmp_path / "part.xacro", PART)
    linked = tmp_path / "linked.xacro"
    linked.symlink_to("robot.xacro")  # known by its real path
    robot = load(linked)
    assert dict(robot.reads) == {
        key(main): digest(MAIN.encode()),
        key(part): digest(PART.encode()),
    }


def test_a_file_read_twice_with_other_bytes_has_no_digest():
    reads: dict[str, str | None] = {}
    record(reads, "a.xacro", b"one")
    record(reads, "a.xacro", b"one")
    assert reads[key("a.xacro")] == digest(b"one")
    record(reads, "a.xacro", b"two")
    assert reads[key("a.xacro")] is None
    record(reads, "a.xacro", b"one")
    assert reads[key("a.xacro")] is None
    assert combined([{"x": "1", "y": "2"}, {"x": "1", "y": "3"}]) == {"x": "1", "y": None}


def test_a_file_is_edited_only_as_it_was_read(tmp_path: Path):
    path = write(tmp_path / "r.urdf", "<robot/>")
    assert as_loaded(path, {}).text == "<robot/>"  # not read by the load: as it is
    assert as_loaded(path, {key(path): digest(b"<robot/>")}).text == "<robot/>"
    for read in (digest(b"<robot></robot>"), None):
        with pytest.raises(ChangedWhileEditing, match="the file changed while it was being"):
            as_loaded(path, {key(path): read})
