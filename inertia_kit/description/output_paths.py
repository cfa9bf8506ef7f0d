"""
Where a named output file (``-o``, ``--output-file``, ``--png``) may be written: not through a
symbolic link in the tree, unless the user asks (``--follow-symlinks``).

A repository a pull request changes can hold ``results.sarif -> ../ci/deploy.sh``; a CI job
that then writes its report to ``results.sarif`` would replace the script (keeping its execute
bit). So an output path is refused when it is itself a symbolic link (one that leads nowhere
too), or when a folder on its way is one (``reports -> /etc`` for ``-o reports/x.sarif``):
every part of the path as written, for a relative path, and the parts below the working folder
for an absolute one (the folders above it are the user's own: ``/tmp`` is a link on macOS).
The write itself then replaces the name given, never what a link planted meanwhile points to
(``write_atomic(follow_symlinks=False)``).
"""

from __future__ import annotations

import os
from pathlib import Path

from inertia_kit.errors import InputError

#: the option that asks to write through links, as every writing command names it
FOLLOW_OPTION = "--follow-symlinks"


def link_on_the_way(path: str | Path) -> tuple[str, str, bool] | None:
    """
    The first symbolic link among the parts of ``path`` looked at (see the module), as
    ``(the link as written, what it points to, whether it is the file itself)``; ``None``
    when there is none.
    """
    written = os.fspath(path)
    here = os.getcwd().rstrip(os.sep)
    if not os.path.isabs(written):
        base, rest = "", written
    elif written.startswith(here + os.sep):
        base, rest = here, written[len(here) + 1 :]
    else:  # outside the working folder: only the file itself
        base, rest = os.path.dirname(written), os.path.basename(written)
    parts = [part for part in rest.split(os.sep) if part not in ("", os.curdir)]
    current = base
    for number, part in enumerate(parts, 1):
        current = os.path.join(current, part)
        if os.path.islink(current):
            try:
                target = os.readlink(current)
            except OSError:
                target = "?"
            return current, target, number == len(parts)
    return None


def refuse_links(path: str | Path, follow: bool) -> None:
    """``InputError`` (nothing written) when ``path`` is, or passes through, a symbolic link
    and ``follow`` (``--follow-symlinks``) is off."""
    if follow:
        return
    found = link_on_the_way(path)
    if found is None:
        return
    link, target, itself = found
    what = (
        f"is a symbolic link to {target}"
        if itself
        else f"passes through {link}, a symbolic link to {target}"
    )
    raise InputError(f"{what}: not written; {FOLLOW_OPTION} writes through it", path)
