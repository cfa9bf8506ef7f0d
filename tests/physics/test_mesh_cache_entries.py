"""
The mesh cache's entries: every float survives an entry bit for bit, and pruning keeps the most
recently used. (Damaged entries, atomic writes and the entries a process writes are tested
through the cache itself, in test_mesh_cache.)
"""

from __future__ import annotations

import os
import time
from pathlib import Path

import numpy as np
from kit.physics import assert_same

from inertia_kit.physics.mesh_cache_entries import UnscaledSolid, decode, encode, prune
from inertia_kit.physics.volume_moments import VolumeMoments


def test_special_floats_survive_an_entry() -> None:
    special = [-0.0, 5e-324, 1.7976931348623157e308, 0.1, 1 / 3, -2.5e-300]
    moments = VolumeMoments(
        np.float64(-0.0),
        np.array(special[:3]),
        np.array(special * 2)[:9].reshape(3, 3),
        np.zeros(3),
    )
    other = {
        "method": "exact",
        "inverted": False,
        "closed": True,
        "volume_error": np.float64(float("inf")),
        "triangle_count": 7,
        "unit_scale": 0.0254,
    }
    raw = UnscaledSolid(moments, np.array(special).reshape(2, 3), other)
    key = {"path": "/x.stl", "suffix": ".stl", "size": 1, "mtime_ns": 2, "ctime_ns": 3, "inode": 4}
    data = encode(key, "code", raw)
    assert data is not None
    back = decode(data, key, "code")
    for name in ("volume", "first", "second", "origin"):
        assert_same(getattr(back.moments, name), getattr(moments, name), name)
    assert_same(back.bounds, raw.bounds, "bounds")
    for name, value in other.items():
        assert_same(back.other[name], value, name)


def test_prune_keeps_the_most_recently_used(tmp_path: Path) -> None:
    folder = tmp_path / "entries"
    folder.mkdir()
    now = time.time()
    for age in range(10):
        entry = folder / f"m{age}.json"
        entry.write_text("{}")
        os.utime(entry, (now - 60 * age, now - 60 * age))
    old, fresh = folder / ".a.json.1.tmp", folder / ".b.json.2.tmp"
    for temporary, age in [(old, 7200), (fresh, 10)]:
        temporary.write_text("")
        os.utime(temporary, (now - age, now - age))

    assert prune(folder, max_entries=5) == 7  # down to 90 %: 4 left, and one .tmp

    assert sorted(p.name for p in folder.iterdir()) == [
        ".b.json.2.tmp",
        "m0.json",
        "m1.json",
        "m2.json",
        "m3.json",
    ]
    assert prune(folder, max_entries=5) == 0
