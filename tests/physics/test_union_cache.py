"""
The on-disk cache of overlapping primitives' unions: the same results as ``union``, bit for
bit, without manifold3d on a hit, and never a failure because of the cache itself.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from kit import REPO

from inertia_kit.physics import union_cache, unions
from inertia_kit.physics.mesh_cache import ENV_DIR, ENV_DISABLE
from inertia_kit.physics.union_cache import cached_union
from inertia_kit.physics.unions import Part, UnionResult, union


def capsule_parts(length: float = 0.3) -> list[Part]:
    """A capsule as franka_ros' self-collision links build one: a cylinder and two spheres."""
    radius = 0.06

    def at(z: float) -> np.ndarray:
        pose = np.eye(4)
        pose[2, 3] = z
        return pose

    return [
        Part.cylinder(radius, length, at(0.1)),
        Part.sphere(radius, at(0.1 - length / 2)),
        Part.sphere(radius, at(0.1 + length / 2)),
    ]


def assert_identical(a: UnionResult, b: UnionResult) -> None:
    assert a.mass_properties.mass == b.mass_properties.mass
    assert a.mass_properties.com.tobytes() == b.mass_properties.com.tobytes()
    assert a.mass_properties.inertia.tobytes() == b.mass_properties.inertia.tobytes()
    assert (a.volume, a.parts_volume, a.overlap_volume, a.exact) == (
        b.volume,
        b.parts_volume,
        b.overlap_volume,
        b.exact,
    )


def entries(cache: Path) -> list[Path]:
    return sorted(cache.glob(f"unions-v{union_cache.FORMAT}/*.json"))


@pytest.fixture
def computed(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """Counts the unions computed (rather than read from the cache)."""
    calls: list[int] = []
    real = union_cache.union

    def counting(*args, **kwargs):
        calls.append(1)
        return real(*args, **kwargs)

    monkeypatch.setattr(union_cache, "union", counting)
    return calls


def test_a_hit_is_the_union_bit_for_bit(tmp_path: Path, computed: list[int]) -> None:
    parts = capsule_parts()
    expected = union(parts, density=1.0)
    assert expected.overlap_volume > 0  # the spheres overlap the cylinder: manifold3d's case
    first = cached_union(parts, density=1.0, cache_dir=tmp_path)
    second = cached_union(parts, density=1.0, cache_dir=tmp_path)
    assert computed == [1]
    assert len(entries(tmp_path)) == 1
    assert_identical(first, expected)
    assert_identical(second, expected)
    # at a mass the same union is another entry
    by_mass = cached_union(parts, mass=2.5, cache_dir=tmp_path)
    assert_identical(by_mass, union(parts, mass=2.5))
    assert len(entries(tmp_path)) == 2


def test_a_moved_part_is_another_entry(tmp_path: Path, computed: list[int]) -> None:
    cached_union(capsule_parts(0.3), density=1.0, cache_dir=tmp_path)
    moved = capsule_parts(0.31)
    assert_identical(
        cached_union(moved, density=1.0, cache_dir=tmp_path), union(moved, density=1.0)
    )
    assert computed == [1, 1]


def test_parts_that_do_not_meet_and_meshes_are_not_stored(tmp_path: Path) -> None:
    apart = [Part.sphere(0.1), Part.sphere(0.1, np.diag([1.0, 1.0, 1.0, 1.0]) + _x(1.0))]
    assert_identical(
        cached_union(apart, density=1.0, cache_dir=tmp_path), union(apart, density=1.0)
    )
    box = Part.box((0.2, 0.2, 0.2))
    tessellated = Part.mesh(*box.tessellation())
    meshes = [tessellated, Part.sphere(0.1)]
    assert_identical(
        cached_union(meshes, density=1.0, cache_dir=tmp_path), union(meshes, density=1.0)
    )
    assert entries(tmp_path) == []


def _x(offset: float) -> np.ndarray:
    shift = np.zeros((4, 4))
    shift[0, 3] = offset
    return shift


def test_cache_off_and_damaged_entries(
    tmp_path: Path, computed: list[int], monkeypatch: pytest.MonkeyPatch
) -> None:
    parts = capsule_parts()
    monkeypatch.setenv(ENV_DISABLE, "1")
    cached_union(parts, density=1.0, cache_dir=tmp_path)
    assert entries(tmp_path) == []
    monkeypatch.delenv(ENV_DISABLE)
    cached_union(parts, density=1.0, cache_dir=tmp_path)
    (entry,) = entries(tmp_path)
    whole = entry.read_bytes()
    for damaged in (
        whole[:-20] + b"\n",
        bytes([whole[0] ^ 1]) + whole[1:],
        b"",
        whole.replace(b"1", b"2", 1),
    ):
        entry.write_bytes(damaged)
        assert_identical(
            cached_union(parts, density=1.0, cache_dir=tmp_path), union(parts, density=1.0)
        )
        assert entry.read_bytes() == whole  # recomputed and written again
    assert len(computed) == 6


def test_errors_are_the_union_s_and_not_stored(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="exactly one of density"):
        cached_union(capsule_parts(), cache_dir=tmp_path)
    with pytest.raises(ValueError, match="no parts"):
        cached_union([], density=1.0, cache_dir=tmp_path)
    assert entries(tmp_path) == []


def test_a_hit_imports_no_manifold3d(tmp_path: Path) -> None:
    cached_union(capsule_parts(), density=1.0, cache_dir=tmp_path)
    code = (
        "import sys\n"
        "from inertia_kit.physics import unions\n"
        "def fail(*args):\n"
        "    raise SystemExit('united the parts on a hit')\n"
        "unions._overlap_corrected = fail\n"
        "sys.path.insert(0, 'tests/physics')\n"
        "from test_union_cache import capsule_parts\n"
        "from inertia_kit.physics.union_cache import cached_union\n"
        "result = cached_union(capsule_parts(), density=1.0)\n"
        "print(result.overlap_volume > 0, 'manifold3d' in sys.modules)\n"
    )
    env = {
        **os.environ,
        "PYTHONPATH": f"{REPO}{os.pathsep}{REPO / 'tests'}",
        ENV_DIR: str(tmp_path),
    }
    env.pop(ENV_DISABLE, None)
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=REPO
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["True", "False"]
    assert unions.DEFAULT_SEGMENTS == union_cache.DEFAULT_SEGMENTS
