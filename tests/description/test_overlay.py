"""
The overlay `--fix` lints its passes through: a file it holds reads as its bytes there, by any
name of the file, only within the block, in a forked child too.
"""

from __future__ import annotations

import os
import pickle
from pathlib import Path

import pytest
from kit import write

from inertia_kit.description.overlay import overlaid
from inertia_kit.description.safexml import read_bounded


def test_a_held_file_reads_as_held_by_any_name_and_only_within_the_block(tmp_path: Path):
    path = write(tmp_path / "a.urdf", "<robot/>")
    other = write(tmp_path / "b.urdf", "<robot name='b'/>")
    (tmp_path / "link.urdf").symlink_to(path)
    with overlaid({os.path.realpath(path): b"<robot name='held'/>"}):
        for name in (path, tmp_path / "link.urdf", tmp_path / "sub" / ".." / "a.urdf"):
            assert read_bounded(name) == b"<robot name='held'/>"
        assert read_bounded(other) == b"<robot name='b'/>"  # not held: the disk
        # an overlay within one holds both (a fix probing an expansion during a --fix pass)
        with overlaid({os.path.realpath(other): b"<robot name='also'/>"}):
            assert read_bounded(path) == b"<robot name='held'/>"
            assert read_bounded(other) == b"<robot name='also'/>"
        assert read_bounded(path) == b"<robot name='held'/>"
        assert read_bounded(other) == b"<robot name='b'/>"
    assert read_bounded(path) == b"<robot/>"
    assert path.read_bytes() == b"<robot/>"


def test_the_block_holds_a_copy(tmp_path: Path):
    path = write(tmp_path / "a.urdf", "<robot/>")
    texts = {os.path.realpath(path): b"<robot name='one'/>"}
    with overlaid(texts):
        texts[os.path.realpath(path)] = b"<robot name='two'/>"
        assert read_bounded(path) == b"<robot name='one'/>"


@pytest.mark.skipif(not hasattr(os, "fork"), reason="xacro expands in a forked child")
def test_a_forked_child_reads_the_overlay(tmp_path: Path):
    """As a xacro expansion does (description.xacro_sandbox)."""
    path = write(tmp_path / "a.urdf", "<robot/>")
    read_end, write_end = os.pipe()
    with overlaid({os.path.realpath(path): b"<robot name='held'/>"}):
        pid = os.fork()
        if pid == 0:  # pragma: no cover - the child
            os.write(write_end, pickle.dumps(read_bounded(path)))
            os._exit(0)
    os.close(write_end)
    with os.fdopen(read_end, "rb") as stream:
        assert pickle.loads(stream.read()) == b"<robot name='held'/>"
    os.waitpid(pid, 0)
