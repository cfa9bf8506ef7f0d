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

from inertia_kit.errors import ConfigError
from inertia_kit.lint.config import Config, parse_config

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python 3.10 only
    import tomli as tomllib

CONFIG_NAME = ".inertia-kit.toml"
PYPROJECT = "pyproject.toml"


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
    try:
        text = path.read_bytes().decode("utf-8")
    except FileNotFoundError:
        raise ConfigError(f"{path}: no such configuration file") from None
    except IsADirectoryError:
        raise ConfigError(f"{path}: is a directory, not a configuration file") from None
    except OSError as error:
        raise ConfigError(f"{path}: cannot read: {error.strerror or error}") from None
    except UnicodeDecodeError as error:
        raise ConfigError(f"{path}: not UTF-8 text: {error.reason}") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ConfigError(f"{path}: invalid TOML: {error}") from None


def find_config(folder: str | Path) -> Path | None:
    """The configuration file that applies in ``folder``: the nearest, looking upward."""
    folder = Path(os.path.abspath(folder))
    for candidate in (folder, *folder.parents):
        # os.path.isfile: False for a folder we may not search (Path.is_file raises there)
        own = candidate / CONFIG_NAME
        if os.path.isfile(own):
            return own
        pyproject = candidate / PYPROJECT
        if os.path.isfile(pyproject) and _has_section(pyproject):
            return pyproject
    return None


def _has_section(pyproject: Path) -> bool:
    try:
        data = pyproject.read_bytes()
    except OSError:
        return False
    if b"inertia-kit" not in data:  # most pyproject.toml files: no need to parse them
        return False
    return "inertia-kit" in _read_toml(pyproject).get("tool", {})


class ConfigFinder:
    """
    The configuration of each linted file: ``--config`` for all, else the nearest file,
    discovered once per folder and read once per file.
    """

    def __init__(self, explicit: str | Path | None = None):
        self.explicit = None if explicit is None else load_config(explicit)
        self._by_folder: dict[str, Path | None] = {}
        self._by_file: dict[Path, Config] = {}

    def for_file(self, path: str | Path) -> Config:
        return self.for_folder(os.path.dirname(os.path.abspath(path)))

    def for_folder(self, folder: str | Path) -> Config:
        """The configuration of the files in ``folder`` (and of its walk)."""
        if self.explicit is not None:
            return self.explicit
        folder = os.path.abspath(folder)
        if folder not in self._by_folder:
            self._by_folder[folder] = find_config(folder)
        found = self._by_folder[folder]
        if found is None:
            return Config()
        if found not in self._by_file:
            self._by_file[found] = load_config(found)
        return self._by_file[found]
