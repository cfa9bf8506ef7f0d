"""
Text edits and atomic writes: bytes outside the edits never change; a symbolic link is written
through (the file it points to is replaced, the link kept); temporary files a killed write left
behind are removed by the next write, and only those.
"""

import codecs
import errno
import os
import stat
import time
from pathlib import Path

import pytest

from inertia_kit.description import edits
from inertia_kit.description.edits import (
    MIN_STALE_SECONDS,
    UNPROVEN_STALE_SECONDS,
    ChangedWhileEditing,
    Edit,
    apply_edits,
    read_source,
    real_target,
    remove_stale_temporaries,
    write_all_atomic,
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


def test_write_atomic_writes_pieces_as_they_come(tmp_path):
    # a long report is written from pieces, never held whole in memory
    path = tmp_path / "report.json"
    path.write_bytes(b"old")
    path.chmod(0o640)
    made = []

    def pieces():
        for n in range(3):
            made.append(n)
            yield f"[{n}]".encode()

    assert write_atomic(path, pieces(), create=True)
    assert path.read_bytes() == b"[0][1][2]" and made == [0, 1, 2]
    assert stat.S_IMODE(path.stat().st_mode) == 0o640
    assert write_atomic(tmp_path / "new.json", iter([b"a", b"b"]), create=True)
    assert (tmp_path / "new.json").read_bytes() == b"ab"


def test_pieces_that_fail_midway_leave_the_file_as_it_was(tmp_path):
    path = tmp_path / "report.json"
    path.write_bytes(b"old")

    def pieces():
        yield b"new"
        raise RuntimeError("a bug while rendering")

    with pytest.raises(RuntimeError):
        write_atomic(path, pieces(), create=True)
    assert path.read_bytes() == b"old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["report.json"]


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


# --- symbolic links: the file they point to is written, the link kept ----------------------------


def linked(tmp_path):
    """``ws/robot.urdf -> mid.urdf -> ../src/robot.urdf`` (a chain of relative links)."""
    (tmp_path / "src").mkdir()
    (tmp_path / "ws").mkdir()
    real = tmp_path / "src" / "robot.urdf"
    real.write_bytes(b"old")
    os.chmod(real, 0o640)
    (tmp_path / "ws" / "mid.urdf").symlink_to("../src/robot.urdf")
    (tmp_path / "ws" / "robot.urdf").symlink_to("mid.urdf")
    return tmp_path / "ws" / "robot.urdf", real


def test_write_through_a_chain_of_links_keeps_the_links(tmp_path, monkeypatch):
    link, real = linked(tmp_path)
    renames = []
    replace = os.replace
    monkeypatch.setattr(os, "replace", lambda a, b: renames.append((a, b)) or replace(a, b))

    assert real_target(link) == real.resolve()
    assert write_atomic(link, b"new", expected=b"old")

    assert real.read_bytes() == b"new" and stat.S_IMODE(real.stat().st_mode) == 0o640
    assert os.readlink(link) == "mid.urdf" and os.readlink(link.parent / "mid.urdf") == (
        "../src/robot.urdf"
    )
    # the temporary file was made beside the real file, so the rename stays in one folder
    [(temporary, target)] = renames
    assert Path(temporary).parent == real.resolve().parent and Path(target) == real.resolve()
    assert sorted(p.name for p in (tmp_path / "src").iterdir()) == ["robot.urdf"]


@pytest.mark.parametrize("kind", ["dangling", "loop"])
def test_a_link_that_leads_nowhere_is_refused(tmp_path, kind):
    link = tmp_path / "robot.urdf"
    if kind == "dangling":
        link.symlink_to("gone/robot.urdf")
        message = r"symbolic link to gone/robot.urdf \(.*\), which does not exist"
    else:
        link.symlink_to("other.urdf")
        (tmp_path / "other.urdf").symlink_to("robot.urdf")
        message = "symbolic link that cannot be followed"
    for write in (
        lambda: write_atomic(link, b"new"),
        lambda: write_atomic(link, b"new", create=True),  # -o OUT: not created at the far end
        lambda: read_source(link),
    ):
        with pytest.raises(InputError, match=message):
            write()
    assert link.is_symlink() and not link.exists()
    assert {p.name for p in tmp_path.iterdir()} <= {"robot.urdf", "other.urdf"}


def test_write_all_checks_every_link_before_writing(tmp_path):
    good = tmp_path / "good.urdf"
    good.write_bytes(b"old")
    dangling = tmp_path / "dangling.urdf"
    dangling.symlink_to("missing.urdf")
    with pytest.raises(InputError, match="does not exist"):
        write_all_atomic([(good, b"new", b"old"), (dangling, b"new", b"old")])
    assert good.read_bytes() == b"old"


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() != 0, reason="needs root")
def test_owner_and_group_are_kept_where_the_system_lets_us(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_bytes(b"old")
    os.chown(path, 1234, 5678)
    assert write_atomic(path, b"new")
    assert (path.stat().st_uid, path.stat().st_gid) == (1234, 5678)


# --- temporary files left by a write that was killed ---------------------------------------------

HOUR = 3600.0


def temporary(folder, name="robot.urdf", *, age=0.0, tag="0123456789ab"):
    path = folder / f".{name}.inertia-kit-{tag}.tmp"
    path.write_bytes(b"half a file")
    when = time.time() - age
    os.utime(path, (when, when))
    return path


def test_stale_temporaries_of_ours_are_removed_and_nothing_else(tmp_path):
    stale = temporary(tmp_path, age=MIN_STALE_SECONDS + 5, tag="000000000001")
    other_name = temporary(tmp_path, "arm.xacro", age=2 * HOUR, tag="000000000002")
    young = temporary(tmp_path, age=5, tag="000000000003")  # perhaps being written right now
    foreign = [  # not ours: another program's temporary files, and look-alikes
        tmp_path / ".robot.urdf.k3j4h5g6.tmp",
        tmp_path / ".robot.urdf.inertia-kit-XYZ.tmp",
        tmp_path / "robot.urdf.inertia-kit-000000000004.tmp",
        tmp_path / ".robot.urdf.inertia-kit-000000000005.tmp.bak",
    ]
    for path in foreign:
        path.write_bytes(b"theirs")
        os.utime(path, (0, 0))
    folder = tmp_path / ".robot.urdf.inertia-kit-000000000006.tmp"
    folder.mkdir()
    os.utime(folder, (0, 0))
    target = tmp_path / "precious.urdf"
    target.write_bytes(b"precious")
    link = tmp_path / ".robot.urdf.inertia-kit-000000000007.tmp"
    link.symlink_to(target)
    os.utime(link, (0, 0), follow_symlinks=False)

    assert sorted(remove_stale_temporaries(tmp_path)) == sorted([stale, other_name])

    assert not stale.exists() and not other_name.exists()
    assert young.exists() and folder.is_dir() and link.is_symlink()
    assert all(p.read_bytes() == b"theirs" for p in foreign)
    assert target.read_bytes() == b"precious"


def test_a_temporary_file_a_live_writer_holds_is_kept_however_old(tmp_path):
    """A writer holds a lock on its temporary file until it has its name (a concurrent run in
    another process, or another thread of this one: the lock is per open file)."""
    import fcntl

    live = temporary(tmp_path, age=10 * HOUR)
    with open(live, "rb") as held:
        fcntl.flock(held.fileno(), fcntl.LOCK_EX)
        assert remove_stale_temporaries(tmp_path) == []
        assert live.exists()
    assert remove_stale_temporaries(tmp_path) == [live]  # its writer is gone


def test_where_no_lock_can_tell_only_the_age_decides(tmp_path, monkeypatch):
    """A file system without locks: a temporary file is stale only after an hour."""

    def no_locks(handle, *, blocking):
        raise OSError(errno.ENOLCK, "No locks available")

    monkeypatch.setattr(edits, "_lock", no_locks)
    recent = temporary(tmp_path, age=UNPROVEN_STALE_SECONDS - 60, tag="000000000001")
    old = temporary(tmp_path, age=UNPROVEN_STALE_SECONDS + 60, tag="000000000002")
    assert remove_stale_temporaries(tmp_path) == [old]
    assert recent.exists()


def test_a_write_removes_stale_temporaries_beside_its_real_target(tmp_path):
    link, real = linked(tmp_path)
    stale = temporary(real.parent, age=2 * HOUR)
    assert write_atomic(link, b"new", expected=b"old")
    assert not stale.exists()
    assert sorted(p.name for p in real.parent.iterdir()) == ["robot.urdf"]


def test_a_failing_write_is_an_input_error_and_leaves_the_file(tmp_path, monkeypatch):
    """A full disk (fsync fails) or a folder we may not write in: the file as it was, no
    temporary file left, an InputError that says what happened."""
    path = tmp_path / "r.urdf"
    path.write_bytes(b"old")

    def full(descriptor):
        raise OSError(errno.ENOSPC, "No space left on device")

    with monkeypatch.context() as patch:
        patch.setattr(os, "fsync", full)
        with pytest.raises(InputError, match="cannot write: No space left on device"):
            write_atomic(path, b"new", expected=b"old")
    assert path.read_bytes() == b"old" and [p.name for p in tmp_path.iterdir()] == ["r.urdf"]

    def denied(target):
        raise PermissionError(errno.EACCES, "Permission denied")

    monkeypatch.setattr(edits, "_create_temporary", denied)
    with pytest.raises(InputError, match=f"no temporary file in {tmp_path} \\(Permission denied"):
        write_atomic(path, b"new", expected=b"old")
    assert path.read_bytes() == b"old"


def test_writers_check_and_replace_one_at_a_time(tmp_path):
    """Two writers that both read the same text: the one that waits for the other's
    check-and-replace then finds the other's bytes, and writes nothing (else both checks pass
    before either replaces, and the second silently undoes the first)."""
    import threading

    path = tmp_path / "robot.urdf"
    path.write_bytes(b"old")
    outcome: list[object] = []

    def second_writer() -> None:
        try:
            outcome.append(edits.write_all_atomic([(path, b"second", b"old")]))
        except InputError as error:
            outcome.append(error)

    with edits._commit_lock([tmp_path]):  # the first writer, between its check and replace
        thread = threading.Thread(target=second_writer)
        thread.start()
        thread.join(0.3)
        assert thread.is_alive() and path.read_bytes() == b"old"  # it waits
        edits.write_atomic(path, b"first")  # the first one's replace
    thread.join(10)
    assert [type(o) for o in outcome] == [edits.ChangedWhileEditing]
    assert path.read_bytes() == b"first"


def test_a_set_of_files_is_written_whole_or_not_at_all(tmp_path, monkeypatch):
    """The last look covers every file of the set before any is renamed into place."""
    a, b = tmp_path / "a.xacro", tmp_path / "b.xacro"
    a.write_bytes(b"a")
    b.write_bytes(b"b")
    original = edits._prepare

    def prepare(target, *args):
        made = original(target, *args)
        if target.name == "b.xacro":
            b.write_bytes(b"saved")  # an editor's save once a's new text is ready
        return made

    monkeypatch.setattr(edits, "_prepare", prepare)
    with pytest.raises(edits.ChangedWhileEditing):
        edits.write_all_atomic([(a, b"A", b"a"), (b, b"B", b"b")])
    assert (a.read_bytes(), b.read_bytes()) == (b"a", b"saved")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.xacro", "b.xacro"]


def test_without_following_links_the_name_itself_is_replaced(tmp_path):
    target = tmp_path / "deploy.sh"
    target.write_bytes(b"#!/bin/sh\n")
    link = tmp_path / "results.sarif"
    link.symlink_to("deploy.sh")
    edits.write_atomic(link, b"{}", create=True, follow_symlinks=False)
    assert target.read_bytes() == b"#!/bin/sh\n"
    assert not link.is_symlink() and link.read_bytes() == b"{}"


def test_read_source_decodes_as_the_parser_an_encoding_libxml2_does_not_know(tmp_path):
    """
    ``encoding="cp500"`` (EBCDIC) on UTF-8 bytes: the parser reads them as UTF-8 and tells
    lines of that text; decoded as cp500 the file had one line (fuzz input 119).
    """
    path = tmp_path / "r.urdf"
    path.write_bytes(
        '<?xml version="1.0" encoding="cp500"?>\n<robot name="é">\n</robot>\n'.encode()
    )
    source = read_source(path)
    assert (source.encoding, source.text[source.offset(2, 1)]) == ("utf-8", "<")
    assert source.encode(source.text) == path.read_bytes()


def test_a_robot_declaring_an_encoding_libxml2_does_not_know_is_linted(tmp_path):
    from click.testing import CliRunner

    from inertia_kit.cli import main

    path = tmp_path / "r.urdf"
    path.write_bytes(
        b'<?xml version="1.0" encoding="cp500"?>\n<robot>\n  <link>\n  </link>\n'
        b'  <link name="l1">\n    <inertial><mass value="-nan"/><inertia/></inertial>\n'
        b'    <collision><geometry><box size="0.2 0.4 0.5"/></geometry></collision>\n'
        b"  </link>\n  <joint>\n  </joint>\n</robot>\n"
    )
    result = CliRunner().invoke(main, ["lint", "--engine", "mujoco", str(path)])
    assert result.exit_code == 1, result.output
    assert "internal error" not in result.output


@pytest.mark.parametrize("codec", ["utf-32-le", "utf-32-be"])
def test_read_source_reads_utf32_by_its_own_mark(tmp_path, codec):
    """UTF-32-LE's mark begins with UTF-16-LE's: read as UTF-16 the offsets were of another text
    (an internal error for a fix on such a file; fuzz input 56 of seed ci)."""
    mark = codecs.BOM_UTF32_LE if codec.endswith("le") else codecs.BOM_UTF32_BE
    path = tmp_path / "r.urdf"
    path.write_bytes(mark + '<?xml version="1.0"?>\n<robot name="é"/>\n'.encode(codec))
    source = read_source(path)
    assert (source.encoding, source.bom) == (codec, mark)
    assert source.text[source.offset(2, 1)] == "<"
    assert source.encode(source.text) == path.read_bytes()


@pytest.mark.parametrize("codec", ["utf-32-le", "utf-32-be"])
def test_read_source_reads_utf32_without_a_mark(tmp_path, codec):
    """UTF-32 without a mark begins with the two bytes of UTF-16's ``<`` too (XML 1.0, F.1): read
    as UTF-16 the columns were another text's and a fix hit no tag (fuzz s1, input 15055, whose
    declaration even said UTF-16)."""
    path = tmp_path / "r.urdf"
    text = '<?xml version="1.0" encoding="UTF-16"?>\n<robot name="é"><link name="a"/></robot>\n'
    path.write_bytes(text.encode(codec))
    source = read_source(path)
    assert (source.encoding, source.bom) == (codec, b"")
    assert source.text == text
    assert source.text[source.offset(2, 17)] == "<"
    assert source.encode(source.text) == path.read_bytes()


def test_write_all_atomic_checks_the_files_read_but_not_written(tmp_path):
    """Edits computed from robot.xacro and base.xacro are stale once another writer saved
    base.xacro: nothing is written (fuzz s1, input 17823: `--fix` on the included files and
    `--add-noqa` on the main one at once ended in a state no order of the two gives)."""
    from inertia_kit.description.edits import ChangedWhileEditing, write_all_atomic
    from inertia_kit.description.reads import digest, key

    main, included = tmp_path / "robot.xacro", tmp_path / "base.xacro"
    main.write_bytes(b"<robot/>\n")
    included.write_bytes(b"<link/>\n")
    reads = {key(main): digest(b"<robot/>\n"), key(included): digest(b"<link/>\n")}
    included.write_bytes(b"<link>saved by another writer</link>\n")
    with pytest.raises(ChangedWhileEditing):
        write_all_atomic([(main, b"<robot><!-- x --></robot>\n", b"<robot/>\n")], unchanged=reads)
    assert main.read_bytes() == b"<robot/>\n"
    # as read: written (the written file itself is checked against its expected bytes)
    included.write_bytes(b"<link/>\n")
    assert write_all_atomic([(main, b"<robot>x</robot>\n", b"<robot/>\n")], unchanged=reads)
    assert main.read_bytes() == b"<robot>x</robot>\n"


# --- outputs that are no regular file -------------------------------------------------------------


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes here")
def test_an_output_that_is_a_named_pipe_is_written_into_not_replaced(tmp_path):
    import threading

    fifo = tmp_path / "report.fifo"
    os.mkfifo(fifo)
    received: list[bytes] = []
    reader = threading.Thread(target=lambda: received.append(fifo.read_bytes()), daemon=True)
    reader.start()
    assert write_atomic(fifo, [b"a report ", b"in pieces\n"], create=True)
    reader.join(timeout=30)
    assert received == [b"a report in pieces\n"]
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)  # still the pipe a pipeline reads


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() != 0, reason="needs root")
def test_an_output_that_is_a_device_is_written_into_never_renamed_over(tmp_path):
    """As root a rename over ``/dev/null`` made it a regular file for the whole system
    (``inertia-lint -o /dev/null``); nodes of our own here, never the system's."""
    null, full = tmp_path / "null", tmp_path / "full"
    try:
        os.mknod(null, stat.S_IFCHR | 0o666, os.makedev(1, 3))
        os.mknod(full, stat.S_IFCHR | 0o666, os.makedev(1, 7))
        with open(null, "wb"):  # a nodev mount makes them but refuses to open them
            pass
    except OSError as error:  # a container without CAP_MKNOD, a nodev mount
        pytest.skip(f"cannot make or open device nodes here: {error.strerror}")
    assert write_atomic(null, b"discarded", create=True)
    assert write_atomic(null, iter([b"in ", b"pieces"]), create=True)
    with pytest.raises(InputError, match="cannot write: No space left on device"):
        write_atomic(full, iter([b"report"]), create=True)  # pieces: /dev/full is not read
    for node in (null, full):
        assert stat.S_ISCHR(os.lstat(node).st_mode)
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".tmp")]


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes here")
def test_a_file_to_edit_that_is_no_regular_file_is_refused(tmp_path):
    import threading

    fifo = tmp_path / "robot.urdf"
    os.mkfifo(fifo)
    # a writer feeds the pipe what the edits expect, again and again: a writer that read it
    # would go on and replace it (the old code did) rather than wait for ever
    stop = threading.Event()

    def feed() -> None:
        while not stop.is_set():
            fifo.write_bytes(b"<robot name='r'/>")

    feeder = threading.Thread(target=feed, daemon=True)
    feeder.start()
    try:
        with pytest.raises(InputError, match="is a named pipe, not a file to edit"):
            write_atomic(fifo, b"<robot/>", expected=b"<robot name='r'/>")
        with pytest.raises(InputError, match="is a named pipe, not a file to edit"):
            write_all_atomic([(fifo, b"<robot/>", b"<robot name='r'/>")])
        assert stat.S_ISFIFO(os.lstat(fifo).st_mode)
    finally:  # nothing read the pipe: let the feeder finish
        stop.set()
        drain = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)
        feeder.join(timeout=10)
        os.close(drain)
