"""
The on-disk mesh cache: the same solids as ``mesh_solid``, bit for bit, without reading an
unchanged mesh again, and never a failure because of the cache itself.
"""

from __future__ import annotations

import dataclasses
import json
import multiprocessing
import os
import subprocess
import sys
import time
import zlib
from pathlib import Path

import numpy as np
import pytest
from kit import REPO
from kit.meshes import box_triangles, write_ascii_stl, write_binary_stl
from kit.physics import assert_same

from inertia_kit.errors import MeshError
from inertia_kit.physics import mesh_cache, mesh_cache_entries
from inertia_kit.physics.mesh_cache import cache_location, cached_mesh_solid
from inertia_kit.physics.meshes import MeshSolid, mesh_solid

ROOT = REPO
SCALES = [(1.0, 1.0, 1.0), (0.001, 0.001, 0.001), (0.3, -2.0, 7.1), (-1.0, 1.0, 1.0)]


@pytest.fixture
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """The default cache location, in ``tmp_path``; files just written may be stored."""
    folder = tmp_path / "cache"
    monkeypatch.setenv(mesh_cache.ENV_DIR, str(folder))
    monkeypatch.delenv(mesh_cache.ENV_DISABLE, raising=False)
    monkeypatch.setattr(mesh_cache, "RACY_SECONDS", 0.0)
    return folder


@pytest.fixture
def calls(monkeypatch: pytest.MonkeyPatch) -> list[tuple]:
    """Every ``mesh_solid`` call the cache makes: a miss makes one, a hit none."""
    made: list[tuple] = []

    def spy(path, scale=(1.0, 1.0, 1.0)):
        made.append((str(path), tuple(scale)))
        return mesh_solid(path, scale)

    monkeypatch.setattr(mesh_cache, "mesh_solid", spy)
    return made


def forbid_reading(monkeypatch: pytest.MonkeyPatch) -> None:
    def fail(path, scale=(1.0, 1.0, 1.0)):
        raise AssertionError(f"read {path} on a cache hit")

    monkeypatch.setattr(mesh_cache, "mesh_solid", fail)


def entries(folder: Path) -> list[Path]:
    return sorted((folder / f"meshes-v{mesh_cache_entries.FORMAT}").glob("*.json"))


# --- meshes ------------------------------------------------------------------------------------


def rotation(rpy) -> np.ndarray:
    r, p, y = rpy
    rx = np.array([[1, 0, 0], [0, np.cos(r), -np.sin(r)], [0, np.sin(r), np.cos(r)]])
    ry = np.array([[np.cos(p), 0, np.sin(p)], [0, 1, 0], [-np.sin(p), 0, np.cos(p)]])
    rz = np.array([[np.cos(y), -np.sin(y), 0], [np.sin(y), np.cos(y), 0], [0, 0, 1]])
    return rz @ ry @ rx


def tilted_box(size=(0.3, 0.2, 0.1), rpy=(0.3, -0.2, 0.5), offset=(0.12, -0.05, 0.2)):
    """(12, 3, 3) float32 closed box, tilted and off the origin: no zero product of inertia."""
    centred = box_triangles(size, low=np.multiply(size, -0.5))
    return (centred @ rotation(rpy).T + offset).astype(np.float32)


def write_dae(path: Path, unit: float | None) -> Path:
    import trimesh

    triangles = tilted_box(size=(300.0, 200.0, 100.0), offset=(120.0, -50.0, 200.0))
    part = trimesh.Trimesh(triangles.reshape(-1, 3), np.arange(36).reshape(-1, 3))
    text = part.export(file_type="dae").decode()
    if unit is not None:
        text = text.replace("<asset>", f'<asset>\n    <unit meter="{unit!r}" name="u"/>', 1)
    path.write_text(text)
    return path


MESHES = {
    "binary-stl": lambda d: write_binary_stl(d / "box.stl", tilted_box()),
    "ascii-stl": lambda d: write_ascii_stl(d / "box.stl", tilted_box()),
    "inverted-stl": lambda d: write_binary_stl(d / "box.stl", tilted_box()[:, ::-1]),
    "open-stl": lambda d: write_binary_stl(d / "box.stl", tilted_box()[:-1]),
    "inconsistent-winding-stl": lambda d: write_binary_stl(
        d / "box.stl", np.concatenate([tilted_box()[:-1], tilted_box()[-1:, ::-1]])
    ),
    "dae-millimetres": lambda d: write_dae(d / "box.dae", 0.001),
    "dae-inches": lambda d: write_dae(d / "box.dae", 0.0254),
    "dae-no-exact-inverse": lambda d: write_dae(d / "box.dae", 6.204411205854946),
}


def assert_identical(a: MeshSolid, b: MeshSolid) -> None:
    """Every field, with its type, dtype, shape, bits and writeability."""
    for field in dataclasses.fields(MeshSolid):
        x, y = getattr(a, field.name), getattr(b, field.name)
        if field.name == "moments":
            for name in ("volume", "first", "second", "origin"):
                assert_same(getattr(x, name), getattr(y, name), f"moments.{name}")
        else:
            assert_same(x, y, field.name)


# --- the same numbers ----------------------------------------------------------------------------


@pytest.mark.parametrize("kind", MESHES)
def test_miss_and_hit_equal_mesh_solid_bit_for_bit(
    tmp_path: Path, cache: Path, calls: list, kind: str
) -> None:
    path = MESHES[kind](tmp_path)
    for scale in SCALES:
        expected = mesh_solid(path, scale)
        assert_identical(cached_mesh_solid(path, scale), expected)
        assert_identical(cached_mesh_solid(path, scale), expected)
    if kind == "dae-no-exact-inverse":  # not cacheable exactly: computed every time
        assert not entries(cache)
    else:
        assert len(entries(cache)) == 1
        # one read for the entry (two for a file in another unit), then hits at every scale
        assert len(calls) == (2 if kind.startswith("dae") else 1)


def test_hit_applies_the_scale_without_reading(
    tmp_path: Path, cache: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    path = MESHES["binary-stl"](tmp_path)
    cached_mesh_solid(path)
    expected = {scale: mesh_solid(path, scale) for scale in SCALES}
    forbid_reading(monkeypatch)
    for scale in SCALES:
        solid = cached_mesh_solid(path, scale)
        assert_identical(solid, expected[scale])
        assert solid.scale == scale


def test_solids_from_one_entry_share_no_arrays(tmp_path: Path, cache: Path) -> None:
    path = MESHES["binary-stl"](tmp_path)
    a, b = cached_mesh_solid(path), cached_mesh_solid(path)
    for x, y in [(a.bounds, b.bounds), (a.moments.first, b.moments.first)]:
        assert not np.shares_memory(x, y)
    with pytest.raises(ValueError):
        a.bounds[0, 0] = 1.0


# --- invalidation ----------------------------------------------------------------------------


def test_rewrite_with_the_same_size_is_a_miss(tmp_path: Path, cache: Path, calls: list) -> None:
    path = write_binary_stl(tmp_path / "part.stl", tilted_box())
    before = cached_mesh_solid(path)
    size = path.stat().st_size
    write_binary_stl(path, tilted_box(size=(0.5, 0.2, 0.1)))
    assert path.stat().st_size == size  # binary STL: the size says only the triangle count

    after = cached_mesh_solid(path)

    assert len(calls) == 2
    assert after.volume != before.volume
    assert_identical(after, mesh_solid(path))
    assert len(entries(cache)) == 1  # the mesh's entry was replaced, not added to


def test_size_change_is_a_miss(tmp_path: Path, cache: Path, calls: list) -> None:
    path = write_binary_stl(tmp_path / "part.stl", tilted_box())
    cached_mesh_solid(path)
    write_binary_stl(path, tilted_box()[:-1])  # open now: convex hull

    assert_identical(cached_mesh_solid(path), mesh_solid(path))
    assert len(calls) == 2


def test_mtime_change_is_a_miss(tmp_path: Path, cache: Path, calls: list) -> None:
    path = MESHES["binary-stl"](tmp_path)
    cached_mesh_solid(path)
    status = path.stat()
    os.utime(path, ns=(status.st_atime_ns, status.st_mtime_ns - 10**9))
    cached_mesh_solid(path)
    cached_mesh_solid(path)
    assert len(calls) == 2


def test_a_file_changed_just_now_is_not_stored(
    tmp_path: Path, cache: Path, calls: list, monkeypatch: pytest.MonkeyPatch
) -> None:
    # a second write in the same timestamp tick would leave the key as it is
    monkeypatch.setattr(mesh_cache, "RACY_SECONDS", 3600.0)
    path = MESHES["binary-stl"](tmp_path)
    for _ in range(2):
        assert_identical(cached_mesh_solid(path), mesh_solid(path))
    assert (len(calls), entries(cache)) == (2, [])


def test_another_code_version_is_a_miss_and_both_are_kept(
    tmp_path: Path, cache: Path, calls: list, monkeypatch: pytest.MonkeyPatch
) -> None:
    path = MESHES["binary-stl"](tmp_path)
    cached_mesh_solid(path)
    monkeypatch.setattr(mesh_cache, "code_key", lambda: "format 1; inertia-kit 99.0")
    cached_mesh_solid(path)
    cached_mesh_solid(path)
    assert len(calls) == 2
    assert len(entries(cache)) == 2  # two installed versions sharing a cache do not thrash


def test_code_key_names_what_the_numbers_depend_on() -> None:
    key = mesh_cache.code_key()
    for part in ("format 1", "inertia-kit", "numpy", "polyhedra.py", "stl.py", "trimesh"):
        assert part in key


def test_symlinks_to_one_file_share_its_entry_and_a_retarget_is_a_miss(
    tmp_path: Path, cache: Path, calls: list
) -> None:
    a = write_binary_stl(tmp_path / "a.stl", tilted_box())
    b = write_binary_stl(tmp_path / "b.stl", tilted_box(size=(0.5, 0.2, 0.1)))
    first, second = tmp_path / "first.stl", tmp_path / "second.stl"
    first.symlink_to(a)
    second.symlink_to(a)
    cached_mesh_solid(first)
    solid = cached_mesh_solid(second)
    assert len(calls) == 1
    assert solid.path == str(second)  # the path as the caller named it, as mesh_solid says it

    second.unlink()
    second.symlink_to(b)
    assert_identical(cached_mesh_solid(second), mesh_solid(second))
    assert len(calls) == 2


# --- damaged entries ----------------------------------------------------------------------------


def reencode(transform):
    """Edit an entry's JSON and give it a valid checksum: a well-formed but foreign entry."""

    def damage(data: bytes) -> bytes:
        document = json.loads(data[9:-1])
        transform(document)
        body = json.dumps(document).encode()
        return b"%08x " % zlib.crc32(body) + body + b"\n"

    return damage


def _set(path: tuple, value):
    def edit(document):
        target = document
        for part in path[:-1]:
            target = target[part]
        target[path[-1]] = value

    return edit


DAMAGES = {
    "empty": lambda data: b"",
    "truncated": lambda data: data[: len(data) // 2],
    "last-byte-missing": lambda data: data[:-1],
    "garbage": lambda data: os.urandom(len(data)),
    "not-utf8": lambda data: data[:9] + b"\xff\xfe" + data[11:],
    "digit-flipped": lambda data: data.replace(b"0.", b"1.", 1),
    "oversized": lambda data: data + b" " * mesh_cache_entries.MAX_ENTRY_BYTES,
    "other-format": reencode(_set(("format",), 99)),
    "other-code": reencode(_set(("code",), "format 1; inertia-kit 0.0.1")),
    "other-file": reencode(_set(("key", "path"), "/elsewhere/box.stl")),
    "other-size": reencode(_set(("key", "size"), 1)),
    "volume-a-string": reencode(_set(("solid", "volume"), ["float64", "1.0"])),
    "first-too-short": reencode(_set(("solid", "first"), [1.0, 2.0])),
    "bounds-integers": reencode(_set(("solid", "bounds"), [0, 0, 0, 1, 1, 1])),
    "unknown-type": reencode(_set(("solid", "other", "closed"), ["complex", True])),
    "field-missing": reencode(lambda d: d["solid"]["other"].pop("method")),
    "field-added": reencode(_set(("solid", "other", "colour"), ["str", "red"])),
    "unit-zero": reencode(_set(("solid", "other", "unit_scale"), ["float", 0.0])),
    "a-list": reencode(lambda d: d.__setitem__("solid", [])),
}


@pytest.mark.parametrize("damage", DAMAGES)
def test_damaged_entry_is_recomputed_and_overwritten(
    tmp_path: Path, cache: Path, calls: list, damage: str
) -> None:
    path = MESHES["binary-stl"](tmp_path)
    expected = mesh_solid(path, (0.3, -2.0, 7.1))
    cached_mesh_solid(path)
    (entry,) = entries(cache)
    good = entry.read_bytes()
    entry.write_bytes(DAMAGES[damage](good))

    assert_identical(cached_mesh_solid(path, (0.3, -2.0, 7.1)), expected)

    assert len(calls) == 2
    assert entry.read_bytes() == good
    assert_identical(cached_mesh_solid(path, (0.3, -2.0, 7.1)), expected)
    assert len(calls) == 2


def test_unreadable_entry_is_ignored(tmp_path: Path, cache: Path, calls: list) -> None:
    path = MESHES["binary-stl"](tmp_path)
    cached_mesh_solid(path)
    (entry,) = entries(cache)
    entry.unlink()
    entry.mkdir()  # open() fails, and so does os.replace over it

    for _ in range(2):
        assert_identical(cached_mesh_solid(path), mesh_solid(path))
    assert len(calls) == 3
    assert not list(entry.parent.glob(".*.tmp"))


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes here")
def test_an_entry_that_is_a_named_pipe_is_ignored_without_blocking(
    tmp_path: Path, cache: Path, calls: list
) -> None:
    """A pipe planted in a cache others can write (scan's --mesh-cache on a cluster): opening
    it for reading waited for a writer for ever."""
    import threading

    path = MESHES["binary-stl"](tmp_path)
    cached_mesh_solid(path)
    (entry,) = entries(cache)
    entry.unlink()
    os.mkfifo(entry)
    found: list = []
    reader = threading.Thread(target=lambda: found.append(cached_mesh_solid(path)), daemon=True)
    reader.start()
    reader.join(timeout=30)
    assert found, "still reading the pipe after 30 s"
    assert_identical(found[0], mesh_solid(path))
    assert len(calls) == 2


# --- where, and when not ------------------------------------------------------------------------


def test_unwritable_location_only_means_no_caching(
    tmp_path: Path, calls: list, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(mesh_cache, "RACY_SECONDS", 0.0)
    blocker = tmp_path / "a-file"
    blocker.write_text("")
    path = MESHES["binary-stl"](tmp_path)
    for folder in [blocker / "cache", blocker]:
        assert_identical(cached_mesh_solid(path, cache_dir=folder), mesh_solid(path))
    assert len(calls) == 2


@pytest.mark.skipif(
    not hasattr(os, "geteuid") or os.geteuid() == 0, reason="root writes to read-only folders"
)
def test_read_only_location_only_means_no_caching(
    tmp_path: Path, calls: list, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(mesh_cache, "RACY_SECONDS", 0.0)
    folder = tmp_path / "cache"
    (folder / f"meshes-v{mesh_cache_entries.FORMAT}").mkdir(parents=True)
    path = MESHES["binary-stl"](tmp_path)
    for mode in (0o500, 0o000):
        (folder / f"meshes-v{mesh_cache_entries.FORMAT}").chmod(mode)
        try:
            assert_identical(cached_mesh_solid(path, cache_dir=folder), mesh_solid(path))
        finally:
            (folder / f"meshes-v{mesh_cache_entries.FORMAT}").chmod(0o700)
    assert len(calls) == 2


@pytest.mark.parametrize("error", [PermissionError, OSError])  # EACCES/EROFS, ENOSPC, ...
def test_failing_writes_only_mean_no_caching(
    tmp_path: Path, cache: Path, calls: list, monkeypatch: pytest.MonkeyPatch, error: type
) -> None:
    def refuse(*args, **kwargs):
        raise error(13, "refused")

    monkeypatch.setattr(mesh_cache_entries, "_create", refuse)  # what root cannot be made to see
    monkeypatch.setattr(mesh_cache_entries.os, "makedirs", refuse)
    path = MESHES["binary-stl"](tmp_path)
    for _ in range(2):
        assert_identical(cached_mesh_solid(path), mesh_solid(path))
    assert len(calls) == 2


@pytest.mark.parametrize("value", ["1", "true", "yes"])
def test_disabled_by_environment(
    tmp_path: Path, cache: Path, calls: list, monkeypatch: pytest.MonkeyPatch, value: str
) -> None:
    monkeypatch.setenv(mesh_cache.ENV_DISABLE, value)
    path = MESHES["binary-stl"](tmp_path)
    for folder in (None, tmp_path / "explicit"):
        for _ in range(2):
            assert_identical(cached_mesh_solid(path, cache_dir=folder), mesh_solid(path))
    assert len(calls) == 4
    assert not cache.exists() and not (tmp_path / "explicit").exists()


@pytest.mark.parametrize("value", ["", "0", "false", "off"])
def test_not_disabled_by_a_false_value(
    tmp_path: Path, cache: Path, monkeypatch: pytest.MonkeyPatch, value: str
) -> None:
    monkeypatch.setenv(mesh_cache.ENV_DISABLE, value)
    cached_mesh_solid(MESHES["binary-stl"](tmp_path))
    assert len(entries(cache)) == 1


def test_location(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    for name in (mesh_cache.ENV_DIR, mesh_cache.ENV_DISABLE, "XDG_CACHE_HOME"):
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert cache_location() == tmp_path / "home" / ".cache" / "inertia-kit"
    monkeypatch.setenv("XDG_CACHE_HOME", "relative/is/ignored")
    assert cache_location() == tmp_path / "home" / ".cache" / "inertia-kit"
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert cache_location() == tmp_path / "xdg" / "inertia-kit"
    monkeypatch.setenv(mesh_cache.ENV_DIR, str(tmp_path / "mine"))
    assert cache_location() == tmp_path / "mine"
    assert cache_location(tmp_path / "given") == tmp_path / "given"
    monkeypatch.setenv(mesh_cache.ENV_DISABLE, "1")
    assert cache_location(tmp_path / "given") is None


def test_default_location_is_used(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, cache: Path
) -> None:
    monkeypatch.delenv(mesh_cache.ENV_DIR)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    cached_mesh_solid(MESHES["binary-stl"](tmp_path))
    assert len(entries(tmp_path / "xdg" / "inertia-kit")) == 1
    assert (
        (tmp_path / "xdg" / "inertia-kit" / "CACHEDIR.TAG")
        .read_text()
        .startswith("Signature: 8a477f597d28d172789f06886806bc55")
    )


# --- errors -------------------------------------------------------------------------------------


def _write(name: str, data: bytes | None):
    def make(tmp_path: Path) -> Path:
        path = tmp_path / name
        if data is not None:
            path.write_bytes(data)
        return path

    return make


def _folder(path: Path) -> Path:
    path.mkdir()
    return path


BAD_FILES = {
    "missing": _write("missing.stl", None),
    "directory": lambda tmp_path: tmp_path,
    "directory-named-stl": lambda tmp_path: _folder(tmp_path / "folder.stl"),
    "unsupported": _write("part.step", b"ISO-10303-21;\n"),
    "garbage-stl": _write("part.stl", b"\x00\x01 not an stl at all"),
    "empty-stl": _write("empty.stl", b""),
    "no-triangles-stl": _write("none.stl", bytes(80) + (0).to_bytes(4, "little")),
    "garbage-dae": _write("part.dae", b"<COLLADA><unclosed"),
}


@pytest.mark.parametrize("case", BAD_FILES)
def test_errors_are_those_of_mesh_solid_and_not_cached(
    tmp_path: Path, cache: Path, calls: list, case: str
) -> None:
    path = BAD_FILES[case](tmp_path)
    with pytest.raises(MeshError) as expected:
        mesh_solid(path)
    for attempt in (1, 2):
        with pytest.raises(MeshError) as caught:
            cached_mesh_solid(path)
        error, reference = caught.value, expected.value
        assert (error.path, error.kind, error.message) == (
            reference.path,
            reference.kind,
            reference.message,
        )
        assert error.__cause__ is None
        assert len(calls) == attempt
    assert not entries(cache)


@pytest.mark.parametrize("scale", [(1.0, 0.0, 1.0), (1.0, 1.0), (1.0, float("nan"), 1.0), "x"])
def test_bad_scale_is_the_same_value_error(tmp_path: Path, cache: Path, scale) -> None:
    path = MESHES["binary-stl"](tmp_path)
    cached_mesh_solid(path)  # a valid entry exists: the scale is refused all the same
    with pytest.raises(ValueError) as expected:
        mesh_solid(path, scale)
    with pytest.raises(ValueError) as caught:
        cached_mesh_solid(path, scale)
    assert str(caught.value) == str(expected.value)


def test_missing_file_after_caching_is_not_found(tmp_path: Path, cache: Path) -> None:
    path = MESHES["binary-stl"](tmp_path)
    cached_mesh_solid(path)
    path.unlink()
    with pytest.raises(MeshError, match="does not exist"):
        cached_mesh_solid(path)


# --- processes ----------------------------------------------------------------------------------


def _solve(arguments) -> bytes:
    """In a worker: the solid's moments and bounds as bytes, through the cache."""
    path, folder, barrier = arguments
    mesh_cache.RACY_SECONDS = 0.0
    if barrier is not None:
        barrier.wait()
    solid = cached_mesh_solid(path, (0.3, -2.0, 7.1), cache_dir=folder)
    m = solid.moments
    return b"".join(np.asarray(v).tobytes() for v in (m.volume, m.first, m.second, solid.bounds))


def _rewrite_and_read(arguments) -> int:
    """In a worker: install the same entry again and again while reading it; count bad reads."""
    entry, payload, key, code, rounds = arguments
    bad = 0
    for _ in range(rounds):
        mesh_cache_entries.write_entry(os.path.dirname(os.path.dirname(entry)), entry, payload)
        bad += mesh_cache_entries.read_entry(entry, key, code) is None
    return bad


def _context():
    methods = multiprocessing.get_all_start_methods()
    return multiprocessing.get_context("fork" if "fork" in methods else "spawn")


def test_concurrent_writers_of_one_entry(tmp_path: Path, cache: Path) -> None:
    path = MESHES["binary-stl"](tmp_path)
    context = _context()
    workers = 6
    with context.Manager() as manager:
        barrier = manager.Barrier(workers)
        with context.Pool(workers) as pool:
            results = pool.map(_solve, [(str(path), str(cache), barrier)] * workers)
    solid = mesh_solid(path, (0.3, -2.0, 7.1))
    expected = b"".join(
        np.asarray(v).tobytes()
        for v in (solid.moments.volume, solid.moments.first, solid.moments.second, solid.bounds)
    )
    assert results == [expected] * workers
    folder = cache / f"meshes-v{mesh_cache_entries.FORMAT}"
    assert len(entries(cache)) == 1
    assert not list(folder.glob(".*.tmp"))


def test_readers_never_see_a_partial_entry(tmp_path: Path, cache: Path) -> None:
    path = MESHES["binary-stl"](tmp_path)
    cached_mesh_solid(path)
    (entry,) = entries(cache)
    key = mesh_cache._key(path)
    code = mesh_cache.code_key()
    payload = entry.read_bytes()
    with _context().Pool(4) as pool:
        bad = pool.map(_rewrite_and_read, [(str(entry), payload, key, code, 200)] * 4)
    assert bad == [0, 0, 0, 0]
    assert entry.read_bytes() == payload
    assert not list(entry.parent.glob(".*.tmp"))


def test_hit_imports_no_trimesh_and_reads_no_mesh(tmp_path: Path, cache: Path) -> None:
    path = MESHES["dae-millimetres"](tmp_path)  # a miss needs trimesh
    scale = (0.3, -2.0, 7.1)
    cached_mesh_solid(path)
    solid = mesh_solid(path, scale)
    code = (
        "import sys\n"
        "from inertia_kit.physics import mesh_cache\n"
        "def fail(*args):\n"
        "    raise SystemExit('read the mesh on a hit')\n"
        "mesh_cache.mesh_solid = fail\n"
        f"solid = mesh_cache.cached_mesh_solid({str(path)!r}, {scale!r})\n"
        "print(solid.moments.second.tobytes().hex(), solid.method, solid.unit_scale)\n"
        "heavy = ('trimesh', 'manifold3d', 'lxml', 'collada')\n"
        "print(sorted(m for m in heavy if m in sys.modules))\n"
    )
    env = {**os.environ, "PYTHONPATH": str(ROOT), mesh_cache.ENV_DIR: str(cache)}
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True
    )
    numbers, imported = done.stdout.splitlines()
    assert numbers.split() == [solid.moments.second.tobytes().hex(), "exact", "0.001"]
    assert imported == "[]"


# --- size ---------------------------------------------------------------------------------------


def test_a_writing_process_prunes_once(
    tmp_path: Path, cache: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(mesh_cache_entries, "MAX_ENTRIES", 2)
    monkeypatch.setattr(mesh_cache_entries, "_pruned", set())
    old = cache / f"meshes-v{mesh_cache_entries.FORMAT}"
    old.mkdir(parents=True)
    for name in ("a", "b", "c"):
        (old / f"{name}.json").write_text("{}")
        os.utime(old / f"{name}.json", (1e9, 1e9))
    cached_mesh_solid(MESHES["binary-stl"](tmp_path))
    assert [p.name.split("-")[0] for p in entries(cache)] == ["box.stl"]


def test_hit_refreshes_an_old_entry(tmp_path: Path, cache: Path) -> None:
    path = MESHES["binary-stl"](tmp_path)
    cached_mesh_solid(path)
    (entry,) = entries(cache)
    os.utime(entry, (1e9, 1e9))
    cached_mesh_solid(path)
    assert time.time() - entry.stat().st_mtime < 600


def test_every_module_that_computes_a_mesh_invalidates_the_cache():
    """A change to any physics module a mesh's computation runs (each format's reader, the
    closure, the hull) must invalidate the cached numbers: each is in the code key's sources."""
    import subprocess
    import sys

    code = r"""
import sys, tempfile
from pathlib import Path
from kit.meshes import box_triangles, obj, write_binary_stl
from kit.meshes import write_textured_collada
folder = Path(tempfile.mkdtemp())
write_binary_stl(folder / "a.stl", box_triangles((1, 2, 3)))
write_binary_stl(folder / "open.stl", box_triangles((1, 2, 3))[1:])
(folder / "a.obj").write_text(obj(box_triangles((1, 2, 3))))
write_textured_collada(folder / "a.dae", box_triangles((1, 2, 3)), image=False)
from inertia_kit.physics.meshes import mesh_solid
for name in ("a.stl", "open.stl", "a.obj", "a.dae"):
    mesh_solid(folder / name)
print(" ".join(m for m in sys.modules if m.startswith("inertia_kit.physics.")))
"""
    tests = str(Path(__file__).resolve().parents[1])
    done = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        check=True,
        env={**os.environ, "PYTHONPATH": tests + os.pathsep + os.environ.get("PYTHONPATH", "")},
    )
    used = {name.rsplit(".", 1)[1] + ".py" for name in done.stdout.split()}
    assert used - set(mesh_cache._SOURCES) == set()
