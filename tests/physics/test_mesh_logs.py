"""
trimesh's and pycollada's logs while we read a mesh: kept from a library user's handlers and the
terminal, passed on to our own logger at DEBUG, one line without traceback; no global logging
setting changes, and other threads keep theirs. COLLADA itself is read without them now
(physics.collada); their reading of it (``_read_scene``, the path PLY, GLB and glTF take) is
what logs here. The real `inertia-lint` is checked in tests/cli/test_cli_lint_logs.py.
"""

from __future__ import annotations

import logging
import threading
from pathlib import Path

import pytest
from kit.meshes import box_triangles, write_textured_collada

from inertia_kit.physics.mesh_formats import _read_scene, library_logs_quiet, read_surface
from inertia_kit.physics.polyhedra import integrate

SIZE = (0.1, 0.2, 0.3)  # 0.006 m³: 6 kg at the default 1000 kg/m³


def textured_part(folder: Path, *, image: bool) -> Path:
    return write_textured_collada(folder / "part.dae", box_triangles(SIZE), image=image)


def logging_state() -> list:
    library = [logging.getLogger(n) for n in ("trimesh", "trimesh.util", "collada")]
    return [
        logging.root.level,
        list(logging.root.handlers),
        logging.root.manager.disable,
        [(lg.level, lg.propagate, list(lg.handlers), lg.disabled) for lg in library],
    ]


def test_library_records_reach_our_debug_log_only(tmp_path: Path, caplog):
    """caplog is a user's handler on the root logger, at DEBUG: trimesh's records (with their
    tracebacks) do not reach it while we read; ours says what happened, in one line."""
    path = textured_part(tmp_path, image=False)
    import trimesh  # noqa: F401 - its loggers exist before the state is taken

    before = logging_state()
    with caplog.at_level(logging.DEBUG):
        triangles, unit = _read_scene(path, ".dae")

    assert unit == 1.0
    volume = integrate(triangles).moments.volume
    assert volume == pytest.approx(0.006, rel=1e-6)  # float32 in the file
    assert [r for r in caplog.records if r.name.split(".")[0] in ("trimesh", "collada")] == []
    ours = [r for r in caplog.records if r.name == "inertia_kit.physics.mesh_formats"]
    assert any("unable to load bumpmap (FileNotFoundError: skin.png)" in r.message for r in ours)
    assert all(r.levelno == logging.DEBUG and r.exc_info is None for r in ours)
    assert logging_state() == before

    # outside a read, trimesh's records reach the user's handlers as before
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        logging.getLogger("trimesh.util").warning("a user's own trimesh call")
    assert [r.message for r in caplog.records] == ["a user's own trimesh call"]


def test_our_collada_reader_logs_nothing(tmp_path: Path, caplog):
    """The same textured part read as the linter reads it: no library, nothing logged."""
    path = textured_part(tmp_path, image=False)
    with caplog.at_level(logging.DEBUG):
        integrator, _, unit, _ = read_surface(path)
    assert (unit, integrator.moments.volume) == (1.0, pytest.approx(0.006, rel=1e-6))
    assert caplog.records == []


def test_other_threads_keep_their_library_logs(tmp_path: Path, caplog):
    """The quiet is the reading thread's only: trimesh used meanwhile in another thread logs."""
    import trimesh  # noqa: F401

    logger = logging.getLogger("trimesh.util")
    with caplog.at_level(logging.WARNING), library_logs_quiet(tmp_path / "part.dae"):
        logger.warning("from the reading thread")
        other = threading.Thread(target=logger.warning, args=("from another thread",))
        other.start()
        other.join()
    assert [r.message for r in caplog.records] == ["from another thread"]
