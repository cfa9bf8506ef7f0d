"""
Which paths the folder walk leaves out, as ruff does: ``exclude`` (replaces the defaults) and
``extend-exclude`` (adds), from the configuration and the command line, ``.gitignore`` files
(``respect-gitignore``), and folders colcon itself skips.

Patterns are gitignore-style (pathspec's ``gitignore`` flavour): one without ``/`` matches a
file or folder name at any depth (``build``, ``*.gen.urdf``), one with ``/`` is anchored to
its base (``robots/legacy``), a trailing ``/`` matches folders only. A configuration's patterns
are relative to its folder, the command line's to the current folder.

The defaults (dropped when ``exclude`` is set): hidden folders (``.git``, ``.venv``),
``__pycache__``, and a colcon workspace's ``build/``, ``install/`` and ``log/`` - a folder of
that name next to a ``src`` folder (the workspace root) or holding what colcon writes there
(``COLCON_IGNORE``, ``.built_by``, ``.colcon_install_layout``). A robot package's own folder
named ``build`` is not workspace output and stays linted. Whatever ``exclude`` says, a folder
holding ``COLCON_IGNORE``, ``AMENT_IGNORE`` or ``CATKIN_IGNORE`` is skipped, as colcon does.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

#: a folder holding one of these is skipped by colcon (and catkin, ament): by the walk too
IGNORE_MARKERS = frozenset(("COLCON_IGNORE", "AMENT_IGNORE", "CATKIN_IGNORE"))
_WORKSPACE_OUTPUT = ("build", "install", "log")
#: An ignore file larger than this is refused unread (git's own bound is 100 MB; real ones hold
#: a few kB, and every pattern costs every path walked).
MAX_IGNORE_BYTES = 1 << 20
_COLCON_WRITES = ("COLCON_IGNORE", ".built_by", ".colcon_install_layout")
DEFAULT_EXCLUDE_TEXT = "hidden folders, __pycache__, a colcon workspace's build/ install/ log/"


def compile_patterns(patterns: Sequence[str]) -> Any:
    """A pathspec for gitignore-style ``patterns``; ``ValueError`` says which one is bad."""
    import pathspec

    for pattern in patterns:
        try:
            pathspec.GitIgnoreSpec.from_lines([pattern])
        except Exception as error:  # pathspec raises its own GitWildMatchPatternError
            raise ValueError(f"{pattern!r} is not a gitignore-style pattern: {error}") from None
    return pathspec.GitIgnoreSpec.from_lines(list(patterns))


@dataclass(frozen=True)
class Patterns:
    """Gitignore-style patterns relative to ``base`` (an absolute folder)."""

    base: str
    patterns: tuple[str, ...]

    def matches(self, path: str | Path, folder: bool) -> bool:
        if not self.patterns:
            return False
        absolute = os.path.abspath(path)
        relative = os.path.relpath(absolute, self.base)
        if relative.startswith(os.pardir) or os.path.isabs(relative):
            relative = os.path.basename(absolute)  # outside the base: names match, paths not
        relative = relative.replace(os.sep, "/") + ("/" if folder else "")
        return bool(_last_match(_spec(self.patterns), relative, False))


def _last_match(spec: Any, relative: str, verdict: bool | None) -> bool | None:
    """As git reads one ignore file: the last pattern that matches decides (``!``: kept)."""
    for pattern in spec.patterns:
        if pattern.include is not None and pattern.match_file(relative) is not None:
            verdict = pattern.include
    return verdict


_SPECS: dict[tuple[str, ...], Any] = {}


def _spec(patterns: tuple[str, ...]) -> Any:
    if patterns not in _SPECS:
        _SPECS[patterns] = compile_patterns(patterns)
    return _SPECS[patterns]


@dataclass(frozen=True)
class Exclusion:
    """What one walk leaves out; :func:`exclusion` builds it from configuration and options."""

    defaults: bool = True
    patterns: tuple[Patterns, ...] = ()
    respect_gitignore: bool = True
    force_exclude: bool = False
    gitignores: GitIgnores = field(default_factory=lambda: GitIgnores(), compare=False)

    def excluded(self, path: str | Path, folder: bool, markers: bool = True) -> bool:
        """
        Whether the walk leaves ``path`` (a ``folder`` or a file) out; ``markers``: a folder
        holding an :data:`IGNORE_MARKERS` file too (the walk sees those in the folder's names).
        """
        path = Path(path)
        if markers and folder and any(os.path.isfile(path / marker) for marker in IGNORE_MARKERS):
            return True
        if self.defaults and folder and _default_excluded(path):
            return True
        if any(patterns.matches(path, folder) for patterns in self.patterns):
            return True
        return self.respect_gitignore and self.gitignores.ignored(path, folder)

    def excludes_given(self, path: str | Path) -> bool:
        """
        With ``force-exclude``, whether a path given on the command line is left out: it, or
        a folder it is in below the current folder, is excluded (``.gitignore`` aside: a
        file a hook hands over is tracked).
        """
        if not self.force_exclude:
            return False
        absolute = Path(os.path.abspath(path))
        rules = Exclusion(self.defaults, self.patterns, respect_gitignore=False)
        if rules.excluded(absolute, os.path.isdir(absolute)):
            return True
        here = Path(os.getcwd())
        return any(
            rules.excluded(parent, True)
            for parent in absolute.parents
            if parent != here and here in parent.parents
        )


def _default_excluded(folder: Path) -> bool:
    name = folder.name
    if name.startswith(".") or name == "__pycache__":
        return True
    if name not in _WORKSPACE_OUTPUT:
        return False
    return os.path.isdir(folder.parent / "src") or any(
        os.path.exists(folder / mark) for mark in _COLCON_WRITES
    )


def exclusion(
    configured: Any,
    *,
    exclude: Sequence[str] | None = None,
    extend_exclude: Sequence[str] = (),
    respect_gitignore: bool | None = None,
    force_exclude: bool | None = None,
) -> Exclusion:
    """
    The exclusion of one walk: the ``configured`` one (a :class:`~.config.Config`) with the
    command line's over it (``exclude``: replaces the configured ``exclude`` and the defaults;
    ``extend_exclude``: added), patterns on the command line relative to the current folder.
    """
    here = os.getcwd()
    base = here if configured.path is None else str(Path(os.path.abspath(configured.path)).parent)
    parts = []
    if exclude is not None:
        parts.append(Patterns(here, tuple(exclude)))
    elif configured.exclude is not None:
        parts.append(Patterns(base, configured.exclude))
    parts.append(Patterns(base, configured.extend_exclude))
    parts.append(Patterns(here, tuple(extend_exclude)))
    return Exclusion(
        defaults=exclude is None and configured.exclude is None,
        patterns=tuple(p for p in parts if p.patterns),
        respect_gitignore=_first(respect_gitignore, configured.respect_gitignore, True),
        force_exclude=_first(force_exclude, configured.force_exclude, False),
    )


def _first(*values: bool | None) -> bool:
    return next(value for value in values if value is not None)


class GitIgnores:
    """
    The ``.gitignore`` files of the repositories walked (each folder's, from the git top
    level down; a deeper file's match, negations included, wins) and ``.git/info/exclude``;
    read once each, without git.
    """

    def __init__(self) -> None:
        self._roots: dict[Path, Path | None] = {}
        self._specs: dict[Path, Any] = {}
        self._layers_of: dict[Path, tuple[tuple[Path, Any], ...]] = {}

    def ignored(self, path: Path, folder: bool) -> bool:
        absolute = Path(os.path.abspath(path))
        root = self._root(absolute.parent)
        if root is None:
            return False
        verdict = None
        for base, spec in self._layers(root, absolute.parent):
            relative = absolute.relative_to(base).as_posix() + ("/" if folder else "")
            verdict = _last_match(spec, relative, verdict)
        return bool(verdict)

    def _root(self, folder: Path) -> Path | None:
        # upward without recursion, each folder met remembered: a walk of a folder thousands
        # deep asks once per folder (a recursion was a RecursionError at a depth of 1000)
        chain = []
        here = folder
        while here not in self._roots:
            if os.path.exists(here / ".git"):
                self._roots[here] = here
            elif here.parent == here:
                self._roots[here] = None
            else:
                chain.append(here)
                here = here.parent
        for each in chain:
            self._roots[each] = self._roots[here]
        return self._roots[here]

    def _layers(self, root: Path, folder: Path) -> tuple[tuple[Path, Any], ...]:
        """
        The ignore files that apply in ``folder`` (below ``root``), from the top: each folder's
        list is its parent's and its own ``.gitignore``, made once, so that a walk's cost is
        linear in its folders, not in their depth times their number.
        """
        chain = []
        here = folder
        while here not in self._layers_of and here != root:
            chain.append(here)
            here = here.parent
        if here not in self._layers_of:  # the root: .git/info/exclude, then its .gitignore
            found = ((root, self._read(root / ".git" / "info" / "exclude", in_tree=False)),)
            found += ((root, self._read(root / ".gitignore", in_tree=True)),)
            self._layers_of[root] = tuple(layer for layer in found if layer[1] is not None)
        layers = self._layers_of[here]
        for each in reversed(chain):
            spec = self._read(each / ".gitignore", in_tree=True)
            if spec is not None:
                layers = (*layers, (each, spec))
            self._layers_of[each] = layers
        return layers

    def _read(self, file: Path, in_tree: bool) -> Any:
        """
        The file's patterns; None for a file with none (missing, or blank lines and comments
        only, as git's template ``.git/info/exclude``), which needs no pathspec.

        As git (2.32 and later) reads them: a ``.gitignore`` in the tree that is a symbolic
        link is not read, and one that cannot be read is passed over. One that is not a
        regular file or is larger than :data:`MAX_IGNORE_BYTES` is a ``ConfigError``.
        """
        from inertia_kit.errors import ConfigError, InputError
        from inertia_kit.reading import Refused, read_regular

        if file not in self._specs:
            try:
                if not os.path.lexists(file) or (in_tree and os.path.islink(file)):
                    data = b""
                else:
                    data = read_regular(file, MAX_IGNORE_BYTES, what="ignore file")
            except Refused as error:
                raise ConfigError(str(error)) from None
            except InputError:
                data = b""
            lines = data.decode("utf-8", errors="replace").splitlines()
            if all(not line.strip() or line.startswith("#") for line in lines):
                self._specs[file] = None
                return None
            # imported here, not at the top: pathspec costs 5 to 20 ms (with typing_extensions
            # before 4.16 it imports asyncio and ssl), and most walks meet no ignore file
            import pathspec

            try:
                self._specs[file] = pathspec.GitIgnoreSpec.from_lines(lines)
            except Exception:  # a line git would not read either: the file's other lines
                self._specs[file] = pathspec.GitIgnoreSpec.from_lines(_valid(lines))
        return self._specs[file]


def _valid(lines: list[str]) -> list[str]:
    kept = []
    for line in lines:
        try:
            compile_patterns([line])
        except ValueError:
            continue
        kept.append(line)
    return kept
