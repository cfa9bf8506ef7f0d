"""
Robot files are written inside their repository: a file about to be edited in place
(``inertia-fill``, ``inertia-lint --fix``, ``--add-noqa``; given by name, found by a folder
walk, or included) that is a symbolic link whose target lies outside the repository holding the
link (:func:`~inertia_kit.lint.fragments.repository_root`: the git top level, else the
configuration's folder, the package root, the file's folder) is refused, and nothing is
written, unless the user asks with ``--follow-symlinks``.

A pull request can add ``urdf/robot.urdf -> ../../../.bashrc``, or a link into another
checkout, for a hook to edit. A link within the repository is written through, the link kept;
so is one in the install space of a colcon workspace (an ``install`` folder holding colcon's
``.colcon_install_layout``) to a file of that workspace: what ``colcon build
--symlink-install`` makes, and a pull request cannot reach above the folder holding
``install``.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from pathlib import Path

from inertia_kit.description.output_paths import FOLLOW_OPTION
from inertia_kit.errors import InputError


def link_out(path: str | Path) -> InputError | None:
    """Why ``path`` must not be written through (a link out of its repository), or ``None``."""
    from inertia_kit.lint.fragments import repository_root

    if not os.path.islink(path):
        return None
    root, why = repository_root(path)
    real = Path(os.path.realpath(path))
    workspace = _colcon_workspace(path)
    for inside in (root, workspace):
        if inside is not None and real.is_relative_to(os.path.realpath(inside)):
            return None
    return InputError(
        f"is a symbolic link to {real}, outside its repository {root}, {why}: not written; "
        f"{FOLLOW_OPTION} writes through it",
        path,
    )


def refuse_links_out(paths: Iterable[str | Path], follow: bool) -> None:
    """``InputError`` for the first of ``paths`` that links out of its repository (unless
    ``follow``): checked before any of them is written."""
    if follow:
        return
    for path in paths:
        error = link_out(path)
        if error is not None:
            raise error


def _colcon_workspace(path: str | Path) -> Path | None:
    """The colcon workspace whose install space holds ``path`` (as written), if it does."""
    for folder in Path(os.path.abspath(path)).parents:
        if folder.name == "install" and (folder / ".colcon_install_layout").is_file():
            return folder.parent
    return None
