"""
The file-discovery options ``inertia-lint`` and ``inertia-fill`` share (ruff's): ``--exclude``,
``--extend-exclude``, ``--[no-]respect-gitignore``, ``--[no-]force-exclude``, ``--show-files``.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import click

from inertia_kit.cli.options import UsageError

_OPTIONS = (
    click.option(
        "--exclude",
        multiple=True,
        metavar="PATTERNS",
        help="Paths the folder walk leaves out: gitignore-style patterns relative to the "
        "current folder, comma-separated (repeatable). Replaces the configured `exclude` and "
        "the defaults (hidden folders, __pycache__, a colcon workspace's build/ install/ log/).",
    ),
    click.option(
        "--extend-exclude",
        multiple=True,
        metavar="PATTERNS",
        help="Like --exclude, but added to the configured `exclude` (or the defaults).",
    ),
    click.option(
        "--respect-gitignore/--no-respect-gitignore",
        default=None,
        help="Leave out what .gitignore files and .git/info/exclude ignore [default: "
        "respect-gitignore in the configuration, else yes].",
    ),
    click.option(
        "--force-exclude/--no-force-exclude",
        default=None,
        help="Apply the exclusions to files given by name too, as pre-commit hands them over "
        "[default: force-exclude in the configuration, else no].",
    ),
    click.option(
        "--show-files",
        is_flag=True,
        help="Print the files that would be processed, one per line, in order, and exit 0.",
    ),
)
#: the names these options are passed to the command's function under
NAMES = ("exclude", "extend_exclude", "respect_gitignore", "force_exclude", "show_files")


def discovery_options(command: Callable[..., Any]) -> Callable[..., Any]:
    """Add the discovery options to a click command."""
    for option in reversed(_OPTIONS):
        command = option(command)
    return command


def _patterns(option: str, values: Sequence[str]) -> list[str]:
    from inertia_kit.lint.exclusion import compile_patterns

    patterns = [p.strip() for value in values for p in value.split(",") if p.strip()]
    if not patterns:
        return patterns  # pathspec (~10 ms) is imported only when there are patterns
    try:
        compile_patterns(patterns)
    except ValueError as error:
        raise UsageError(f"{option}: {error}") from None
    return patterns


def discovery(options: dict[str, Any], finder: Any = None) -> Any:
    """The :class:`~inertia_kit.lint.discovery.Discovery` the options ask for."""
    from inertia_kit.lint.discovery import Discovery

    exclude = options.get("exclude") or ()
    return Discovery(
        exclude=_patterns("--exclude", exclude) if exclude else None,
        extend_exclude=_patterns("--extend-exclude", options.get("extend_exclude") or ()),
        respect_gitignore=options.get("respect_gitignore"),
        force_exclude=options.get("force_exclude"),
        config=finder,
    )


def show_files(paths: Sequence[str], found: Any) -> int:
    """``--show-files``: the files ``found`` (a ``Discovery``) for ``paths``, one a line."""
    from inertia_kit.cli.printing import say
    from inertia_kit.lint.discovery import expand_paths

    for file in expand_paths(paths, found):
        say(str(file), err=False)  # a file name may hold a newline: one line each, escaped
    return 0
