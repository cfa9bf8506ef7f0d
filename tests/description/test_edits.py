"""Text edits and atomic writes: bytes outside the edits never change."""

import codecs
import os
import stat

import pytest

from inertia_kit.description.edits import (
    ChangedWhileEditing,
    Edit,
    apply_edits,
    read_source,
    write_atomic,
)
from inertia_kit.errors import InputError


def test_apply_edits_splices_in_one_pass_and_skips_overlaps():
    text = "0123456789"
    new, applied = apply_edits(
        text, [Edit("f", 5, 7, "ab"), Edit("f", 0, 1, "X"), Edit("f", 6, 8, "overlap")]
    )
    assert new == "X1234ab789"
    assert [e.content for e in applied] == ["X", "ab"]


def test_insertion_at_the_same_point_keeps_order_of_offsets():
    new, _ = apply_edits("ab", [Edit("f", 1, 1, "-")])
    assert new == "a-b"


def test_edit_outside_the_text_is_an_error():
    with pytest.raises(ValueError, match="outside the text"):
        apply_edits("ab", [Edit("f", 1, 5, "")])


@pytest.mark.parametrize(
    "data",
    [
        b'<robot name="r">\r\n  <link name="a"/>\r\n</robot>\r\n',
        b"\xef\xbb\xbf<robot name='r'>\n\t<link name='a'/>\n</robot>",
        '<?xml version="1.0" encoding="latin-1"?>\n<robot name="caf\xe9"/>\n'.encode("latin-1"),
        codecs.BOM_UTF16_LE + "<robot/>\n".encode("utf-16-le"),
    ],
)
def test_read_source_round_trips_every_byte(tmp_path, data):
    path = tmp_path / "r.urdf"
    path.write_bytes(data)
    source = read_source(path)
    assert source.encode(source.text) == data


def test_newline_and_offsets(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_bytes(b'<robot name="r">\r\n  <link name="a"/>\r\n</robot>\r\n')
    source = read_source(path)
    assert source.newline == "\r\n"
    assert source.text[source.offset(2, 3)] == "<"


def test_write_atomic_replaces_content_and_keeps_mode(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_bytes(b"old")
    os.chmod(path, 0o640)
    assert write_atomic(path, b"new", expected=b"old")
    assert path.read_bytes() == b"new"
    assert stat.S_IMODE(path.stat().st_mode) == 0o640
    assert [p.name for p in tmp_path.iterdir()] == ["r.urdf"]  # no temporary left behind


def test_write_atomic_writes_nothing_when_unchanged(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_bytes(b"same")
    before = path.stat().st_mtime_ns
    assert not write_atomic(path, b"same")
    assert path.stat().st_mtime_ns == before


def test_a_file_changed_meanwhile_is_not_overwritten(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_bytes(b"changed by someone else")
    with pytest.raises(ChangedWhileEditing):
        write_atomic(path, b"ours", expected=b"what we read")
    assert path.read_bytes() == b"changed by someone else"


def test_read_only_file_is_an_input_error(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_bytes(b"old")
    os.chmod(path, 0o444)
    with pytest.raises(InputError, match="read-only"):
        write_atomic(path, b"new")


def test_create_writes_a_new_file_and_refuses_a_missing_folder(tmp_path):
    new = tmp_path / "out.urdf"
    assert write_atomic(new, b"data", create=True)
    assert new.read_bytes() == b"data"
    assert not write_atomic(new, b"data", create=True)  # same bytes: nothing written
    with pytest.raises(InputError, match="no folder"):
        write_atomic(tmp_path / "nowhere" / "out.urdf", b"data", create=True)
    with pytest.raises(InputError, match="cannot read"):
        write_atomic(
            tmp_path / "absent.urdf", b"data"
        )  # without create, a missing file is an error
    with pytest.raises(InputError, match="folder"):
        write_atomic(tmp_path, b"data", create=True)
