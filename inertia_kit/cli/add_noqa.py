"""
``inertia-lint --add-noqa``: write a suppression comment for every current finding, so that a
repository adopts the linter today and only new findings fail (ruff's ``--add-noqa``).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from inertia_kit.cli.printing import say, show

if TYPE_CHECKING:
    from inertia_kit.lint.runner import FileResult

# installed packages: their macros are not ours to annotate
_INSTALLED = ("site-packages", "dist-packages")


def writable_under(paths: Sequence[str]) -> Callable[[str], bool]:
    """
    Which files ``--add-noqa`` may edit: those under a folder given (for a file given, its
    folder; and the current folder when every path given lies in it), never inside an
    installed package or a hidden folder (``.venv``).
    """
    here = Path.cwd().resolve()
    given = [_standing(p) for p in paths]
    roots = [p if os.path.isdir(p) else p.parent for p in given]
    if all(p.is_relative_to(here) for p in given):
        roots.append(here)

    def writable(path: str) -> bool:
        file = _standing(path)
        for root in roots:
            if file.is_relative_to(root):
                inside = file.relative_to(root).parts[:-1]
                return not any(p in _INSTALLED or p.startswith(".") for p in inside)
        return False

    return writable


def _standing(path: str) -> Path:
    """
    Where ``path`` stands: a folder resolved, a file in its resolved folder. A symbolic link
    counts where it stands, not where it points: one out of its repository is refused for
    writing (:mod:`~inertia_kit.lint.repository_links`), given or found by a folder walk.
    """
    if os.path.isdir(path):
        return Path(path).resolve()
    return Path(os.path.realpath(os.path.dirname(os.path.abspath(path)))) / Path(path).name


def add_noqa(
    paths: Sequence[str],
    results: Sequence[FileResult],
    relint: Callable[[], list[FileResult]],
    quiet: bool = False,
    follow_symlinks: bool = False,
    diff: bool = False,
) -> int:
    """
    Write the comments, lint again to prove them, say what was done (``quiet``: only errors and
    the findings that still fail); the exit code. A file that is a symbolic link out of its
    repository is not written (nor any other), unless ``follow_symlinks``. ``diff``: print the
    comments as a unified diff instead and write nothing (exit 1 when there is one).
    """
    from inertia_kit.description.edits import write_all_atomic
    from inertia_kit.description.reads import combined
    from inertia_kit.errors import InputError
    from inertia_kit.lint.add_noqa import plan
    from inertia_kit.lint.merge import merge
    from inertia_kit.lint.repository_links import refuse_links_out

    run = merge(results)
    try:
        # placed in the text each robot's lint read (else: changed meanwhile, nothing written)
        reads = combined(r.reads for r in results)
        planned = plan(run.findings, writable_under(paths), reads)
        if diff:
            from inertia_kit.description.edits import unified_diff

            shown = unified_diff(
                (os.path.relpath(p), old.text, new) for p, (old, new) in planned.texts.items()
            )
            show(shown, nl=False)  # redacted, as lint's --diff
            return 1 if shown else 0
        writes = [(p, old.encode(new), old.original) for p, (old, new) in planned.texts.items()]
        refuse_links_out([path for path, _, _ in writes], follow_symlinks)
        # the comments are for the findings of the files as read: any of them saved since
        # by another writer (an included xacro --fix edited) makes them stale
        write_all_atomic(writes, unchanged=reads)
    except InputError as error:
        say(f"error: {error}")  # it says what was left as it was
        return 2
    total = sum(planned.added.values())
    where = "" if not total else f" in {_count(len(planned.added), 'file')}"
    extended = "" if not planned.extended else f" ({planned.extended} already there, given codes)"
    if not quiet:
        say(f"Added {_count(total, 'suppression comment')}{extended}{where}.")
        for path, count in planned.added.items():
            say(f"  {os.path.relpath(path)}: {count}")
        for finding, why in planned.skipped:
            line = "" if finding.line is None else f":{finding.line}"
            say(f"note: {finding.path}{line}: {finding.code} not suppressed: {why}")
    relint_results = relint() if writes else list(results)
    after = merge(relint_results)
    for level, text in after.messages:
        if not (quiet and level == "note"):
            say(f"{level}: {text}")
    if after.errors:
        return 2
    if after.failing:
        left = [f for f in after.findings if any(f in r.failing for r in relint_results)]
        for finding in left:
            line = "" if finding.line is None else f":{finding.line}"
            say(f"  {finding.path}{line}: {finding.code} {finding.name}")
        say(f"{_count(len(left), 'finding')} still fail `inertia-lint`")
        return 1
    return 0


def _count(n: int, noun: str) -> str:
    return f"{n} {noun}{'' if n == 1 else 's'}"
