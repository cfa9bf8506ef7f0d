"""
inertia_kit.reading: a file of the tree is read only if it is a regular file, and only up to a
bound; a named pipe (which would block the read), a device (``/dev/zero`` never ends) or a file
over the bound is refused before it is read, with a message naming it.
"""

from __future__ import annotations

import os
import threading

import pytest

from inertia_kit.errors import InputError
from inertia_kit.reading import Refused, check_regular, open_regular, read_regular


def finishes(call, seconds: float = 10.0):
    """``call()``'s outcome (its value or the exception it raised), failing if it blocks."""
    outcome: list = []

    def run():
        try:
            outcome.append(call())
        except BaseException as error:
            outcome.append(error)

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    thread.join(seconds)
    assert outcome, f"still reading after {seconds} s"
    return outcome[0]


def test_a_regular_file_within_the_bound_is_read(tmp_path):
    path = tmp_path / "a.urdf"
    path.write_bytes(b"x" * 100)
    assert read_regular(path, 100) == b"x" * 100
    with pytest.raises(Refused, match="larger than 99 bytes; no robot is that big"):
        read_regular(path, 99, what="robot")


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes here")
def test_a_named_pipe_is_refused_without_blocking(tmp_path):
    pipe = tmp_path / "robot.urdf"
    os.mkfifo(pipe)
    error = finishes(lambda: read_regular(pipe, 1 << 20))
    assert isinstance(error, Refused)
    assert error.path == str(pipe) and "named pipe" in error.message
    assert isinstance(finishes(lambda: check_regular(pipe, 1 << 20)), Refused)


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="no /dev/zero here")
def test_a_link_to_a_device_is_refused_unread(tmp_path):
    link = tmp_path / "robot.urdf"
    link.symlink_to("/dev/zero")
    error = finishes(lambda: read_regular(link, 1 << 30))
    assert isinstance(error, Refused) and "character device" in error.message


def test_links_are_followed_unless_asked_not_to(tmp_path):
    (tmp_path / "real").write_bytes(b"data")
    (tmp_path / "link").symlink_to("real")
    assert read_regular(tmp_path / "link", 10) == b"data"
    with pytest.raises(Refused, match="symbolic link"):
        read_regular(tmp_path / "link", 10, follow_links=False)
    (tmp_path / "loop").symlink_to("loop")
    with pytest.raises(InputError, match="loop of links"):
        read_regular(tmp_path / "loop", 10)


def test_missing_files_and_folders_are_named(tmp_path):
    with pytest.raises(InputError, match="no such file") as caught:
        read_regular(tmp_path / "nope", 10)
    assert not isinstance(caught.value, Refused)
    with pytest.raises(Refused, match="is a directory, not a mesh file"):
        read_regular(tmp_path, 10, what="mesh file")


@pytest.mark.parametrize("size", [0, 1, 999, 1000, 1001, 5000])
def test_read_at_most_gives_what_read_of_one_more_than_the_bound_gives(tmp_path, size):
    """The bytes ``read(limit + 1)`` gives, up to a file one byte over ``limit`` and beyond."""
    from inertia_kit.reading import read_at_most

    path = tmp_path / "data"
    path.write_bytes(bytes(range(256)) * (size // 256) + bytes(size % 256))
    with open(path, "rb") as stream:
        expected = stream.read(1001)
    with open(path, "rb") as stream:
        assert read_at_most(stream, 1000) == expected


def test_read_at_most_reads_on_past_the_size_a_file_reports(tmp_path):
    """A file that holds more than its size said (it grew, or reports none: a pipe, /proc)
    is read on to the bound; the buffer is the file's size, not the bound's (256 MB)."""
    import tracemalloc

    from inertia_kit.reading import read_at_most

    read, write = os.pipe()  # fstat reports no size
    os.write(write, b"x" * 3000)
    os.close(write)
    with os.fdopen(read, "rb") as stream:
        assert read_at_most(stream, 1000) == b"x" * 1001
    path = tmp_path / "small"
    path.write_bytes(b"y" * 28000)
    tracemalloc.start()
    try:
        with open(path, "rb") as stream:
            assert read_at_most(stream, 256 << 20) == b"y" * 28000
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 1 << 20, peak


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes here")
def test_open_regular_refuses_what_is_no_regular_file_without_blocking(tmp_path):
    pipe = tmp_path / "entry.json"
    os.mkfifo(pipe)
    assert isinstance(finishes(lambda: open_regular(pipe)), OSError)
    assert isinstance(finishes(lambda: open_regular(tmp_path)), OSError)
    regular = tmp_path / "r.json"
    regular.write_bytes(b"{}")
    with open_regular(regular) as stream:
        assert stream.read() == b"{}"
