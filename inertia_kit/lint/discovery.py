"""
Which files a run lints: the files given, and the robot files of the folders given (``*.urdf``,
``*.xacro``, and ``*.xml`` whose root element is ``<mujoco>``: an MJCF model, not a
``package.xml`` or a launch file), each once; what the walk leaves out (``exclude``,
``.gitignore``, colcon's folders) is :mod:`.exclusion`.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from inertia_kit.lint.exclusion import IGNORE_MARKERS, Exclusion, exclusion
from inertia_kit.lint.stand_in import is_stand_in
from inertia_kit.reading import open_regular

#: a robot file's name, case ignored: the folder walk and the pre-commit hooks' `files:` pattern
#: (.pre-commit-hooks.yaml, checked equal by a test) pick the same files (`GEN.URDF` too); of
#: the ``.xml`` files, only MJCF models (:func:`is_robot_file`)
ROBOT_FILE = r"(?i)\.(urdf|xacro|xml)$"
_ROBOT_FILE = re.compile(ROBOT_FILE)
_XML = re.compile(r"(?i)\.xml$")
#: enough of a file's start to find its root element past a long licence comment
_HEAD = 65536


def is_robot_file(path: str | Path) -> bool:
    """
    Whether the walk lints a file by its name and, for ``.xml``, its root element: an MJCF
    model (``<mujoco>``) is a robot file, other XML (``package.xml``, launch files, URDF saved
    as ``.xml``) is not. A file that cannot be read is not one.
    """
    name = os.path.basename(path)
    if not _ROBOT_FILE.search(name):
        return False
    if not _XML.search(name):
        return True
    from inertia_kit.description.loader import format_of

    try:
        with open_regular(path) as file:  # a pipe, or a link to one, is no robot to find
            return format_of(file.read(_HEAD)) == "mjcf"
    except OSError:
        return False


@dataclass
class Discovery:
    """
    The command line's discovery options (``--exclude``, ``--extend-exclude``,
    ``--[no-]respect-gitignore``, ``--[no-]force-exclude``; ``None``: as configured) over the
    configuration that applies to each path given (``config``: a ``ConfigFinder``; default:
    the nearest configuration file).
    """

    exclude: Sequence[str] | None = None
    extend_exclude: Sequence[str] = ()
    respect_gitignore: bool | None = None
    force_exclude: bool | None = None
    config: Any = None
    _by_config: dict[str | None, Exclusion] = field(default_factory=dict)

    def for_path(self, path: Path) -> Exclusion:
        """The exclusion for a path given: its configuration's, with the options over it."""
        if self.config is None:
            from inertia_kit.lint.config_files import ConfigFinder

            self.config = ConfigFinder()
        configured = self.config.for_folder(path) if _is_dir(path) else self.config.for_file(path)
        if configured.path not in self._by_config:
            self._by_config[configured.path] = exclusion(
                configured,
                exclude=self.exclude,
                extend_exclude=self.extend_exclude,
                respect_gitignore=self.respect_gitignore,
                force_exclude=self.force_exclude,
            )
        return self._by_config[configured.path]


def _is_dir(path: Path) -> bool:
    # os.path's answer: False for what cannot be looked at (a file in a folder we may not
    # search), where Path.is_dir raises; reading the file then says why
    return os.path.isdir(path)


def expand_paths(paths: Iterable[str | Path], discovery: Discovery | None = None) -> Iterator[Path]:
    """
    Files as given (with ``force-exclude``, unless excluded or an ``.xml`` file that is no MJCF
    model); folders searched for ``*.urdf``, ``*.xacro`` (``*.urdf.xacro`` too; case ignored,
    :data:`ROBOT_FILE`) and MJCF ``*.xml`` (:func:`is_robot_file`), in sorted order, leaving out
    what :mod:`.exclusion` excludes. Each file once.
    """
    discovery = Discovery() if discovery is None else discovery
    seen: set[str] = set()
    for entry in paths:
        path = Path(entry)
        rules = discovery.for_path(path)
        if rules.excludes_given(path) or (
            rules.force_exclude and _XML.search(path.name) and not is_robot_file(path)
        ):
            # a hook hands over every *.xml of a commit: only MJCF models are robot files
            continue
        found = _robot_files(path, rules) if _is_dir(path) else [path]
        for file in found:
            key = os.path.normcase(os.path.abspath(file))
            if key not in seen:
                seen.add(key)
                yield file


def _walk(top: str) -> Iterator[tuple[str, list[str], list[str]]]:
    """
    ``os.walk(top)`` (top-down, links to folders listed but not entered, unreadable folders
    passed over) without recursion: Python 3.11's recurses, and a tree 1000 folders deep was a
    RecursionError. The caller may prune ``folders`` in place, as with os.walk.
    """
    stack = [top]
    while stack:
        here = stack.pop()
        folders: list[str] = []
        names: list[str] = []
        try:
            with os.scandir(here) as entries:
                for entry in entries:
                    try:
                        is_folder = entry.is_dir()
                    except OSError:
                        is_folder = False
                    (folders if is_folder else names).append(entry.name)
        except OSError:
            continue
        yield here, folders, names
        stack.extend(
            path
            for path in (os.path.join(here, name) for name in reversed(folders))
            if not os.path.islink(path)
        )


def _robot_files(folder: Path, rules: Exclusion) -> list[Path]:
    files = []
    for top, folders, names in _walk(os.fspath(folder)):
        if top != os.fspath(folder) and not IGNORE_MARKERS.isdisjoint(names):
            folders[:] = []  # colcon skips this folder (a folder given is walked all the same)
            continue
        folders[:] = sorted(
            f for f in folders if not rules.excluded(Path(top, f), folder=True, markers=False)
        )
        files.extend(
            Path(top, name)
            for name in names
            if _ROBOT_FILE.search(name)
            and not is_stand_in(name)  # another run's robot read from stdin
            and not rules.excluded(Path(top, name), folder=False)
            and is_robot_file(Path(top, name))
        )
    return sorted(f for f in files if os.path.isfile(f))
