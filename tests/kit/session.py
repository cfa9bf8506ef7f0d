"""
Setup made once for the whole test session, however many pytest-xdist workers run it: a
folder the first worker to ask makes, under a lock the others wait on, then all share.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path


def shared_folder(tmp_path_factory, name: str, make: Callable[[Path], None]) -> Path:
    """
    The folder ``name``, filled by ``make(folder)`` once in this session: in the session's
    temporary root, which every xdist worker's own root sits in (else, without xdist or
    without ``fcntl``, this process's root). A folder ``make`` left unfinished (it raised) is
    made again.
    """
    own = tmp_path_factory.getbasetemp()
    try:
        import fcntl
    except ImportError:  # no lock to share it with: this worker makes its own
        fcntl = None
    root = own.parent if fcntl is not None and os.environ.get("PYTEST_XDIST_WORKER") else own
    folder = root / name
    with open(root / f"{name}.lock", "w") as lock:
        if fcntl is not None:
            fcntl.flock(lock.fileno(), fcntl.LOCK_EX)
        done = root / f"{name}.done"
        if not done.exists():
            if folder.exists():
                from kit import remove_tree

                remove_tree(folder)
            folder.mkdir()
            make(folder)
            done.touch()
    return folder
