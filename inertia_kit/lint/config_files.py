"""
Configuration files: which one applies to a linted file, and reading it.

A linted file gets the configuration nearest to it: its folder, then each parent folder, where a
``.inertia-kit.toml`` wins over a ``pyproject.toml`` in the same folder and a ``pyproject.toml``
without ``[tool.inertia-kit]`` is passed over (ruff's discovery). ``--config PATH`` names one
file for every linted file instead. The keys and their validation: :mod:`inertia_kit.lint.config`.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Any

from inertia_kit.errors import ConfigError, InputError
from inertia_kit.lint.config import Config, parse_config

CONFIG_NAME = ".inertia-kit.toml"
PYPROJECT = "pyproject.toml"
#: A configuration file larger than this is refused unread (the largest real pyproject.toml
#: files are tens of kB).
MAX_CONFIG_BYTES = 1 << 20


def load_config(path: str | Path) -> Config:
    """
    Read one configuration file: ``pyproject.toml`` (its ``[tool.inertia-kit]`` table, which
    must exist) or any other name (``.inertia-kit.toml``: the keys at the top level).
    """
    path = Path(path)
    document = _read_toml(path)
    if path.name == PYPROJECT:
        table = document.get("tool", {}).get("inertia-kit")
        if table is None:
            raise ConfigError(f"{path}: no [tool.inertia-kit] table")
        return parse_config(table, path, prefix="tool.inertia-kit.")
    return parse_config(document, path)


def _read_toml(path: Path) -> dict[str, Any]:
    # imported here: most runs find no configuration, or a pyproject.toml without ours
    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover - exercised on Python 3.10 only
        import tomli as tomllib

    from inertia_kit.reading import read_regular

    if not path.exists():
        raise ConfigError(f"{path}: no such configuration file")
    try:
        text = read_regular(path, MAX_CONFIG_BYTES, what="configuration file").decode("utf-8")
    except InputError as error:
        raise ConfigError(str(error)) from None
    except UnicodeDecodeError as error:
        raise ConfigError(f"{path}: not UTF-8 text: {error.reason}") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ConfigError(f"{path}: invalid TOML: {error}") from None


def find_config(folder: str | Path, upward: bool = True) -> Path | None:
    """The configuration file that applies in ``folder``: the nearest, looking upward (or, not
    ``upward``, in ``folder`` itself)."""
    folder = Path(os.path.abspath(folder))
    for candidate in (folder, *folder.parents) if upward else (folder,):
        # os.path.isfile: False for a folder we may not search (Path.is_file raises there)
        own = candidate / CONFIG_NAME
        if _is_config_file(own):
            return own
        pyproject = candidate / PYPROJECT
        if _is_config_file(pyproject) and _has_section(pyproject):
            return pyproject
    return None


def _is_config_file(path: Path) -> bool:
    """Whether ``path`` is a file to read; ``ConfigError`` for one that exists but is not a
    regular file (a named pipe would block the read, ``/dev/zero`` never ends)."""
    # os.path's: False, not PermissionError, in a folder that may not be searched
    if os.path.isfile(path):
        return True
    if os.path.exists(path):
        from inertia_kit.reading import check_regular

        try:
            check_regular(path, MAX_CONFIG_BYTES, what="configuration file")
        except InputError as error:
            raise ConfigError(str(error)) from None
    return False


def _has_section(pyproject: Path) -> bool:
    from inertia_kit.reading import read_regular

    try:
        data = read_regular(pyproject, MAX_CONFIG_BYTES, what="configuration file")
    except InputError as error:
        raise ConfigError(str(error)) from None
    if b"inertia-kit" not in data:  # most pyproject.toml files: no need to parse them
        return False
    return "inertia-kit" in _read_toml(pyproject).get("tool", {})


_DEFAULT = Config()


class ConfigFinder:
    """
    The configuration of each linted file: ``--config`` for all, else the nearest file,
    discovered once per folder and read once per file.
    """

    def __init__(self, explicit: str | Path | None = None):
        self.explicit = None if explicit is None else load_config(explicit)
        self._by_folder: dict[str, Path | None] = {}
        self._by_file: dict[Path, Config] = {}

    def _nearest(self, folder: str) -> Path | None:
        """:func:`find_config` of ``folder``, each folder on the way up looked at once: an asset
        library's thousand folders share their parents' answer."""
        if folder not in self._by_folder:
            own = find_config(folder, upward=False)
            parent = os.path.dirname(folder)
            if own is None and parent != folder:
                own = self._nearest(parent)
            self._by_folder[folder] = own
        return self._by_folder[folder]

    def for_file(self, path: str | Path) -> Config:
        return self.for_folder(os.path.dirname(os.path.abspath(path)))

    def for_folder(self, folder: str | Path) -> Config:
        """The configuration of the files in ``folder`` (and of its walk)."""
        if self.explicit is not None:
            return self.explicit
        found = self._nearest(os.path.abspath(folder))
        if found is None:
            return _DEFAULT  # one for every file without a configuration
        if found not in self._by_file:
            self._by_file[found] = load_config(found)
        return self._by_file[found]
